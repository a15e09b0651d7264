#include "reconfigure.hpp"

#include "mpm_sdem/core/world.hpp"
#include "sim_loop.hpp"

namespace mpm_sdem::node {

namespace {

mpm_sdem::NodeConfig toConfig(const RuntimeSettings& s) {
  const NodeParams& p = s.params;
  mpm_sdem::NodeConfig c;
  c.real_time_factor = p.real_time_factor;
  c.particles_rate = p.particles_rate;
  c.cloud_decimation = p.cloud_decimation;
  c.blocks_rate = p.blocks_rate;
  c.stats_rate = p.stats_rate;
  c.image_rate = p.image_rate;
  c.terrain_rate = p.terrain_rate;
  c.clock_rate = p.clock_rate;
  c.cmd_vel_timeout = p.cmd_vel_timeout;
  c.follow_tf_time_constant = p.follow_tf_time_constant;
  c.follow_tf_max_speed = p.follow_tf_max_speed;
  c.gravity_x = s.gravity.x();
  c.gravity_y = s.gravity.y();
  return c;
}

RuntimeSettings fromConfig(const mpm_sdem::NodeConfig& c, RuntimeSettings s) {
  NodeParams& p = s.params;
  p.real_time_factor = c.real_time_factor;
  p.particles_rate = c.particles_rate;
  p.cloud_decimation = c.cloud_decimation;
  p.blocks_rate = c.blocks_rate;
  p.stats_rate = c.stats_rate;
  p.image_rate = c.image_rate;
  p.terrain_rate = c.terrain_rate;
  p.clock_rate = c.clock_rate;
  p.cmd_vel_timeout = c.cmd_vel_timeout;
  p.follow_tf_time_constant = c.follow_tf_time_constant;
  p.follow_tf_max_speed = c.follow_tf_max_speed;
  s.gravity = {c.gravity_x, c.gravity_y};
  return s;
}

}  // namespace

Reconfigure::Reconfigure(const ros::NodeHandle& pnh, CommandQueue& queue,
                         const RuntimeSettings& settings)
    : queue_(queue), current_(settings), server_(mutex_, pnh) {
  // The server starts from the parameter server and the cfg's defaults; the node's values
  // replace them before the first callback.
  server_.updateConfig(toConfig(current_));
  server_.setCallback([this](mpm_sdem::NodeConfig& c, std::uint32_t level) { onChange(c, level); });
}

void Reconfigure::publish(const RuntimeSettings& settings) {
  boost::recursive_mutex::scoped_lock lock(mutex_);
  current_ = settings;
  server_.updateConfig(toConfig(current_));
}

void Reconfigure::onChange(mpm_sdem::NodeConfig& config, std::uint32_t /*level*/) {
  // Called with mutex_ held by the server.
  const RuntimeSettings next = fromConfig(config, current_);
  Problem p = runtimeProblem(next.params);
  if (p.empty()) p = World::gravityProblem(next.gravity);
  if (!p.empty()) {
    ROS_WARN("dynamic_reconfigure: refused (%s); the values in effect stay", p.text().c_str());
    config = toConfig(current_);
    return;
  }
  // The loop says "nothing changed" (and logs nothing) when nothing did: the first call.
  current_ = next;
  queue_.post([next](SimLoop& sim) { return sim.applySettings(next); });
}

}  // namespace mpm_sdem::node
