#!/usr/bin/env bash
# How a run ends, as a script sees it (docs/node.md), on one master and robot_bed.yaml:
# 1. a robot description set by the launch that reads it: an INFO line, no warning;
# 2. the same description read by the next launch, the one that set it having ended: a WARN that
#    it may be left from before, with how to clear it;
# 3. SIGINT to mpm_sdem_launch (Ctrl-C) while the node runs: the node closes its bag, and the
#    launcher exits 0 (it exited 1, "required node(s) mpm_sdem never ran");
# 4. a block thrown out of the domain in a headless run with end_action shutdown: the node ends
#    with status 3 and the reason, its bag closed (it waited for ever for a ~resume).
# Run by ctest through the devel space's env.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export ROS_HOSTNAME=127.0.0.1
export ROS_MASTER_URI="http://127.0.0.1:$((20000 + ($$ + 7) % 20000))"
export ROS_HOME="${ROS_HOME:-$(mktemp -d)}"
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
dir=$(mktemp -d)
roscore -p "${ROS_MASTER_URI##*:}" >"$dir/roscore.log" 2>&1 &
core=$!
trap 'kill $core 2>/dev/null; wait $core 2>/dev/null || true; rm -rf "$dir"' EXIT
for _ in $(seq 100); do rosparam list >/dev/null 2>&1 && break; sleep 0.1; done
bed="$ROOT/test/data/robot_bed.yaml"
launcher="$ROOT/scripts/mpm_sdem_launch"
# Each case runs whatever the one before found; the script fails if any did.
failed=0
fail() {
  echo "FAIL: $1; its log:"
  sed 's/^/    /' "$2"
  failed=1
}
# A finished bag: renamed from .active and readable.
closed() { [ -f "$1" ] && [ ! -e "$1.active" ] && rosbag info "$1" >/dev/null; }

# 1 and 2: the stale robot description.
status=0
timeout 120 "$launcher" "$ROOT/test/ros/robot_description.launch" scene:="$bed" \
  set:="['time.end=0.01']" >"$dir/fresh.log" 2>&1 || status=$?
[ "$status" = 0 ] || fail "the launch that sets the description exited $status" "$dir/fresh.log"
grep -q "set by a launch that still runs" "$dir/fresh.log" ||
  fail "no INFO line for a description this launch set" "$dir/fresh.log"
if grep -q "may be left from before" "$dir/fresh.log"; then
  fail "a warning for a description this launch set" "$dir/fresh.log"
fi
status=0
timeout 120 "$launcher" mpm_sdem sim.launch scene:="$bed" set:="['time.end=0.01']" \
  robot_links:="[tool]" headless:=true end_action:=shutdown threads:=1 >"$dir/stale.log" 2>&1 ||
  status=$?
[ "$status" = 0 ] || fail "the launch reading a left description exited $status" "$dir/stale.log"
grep "WARN" "$dir/stale.log" | grep -q "may be left from before.*rosparam delete /robot_description" ||
  fail "no warning for the description an ended launch left" "$dir/stale.log"
echo "a description set by this launch: $(grep -o "the robot description is.*" "$dir/fresh.log")"
echo "one left by the launch before: $(grep -o "the robot description parameter.*" "$dir/stale.log")"

# 3: Ctrl-C.
"$launcher" mpm_sdem sim.launch scene:="$bed" headless:=true threads:=1 real_time_factor:=1 \
  record:=true bag:="$dir/sigint.bag" >"$dir/sigint.log" 2>&1 &
launch=$!
for _ in $(seq 600); do grep -q "scene robot_bed:" "$dir/sigint.log" && break; sleep 0.1; done
sleep 1
kill -INT $launch
status=0
wait $launch || status=$?
[ "$status" = 0 ] || fail "SIGINT to mpm_sdem_launch: exit status $status, not 0" "$dir/sigint.log"
closed "$dir/sigint.bag" || fail "SIGINT: the bag was not closed" "$dir/sigint.log"
echo "SIGINT to mpm_sdem_launch: exit status $status, $(grep -o "bag closed.*" "$dir/sigint.log")"

# 4: a block out of the domain, end_action shutdown.
status=0
timeout 60 "$launcher" mpm_sdem sim.launch scene:="$bed" set:="['blocks.1.velocity=[0,10]']" \
  headless:=true end_action:=shutdown threads:=1 record:=true bag:="$dir/outside.bag" \
  >"$dir/outside.log" 2>&1 || status=$?
[ "$status" = 3 ] || fail "a block out of the domain: exit status $status, not 3" "$dir/outside.log"
grep -q "block 'box'.*left the domain.*shutting down with status 3" "$dir/outside.log" ||
  fail "a block out of the domain: the reason is not logged" "$dir/outside.log"
closed "$dir/outside.bag" || fail "a block out of the domain: the bag was not closed" "$dir/outside.log"
echo "a block out of the domain: exit status $status, $(grep -o "block 'box'.*left the domain[^;]*" "$dir/outside.log" | head -1)"
exit $failed
