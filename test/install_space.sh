#!/usr/bin/env bash
# The install space works on its own: installs the build into a temporary prefix, sets up the
# environment a catkin install space's setup.bash would (nothing from the build or source tree),
# then runs the installed programs' --help, the default scene and the excavator demo through
# roslaunch until their ends, and a launch whose node fails, which must give a non-zero exit
# status.
# usage: install_space.sh BUILD_DIR
set -euo pipefail
BUILD="$(cd "$1" && pwd)"
PREFIX="$(mktemp -d /tmp/mpm_sdem_install.XXXXXX)"
cleanup() { rm -rf "$PREFIX"; }
trap cleanup EXIT

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cmake --install "$BUILD" --prefix "$PREFIX" >"$PREFIX.log" 2>&1 ||
  { cat "$PREFIX.log"; fail "cmake --install"; }
rm -f "$PREFIX.log"

# What <prefix>/setup.bash sets (catkin's env hooks), and only that: a program that needs a
# library from the build tree fails here.
export PATH="$PREFIX/bin:/usr/bin:/bin"
export LD_LIBRARY_PATH="$PREFIX/lib"
export CMAKE_PREFIX_PATH="$PREFIX"
export ROS_PACKAGE_PATH="$PREFIX/share"
export PYTHONPATH="$PREFIX/lib/python3/dist-packages"
export PKG_CONFIG_PATH="$PREFIX/lib/pkgconfig"
export ROS_HOME="$PREFIX/ros_home"
export ROS_HOSTNAME=127.0.0.1
# A master of its own (roslaunch starts one): a port no other test uses.
export ROS_MASTER_URI="http://127.0.0.1:$((20000 + $$ % 20000))"
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1

found="$(python3 -c 'import rospkg; print(rospkg.RosPack().get_path("mpm_sdem"))')"
[ "$found" = "$PREFIX/share/mpm_sdem" ] || fail "rospkg finds mpm_sdem at $found"

for program in mpm_sdem_run mpm_sdem_compare mpm_sdem_sweep mpm_sdem_node; do
  exe="$PREFIX/lib/mpm_sdem/$program"
  [ -x "$exe" ] || fail "$program is not installed"
  missing="$(ldd "$exe" | grep 'not found' || true)"
  [ -z "$missing" ] || fail "$program: $missing"
done
"$PREFIX/lib/mpm_sdem/mpm_sdem_run" --help >/dev/null || fail "mpm_sdem_run --help"
"$PREFIX/lib/mpm_sdem/mpm_sdem_compare" --help >/dev/null || fail "mpm_sdem_compare --help"
"$PREFIX/lib/mpm_sdem/mpm_sdem_sweep" --help >/dev/null || fail "mpm_sdem_sweep --help"
command -v mpm_sdem_launch >/dev/null || fail "mpm_sdem_launch is not on the install's PATH"

# The default scene, as scripts/run launches it, for 20 ms of simulated time.
BAG="$PREFIX/run.bag"
timeout 240 mpm_sdem_launch mpm_sdem debris_impact.launch headless:=true end_action:=shutdown threads:=1 \
  set:="['time.end=0.02']" record:=true bag:="$BAG" >"$PREFIX/launch.log" 2>&1 ||
  { cat "$PREFIX/launch.log"; fail "the default scene from the install space failed"; }
grep -q "reached the scene's end time" "$PREFIX/launch.log" ||
  { cat "$PREFIX/launch.log"; fail "the node did not reach the scene's end"; }
[ -s "$BAG" ] || fail "no bag at $BAG"

# The excavator demo (launch/excavator_dig.launch) as installed: the URDF and the bucket's mesh
# from share/, robot_state_publisher, the joint path of the installed excavator_dig.py. Both
# links become blocks once tf has them (at t = 0.08 s here), the script starts the dig when
# ~blocks lists them, and the run reaches its end. A quarter of real time, so that the Python
# node has started (about 1 s here) well before the links are due.
timeout 240 mpm_sdem_launch mpm_sdem excavator_dig.launch headless:=true end_action:=shutdown \
  threads:=1 real_time_factor:=0.25 set:="['time.end=1.0']" >"$PREFIX/dig.log" 2>&1 ||
  { cat "$PREFIX/dig.log"; fail "the excavator demo from the install space failed"; }
for link in stick bucket; do
  grep -q "link '$link' is block" "$PREFIX/dig.log" ||
    { cat "$PREFIX/dig.log"; fail "the excavator's link '$link' made no block"; }
done
# The installed script imports the package's messages (~blocks) to start the dig.
grep -q "the dig starts" "$PREFIX/dig.log" ||
  { cat "$PREFIX/dig.log"; fail "excavator_dig.py did not see the links in ~blocks"; }
grep -q "reached the scene's end time" "$PREFIX/dig.log" ||
  { cat "$PREFIX/dig.log"; fail "the excavator demo did not reach its end"; }

# A node that stops at once (no such scene) must fail the launch. (Before: with
# libmpm_sdem_mesh.so missing from the install the node exited 127 and roslaunch 0.)
status=0
timeout 120 mpm_sdem_launch mpm_sdem sim.launch headless:=true scene:="$PREFIX/no_such_scene.yaml" \
  >"$PREFIX/bad.log" 2>&1 || status=$?
[ "$status" -ne 0 ] || { cat "$PREFIX/bad.log"; fail "a node that failed gave exit status 0"; }
grep -q "no_such_scene.yaml" "$PREFIX/bad.log" || { cat "$PREFIX/bad.log"; fail "no reason given"; }
echo "install space: programs load, the default scene and the excavator demo run, a failing node" \
  "exits $status"
