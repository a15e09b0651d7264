#!/usr/bin/env bash
# Every shipped launch file (but sim.launch, which needs a scene) loads in roslaunch, starts the
# node, and names a scene file that exists and that the runner runs for 10 ms (a bad scene stops
# it before simulating). Arguments: the package's source directory, the runner.
set -euo pipefail
src="$1"
runner="$2"
export ROS_PACKAGE_PATH="$src${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
status=0
for f in "$src"/launch/*.launch; do
  [ "$(basename "$f")" = sim.launch ] && continue
  nodes=$(roslaunch --nodes "$f" 2>&1) || { echo "FAIL $f: $nodes"; status=1; continue; }
  grep -qx /mpm_sdem <<<"$nodes" || { echo "FAIL $f: no /mpm_sdem node ($nodes)"; status=1; }
  scene=$(roslaunch --dump-params "$f" | sed -n 's|^/mpm_sdem/scene: ||p')
  if [ ! -f "$scene" ]; then
    echo "FAIL $f: scene '$scene' is not a file"
    status=1
  elif ! "$runner" "$scene" --set time.end=0.01 --set output.interval=0.01 --quiet --out "$(mktemp -d)" >/dev/null 2>&1; then
    echo "FAIL $f: the runner refuses $scene"
    status=1
  else
    echo "ok   $(basename "$f"): $(basename "$scene")"
  fi
done
exit $status
