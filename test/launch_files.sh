#!/usr/bin/env bash
# Every shipped launch file (but sim.launch, which needs a scene; 13 of them) loads in roslaunch,
# starts the node, and names a scene file that exists and that the runner runs for 10 ms with the
# launch file's own `set` overrides (debris_impact_granular_fine, excavator_blade_fast; a bad
# scene or override stops it before simulating: checked with `time.cfl=8`), writing ParaView
# frames at 0, 5 and 10 ms (--vtk-every) listed in vtk/points.pvd.
# Arguments: the package's source directory, the runner.
set -euo pipefail
src="$1"
runner="$2"
export ROS_PACKAGE_PATH="$src${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
# One launch file: "ok" or "FAIL" lines; its exit status.
check() {
  local f="$1" status=0
  nodes=$(roslaunch --nodes "$f" 2>&1) || { echo "FAIL $f: $nodes"; return 1; }
  grep -qx /mpm_sdem <<<"$nodes" || { echo "FAIL $f: no /mpm_sdem node ($nodes)"; status=1; }
  params=$(roslaunch --dump-params "$f")
  scene=$(sed -n 's|^/mpm_sdem/scene: ||p' <<<"$params")
  # The `set` list as the node gets it (one "- key=value" line each under /mpm_sdem/set:).
  sets=()
  while IFS= read -r kv; do sets+=(--set "$kv"); done < <(sed -n '/^\/mpm_sdem\/set:/,/^\//s/^- //p' <<<"$params")
  out=$(mktemp -d)
  if [ ! -f "$scene" ]; then
    echo "FAIL $f: scene '$scene' is not a file"
    status=1
  elif ! "$runner" "$scene" "${sets[@]}" --set time.end=0.01 --set output.interval=0.01 --vtk-every 0.005 --threads 1 --quiet --out "$out" >/dev/null 2>&1; then
    echo "FAIL $f: the runner refuses $scene"
    status=1
  elif ! grep -q 'file="points_000002.vtu"' "$out/vtk/points.pvd" 2>/dev/null; then
    echo "FAIL $f: --vtk-every 0.005 left no third frame in $out/vtk/points.pvd"
    status=1
  else
    echo "ok   $(basename "$f"): $(basename "$scene")${sets:+ ${sets[*]}}"
    rm -rf "$out"
  fi
  return $status
}
export -f check
export runner
# Two at a time (roslaunch's start-up is most of each; the runner on one thread each).
status=0
for f in "$src"/launch/*.launch; do
  [ "$(basename "$f")" = sim.launch ] || printf '%s\0' "$f"
done | xargs -0 -P 2 -I{} bash -c 'check "$1"' _ {} || status=1
exit $status
