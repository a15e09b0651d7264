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
source "$(dirname "${BASH_SOURCE[0]}")/own_master.sh" 7
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
  set:="['time.end=0.01']" >"$DIR/fresh.log" 2>&1 || status=$?
[ "$status" = 0 ] || fail "the launch that sets the description exited $status" "$DIR/fresh.log"
grep -q "set by a launch that still runs" "$DIR/fresh.log" ||
  fail "no INFO line for a description this launch set" "$DIR/fresh.log"
if grep -q "may be left from before" "$DIR/fresh.log"; then
  fail "a warning for a description this launch set" "$DIR/fresh.log"
fi
status=0
timeout 120 "$launcher" mpm_sdem sim.launch scene:="$bed" set:="['time.end=0.01']" \
  robot_links:="[tool]" headless:=true end_action:=shutdown threads:=1 >"$DIR/stale.log" 2>&1 ||
  status=$?
[ "$status" = 0 ] || fail "the launch reading a left description exited $status" "$DIR/stale.log"
grep "WARN" "$DIR/stale.log" | grep -q "may be left from before.*rosparam delete /robot_description" ||
  fail "no warning for the description an ended launch left" "$DIR/stale.log"
echo "a description set by this launch: $(grep -o "the robot description is.*" "$DIR/fresh.log")"
echo "one left by the launch before: $(grep -o "the robot description parameter.*" "$DIR/stale.log")"

# 3: Ctrl-C.
"$launcher" mpm_sdem sim.launch scene:="$bed" headless:=true threads:=1 real_time_factor:=1 \
  record:=true bag:="$DIR/sigint.bag" >"$DIR/sigint.log" 2>&1 &
launch=$!
for _ in $(seq 600); do grep -q "scene robot_bed:" "$DIR/sigint.log" && break; sleep 0.1; done
sleep 1
kill -INT $launch
status=0
wait $launch || status=$?
[ "$status" = 0 ] || fail "SIGINT to mpm_sdem_launch: exit status $status, not 0" "$DIR/sigint.log"
closed "$DIR/sigint.bag" || fail "SIGINT: the bag was not closed" "$DIR/sigint.log"
echo "SIGINT to mpm_sdem_launch: exit status $status, $(grep -o "bag closed.*" "$DIR/sigint.log")"

# 4: a block out of the domain, end_action shutdown.
status=0
timeout 60 "$launcher" mpm_sdem sim.launch scene:="$bed" set:="['blocks.1.velocity=[0,10]']" \
  headless:=true end_action:=shutdown threads:=1 record:=true bag:="$DIR/outside.bag" \
  >"$DIR/outside.log" 2>&1 || status=$?
[ "$status" = 3 ] || fail "a block out of the domain: exit status $status, not 3" "$DIR/outside.log"
grep -q "block 'box'.*left the domain.*shutting down with status 3" "$DIR/outside.log" ||
  fail "a block out of the domain: the reason is not logged" "$DIR/outside.log"
closed "$DIR/outside.bag" || fail "a block out of the domain: the bag was not closed" "$DIR/outside.log"
echo "a block out of the domain: exit status $status, $(grep -o "block 'box'.*left the domain[^;]*" "$DIR/outside.log" | head -1)"
exit $failed
