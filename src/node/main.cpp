// mpm_sdem_node: loads a scene, steps it, publishes, serves, records. Parameters: docs/node.md.
#include <ros/ros.h>

#include <csignal>
#include <fstream>
#include <sstream>

#include "mpm_sdem/scene/scene.hpp"
#include "node_params.hpp"
#include "services.hpp"
#include "sim_loop.hpp"

namespace {

// SIGINT and SIGTERM end the loop, which then closes the bag and the video before exiting.
volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) {
  g_stop = 1;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "mpm_sdem", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  ros::NodeHandle nh, pnh("~");

  using namespace mpm_sdem;
  node::NodeParams params;
  std::string error;
  if (!node::loadParams(pnh, params, error)) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  Scene scene;
  std::ostringstream text;
  try {
    scene = loadScene(params.scene, params.overrides);
    text << std::ifstream(params.scene).rdbuf();
  } catch (const SceneError& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  if (!node::chooseImageScale(scene, params, error)) {
    ROS_FATAL("%s", error.c_str());
    return 1;
  }
  ROS_INFO("~image and video colours: %s (%s)", render::colorByName(params.image.scale.color_by),
           params.image.scale.origin.c_str());
  try {
    node::SimLoop sim(nh, pnh, params, std::move(scene), text.str());
    node::Services services(pnh, sim.commands());
    ros::AsyncSpinner spinner(1);  // callbacks queue commands; the loop below applies them
    spinner.start();
    const int status = sim.run(g_stop);
    spinner.stop();
    ros::shutdown();
    return status;
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
}
