#!/usr/bin/env bash
# rosdep check on package.xml, offline: every <depend> key must resolve, through rosdep's own
# resolver, to Debian packages that are installed. The ROS keys come from Debian's rosdep data
# (python3-rosdep2's debian.yaml), the system keys from rosdistro's as excerpted in
# test/data/rosdep/system_keys.yaml (rosdep update would fetch rosdistro from GitHub).
# usage: rosdep_check.sh SOURCE_DIR
set -euo pipefail
SRC="$(cd "$1" && pwd)"
WORK="$(mktemp -d /tmp/mpm_sdem_rosdep.XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
DEBIAN_DATA=/usr/share/python3-rosdep2/debian.yaml
[ -f "$DEBIAN_DATA" ] || { echo "FAIL: $DEBIAN_DATA missing (python3-rosdep2)"; exit 1; }
mkdir -p "$WORK/sources.list.d"
cat >"$WORK/sources.list.d/10-offline.list" <<LIST
yaml file://$DEBIAN_DATA debian
yaml file://$SRC/test/data/rosdep/system_keys.yaml
LIST
# No distributions to fetch: the ROS keys are Debian's, not a ROS distribution's.
cat >"$WORK/index.yaml" <<INDEX
%YAML 1.1
---
type: index
version: 4
distributions: {}
INDEX
export ROSDEP_SOURCE_PATH="$WORK/sources.list.d"
export ROSDISTRO_INDEX_URL="file://$WORK/index.yaml"
export ROS_HOME="$WORK/ros_home"
# Only this package is "source": the installed ROS packages resolve through rosdep's data.
export ROS_PACKAGE_PATH="$SRC"
unset ROS_DISTRO
rosdep update >"$WORK/update.log" 2>&1 || { cat "$WORK/update.log"; exit 1; }
rosdep check --from-paths "$SRC" --ignore-src --os=debian:bookworm --rosdistro=debian
