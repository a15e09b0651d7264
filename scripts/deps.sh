# Sourced by scripts/run and scripts/test: installs missing Debian packages (idempotent; no apt
# call when everything is there) and configures and builds the package out of tree.
# Environment: BUILD_DIR (default: <repo>/build), JOBS (default: 2).

MPM_SDEM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$MPM_SDEM_ROOT/build}"
JOBS="${JOBS:-2}"

# Debian's ROS 1 needs the system python3, not a pyenv shim (shared/ros-on-debian.md, fix 1).
export PATH="/usr/bin:$PATH"

MPM_SDEM_PACKAGES=(
  g++ cmake make clang-format
  catkin libroscpp-dev ros-message-generation ros-message-runtime libstd-msgs-dev ros-std-msgs
  libgeometry-msgs-dev ros-geometry-msgs python3-geometry-msgs libsensor-msgs-dev ros-sensor-msgs
  python3-sensor-msgs libvisualization-msgs-dev python3-visualization-msgs libstd-srvs-dev
  python3-std-srvs libtf2-ros-dev python3-tf2-msgs librosbag-dev python3-rosbag python3-roslaunch
  python3-rostopic python3-rosservice python3-rosnode python3-rosparam rosout librostest-dev
  python3-rostest libgtest-dev libbox2d-dev libopencv-dev libeigen3-dev libyaml-cpp-dev
  libbenchmark-dev libhwy-dev libcgal-dev libcereal-dev zlib1g-dev libvtk9-dev
  liburdfdom-dev libtf2-eigen-dev libroslib-dev python3-roslib python3-rospy
  ros-robot-state-publisher librobot-state-publisher-dev
  rviz xvfb python3-pil python3-numpy python3-matplotlib
  parallel mkdocs doxygen
  clang libclang-rt-14-dev libomp-14-dev
  # What Debian's rosdep data resolves package.xml's ROS keys to beyond the above (`rosdep check`
  # in test/rosdep_check.sh), rosdep itself, and rospack/rosrun for the README's commands.
  ros-rosgraph-msgs ros-std-srvs ros-visualization-msgs ros-tf2-msgs python3-tf2-ros librviz-dev
  python3-rosdep2 rospack-tools rosbash
)

mpm_sdem_install_deps() {
  local missing=()
  local p
  for p in "${MPM_SDEM_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed"; then
      missing+=("$p")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  echo "installing ${#missing[@]} missing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq -o DPkg::Lock::Timeout=300 \
    "${missing[@]}"
}

mpm_sdem_build() {
  # catkin caches an empty PYTHONPATH for tests on a first configure without this directory
  # (shared/ros-on-debian.md, fix 2).
  mkdir -p "$BUILD_DIR/devel/lib/python3/dist-packages"
  cmake -S "$MPM_SDEM_ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@" >"$BUILD_DIR/cmake.log" 2>&1 ||
    { cat "$BUILD_DIR/cmake.log"; return 1; }
  cmake --build "$BUILD_DIR" -j"$JOBS"
}
