#!/usr/bin/env bash
# Two launches on one master, as a user would run them: the blade scene following a tf frame,
# then the default scene, whose empty ~follow_tf must not inherit the blade's (it named a block
# the default scene lacks, and the node refused to start). Run by ctest through the devel space's
# env.sh; each launch must end with status 0 at its scene's end.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/own_master.sh" 0
launch() {
  timeout 120 "$ROOT/scripts/mpm_sdem_launch" mpm_sdem "$@" headless:=true end_action:=shutdown \
    threads:=1 >"$ROS_HOME/launch.log" 2>&1 || { cat "$ROS_HOME/launch.log"; return 1; }
}
launch sim.launch scene:="$ROOT/config/scenes/excavator_blade.yaml" \
  follow_tf:="{blade: excavator/blade_link}" set:="['time.end=0.01']"
launch debris_impact.launch set:="['time.end=0.02']"
grep -q "reached the scene's end time" "$ROS_HOME/launch.log"
echo "two launches on one master: both ran to their end"
