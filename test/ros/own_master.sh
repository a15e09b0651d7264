# Sourced by the shell rostests: a ROS master of their own on a port of this process's (OFFSET
# apart from another test's), ROS on the loopback, logs line-buffered; stopped, and DIR removed,
# when the test exits. Sets ROOT (the package), DIR (a scratch folder) and waits for the master.
# usage: source own_master.sh OFFSET
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export ROS_HOSTNAME=127.0.0.1
export ROS_MASTER_URI="http://127.0.0.1:$((20000 + ($$ + ${1:-0}) % 20000))"
export ROS_HOME="${ROS_HOME:-$(mktemp -d)}"
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
DIR=$(mktemp -d)
roscore -p "${ROS_MASTER_URI##*:}" >"$DIR/roscore.log" 2>&1 &
own_master_pid=$!
trap 'kill $own_master_pid 2>/dev/null; wait $own_master_pid 2>/dev/null || true; rm -rf "$DIR"' EXIT
for _ in $(seq 100); do rosparam list >/dev/null 2>&1 && break; sleep 0.1; done
