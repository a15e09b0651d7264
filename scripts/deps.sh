# Sourced by the scripts: installs missing Debian packages (idempotent; no apt call when
# everything is there) and configures and builds the package out of tree.
# Environment: BUILD_DIR (default: <repo>/build), JOBS (default: 2).

MPM_SDEM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$MPM_SDEM_ROOT/build}"
JOBS="${JOBS:-2}"

# Debian's ROS 1 needs the system python3, not a pyenv shim (shared/ros-on-debian.md, fix 1).
export PATH="/usr/bin:$PATH"

# What the node, the runner and the default scene need (scripts/run): the compiler, ROS 1's
# C++ and launch packages, and the core's libraries. OpenCV by module (the images and the video),
# not libopencv-dev, which brings every module and VTK with it; VTK itself (ParaView output) is
# optional in the build and comes with the test packages.
MPM_SDEM_RUN_PACKAGES=(
  g++ cmake make
  catkin libroscpp-dev ros-message-generation ros-message-runtime libstd-msgs-dev ros-std-msgs
  libgeometry-msgs-dev ros-geometry-msgs libsensor-msgs-dev ros-sensor-msgs
  libvisualization-msgs-dev ros-visualization-msgs libstd-srvs-dev ros-std-srvs libtf2-ros-dev
  ros-tf2-msgs libtf2-eigen-dev ros-rosgraph-msgs libroslib-dev librosbag-dev python3-rosbag
  python3-roslaunch rosout libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libbox2d-dev libeigen3-dev libyaml-cpp-dev libhwy-dev libcgal-dev libcereal-dev zlib1g-dev
  liburdfdom-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-videoio-dev
  libopencv-flann-dev
)

# What the tests, the report, the docs, the fuzzers and the benchmarks add (scripts/test,
# scripts/validate, scripts/fuzz, scripts/bench).
MPM_SDEM_TEST_PACKAGES=(
  clang-format libgtest-dev libbenchmark-dev libvtk9-dev
  # What rosdep resolves package.xml's OpenCV key to (test/rosdep_check.sh); the build needs only
  # the five modules above.
  libopencv-dev
  python3-geometry-msgs python3-sensor-msgs python3-visualization-msgs python3-std-srvs
  python3-tf2-msgs python3-tf2-ros python3-rostopic python3-rosservice python3-rosnode
  python3-rosparam python3-roslib python3-rospy librostest-dev python3-rostest
  ros-robot-state-publisher librobot-state-publisher-dev
  rviz librviz-dev xvfb python3-pil python3-numpy python3-matplotlib
  parallel mkdocs doxygen
  clang libclang-rt-14-dev libomp-14-dev
  # What Debian's rosdep data resolves package.xml's ROS keys to beyond the above (`rosdep check`
  # in test/rosdep_check.sh), rosdep itself, and rospack/rosrun for the README's commands.
  python3-rosdep2 rospack-tools rosbash
)

# mpm_sdem_install_deps run|all: installs what is missing of the run packages, or of both lists.
mpm_sdem_install_deps() {
  local wanted=("${MPM_SDEM_RUN_PACKAGES[@]}")
  if [ "${1:-all}" = all ]; then wanted+=("${MPM_SDEM_TEST_PACKAGES[@]}"); fi
  local missing=()
  local p
  for p in "${wanted[@]}"; do
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
  # Without recommends: the lists name what is used, and a run-only install stays small.
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    -o DPkg::Lock::Timeout=300 "${missing[@]}"
}

# mpm_sdem_configure [CMAKE_ARGS...]: configures the build directory.
mpm_sdem_configure() {
  # catkin caches an empty PYTHONPATH for tests on a first configure without this directory
  # (shared/ros-on-debian.md, fix 2).
  mkdir -p "$BUILD_DIR/devel/lib/python3/dist-packages"
  # Without the variables a sourced devel space sets: catkin caches the setup's effect as the
  # difference it makes to this environment (catkin_generated/setup_cached.sh), so a configure
  # from a shell that had sourced build/devel/setup.bash cached no ROS_PACKAGE_PATH, and every
  # rostest then failed with "ResourceNotFound: mpm_sdem".
  env -u CMAKE_PREFIX_PATH -u LD_LIBRARY_PATH -u PKG_CONFIG_PATH -u PYTHONPATH -u ROS_DISTRO \
    -u ROS_ETC_DIR -u ROS_PACKAGE_PATH -u ROS_PYTHON_VERSION -u ROS_VERSION -u ROS_ROOT \
    -u ROSLISP_PACKAGE_DIRECTORIES \
    cmake -S "$MPM_SDEM_ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@" >"$BUILD_DIR/cmake.log" 2>&1 ||
    { cat "$BUILD_DIR/cmake.log"; return 1; }
}

# mpm_sdem_build [CMAKE_ARGS...]: configures and builds every target.
mpm_sdem_build() {
  mpm_sdem_configure "$@"
  cmake --build "$BUILD_DIR" -j"$JOBS"
}
