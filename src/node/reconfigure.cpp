#include "reconfigure.hpp"

#include <cstdio>
#include <utility>

#include "mpm_sdem/core/world.hpp"
#include "sim_loop.hpp"

namespace mpm_sdem::node {

namespace {

mpm_sdem::NodeConfig toConfig(const RuntimeSettings& s, const std::string& refused) {
  const NodeParams& p = s.params;
  mpm_sdem::NodeConfig c;
  c.refused = refused;
  c.real_time_factor = p.real_time_factor;
  c.particles_rate = p.particles_rate;
  c.cloud_decimation = p.cloud_decimation;
  c.blocks_rate = p.blocks_rate;
  c.stats_rate = p.stats_rate;
  c.image_rate = p.image_rate;
  c.terrain_rate = p.terrain_rate;
  c.clock_rate = p.clock_rate;
  c.cmd_vel_timeout = p.cmd_vel_timeout;
  c.follow_tf_delay = p.follow_tf_delay;
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
  p.follow_tf_delay = c.follow_tf_delay;
  p.follow_tf_max_speed = c.follow_tf_max_speed;
  s.gravity = {c.gravity_x, c.gravity_y};
  return s;
}

// The settings a request asks to change, with the values asked for ("blocks_rate -5,
// gravity_y -2e+04"): a refusal names them, not a value the server made of them.
std::string asked(const mpm_sdem::NodeConfig& now, const mpm_sdem::NodeConfig& next) {
  using C = mpm_sdem::NodeConfig;
  const std::pair<const char*, double C::*> doubles[] = {
      {"real_time_factor", &C::real_time_factor},
      {"particles_rate", &C::particles_rate},
      {"blocks_rate", &C::blocks_rate},
      {"stats_rate", &C::stats_rate},
      {"image_rate", &C::image_rate},
      {"terrain_rate", &C::terrain_rate},
      {"clock_rate", &C::clock_rate},
      {"cmd_vel_timeout", &C::cmd_vel_timeout},
      {"follow_tf_delay", &C::follow_tf_delay},
      {"follow_tf_max_speed", &C::follow_tf_max_speed},
      {"gravity_x", &C::gravity_x},
      {"gravity_y", &C::gravity_y}};
  std::string out;
  char text[96];
  // NaN differs from everything, itself included: asked for whenever it is sent.
  for (const auto& [name, field] : doubles)
    if (!(now.*field == next.*field)) {
      std::snprintf(text, sizeof text, "%s%s %g", out.empty() ? "" : ", ", name, next.*field);
      out += text;
    }
  if (now.cloud_decimation != next.cloud_decimation) {
    std::snprintf(text, sizeof text, "%scloud_decimation %d", out.empty() ? "" : ", ",
                  next.cloud_decimation);
    out += text;
  }
  return out;
}

}  // namespace

Reconfigure::Reconfigure(const ros::NodeHandle& pnh, CommandQueue& queue,
                         const RuntimeSettings& settings)
    : queue_(queue), current_(settings), server_(mutex_, pnh) {
  // The server starts from the parameter server and the cfg's defaults; the node's values
  // replace them before the first callback.
  server_.updateConfig(toConfig(current_, refused_));
  server_.setCallback([this](mpm_sdem::NodeConfig& c, std::uint32_t level) { onChange(c, level); });
}

void Reconfigure::publish(const RuntimeSettings& settings) {
  boost::recursive_mutex::scoped_lock lock(mutex_);
  current_ = settings;
  server_.updateConfig(toConfig(current_, refused_));
}

void Reconfigure::onChange(mpm_sdem::NodeConfig& config, std::uint32_t /*level*/) {
  // Called with mutex_ held by the server, which answers the caller and publishes
  // ~parameter_updates with config as this leaves it. The cfg gives no min or max, so config
  // holds the values asked for, not the server's clamp of them (cfg/Node.cfg).
  const RuntimeSettings next = fromConfig(config, current_);
  Problem p = runtimeProblem(next.params);
  if (p.empty()) p = World::gravityProblem(next.gravity);
  if (!p.empty()) {
    refused_ = "refused " + asked(toConfig(current_, ""), config) + ": " + p.text() +
               "; the values in effect stay";
    ROS_WARN("dynamic_reconfigure: %s", refused_.c_str());
    config = toConfig(current_, refused_);
    return;
  }
  refused_.clear();
  config.refused.clear();
  // The loop says "nothing changed" (and logs nothing) when nothing did: the first call.
  current_ = next;
  queue_.post([next](SimLoop& sim) { return sim.applySettings(next); });
}

}  // namespace mpm_sdem::node
