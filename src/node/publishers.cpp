#include "publishers.hpp"

#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/fill_image.h>
#include <std_msgs/String.h>

#include "mpm_sdem/core/diagnostics.hpp"

namespace mpm_sdem::node {

namespace {

Profile since(const Profile& now, const Profile& then) {
  Profile d;
  for (int k = 0; k < static_cast<int>(Stage::kCount); ++k)
    d.seconds[k] = now.seconds[k] - then.seconds[k];
  d.steps = now.steps - then.steps;
  return d;
}

}  // namespace

bool Publishers::Channel::due(Real t, bool force, bool always) {
  if (!always && pub.getNumSubscribers() == 0) return false;
  return clock.due(t, force);
}

Publishers::Publishers(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params,
                       const std::string& scene_text)
    : params_(params) {
  particles_ = {pnh.advertise<sensor_msgs::PointCloud2>("particles", 2),
                SampleClock(params.particles_rate)};
  blocks_ = {pnh.advertise<mpm_sdem::BlockStates>("blocks", 10), SampleClock(params.blocks_rate)};
  poses_ = {pnh.advertise<geometry_msgs::PoseArray>("block_poses", 10),
            SampleClock(params.blocks_rate)};
  // Latched: a late listener (rostopic echo -n1) gets the last one at once, paused or not.
  stats_ = {pnh.advertise<mpm_sdem::SimStats>("stats", 10, true), SampleClock(params.stats_rate)};
  image_ = {pnh.advertise<sensor_msgs::Image>("image", 1), SampleClock(params.image_rate)};
  // FEM bodies' triangles coloured by von Mises stress, at the blocks' rate; latched, so a
  // late listener sees them while paused.
  fem_ = {pnh.advertise<visualization_msgs::Marker>("fem_mesh", 2, true),
          SampleClock(params.blocks_rate)};
  fem_nodes_ = {pnh.advertise<sensor_msgs::PointCloud2>("fem_nodes", 2, true),
                SampleClock(params.blocks_rate)};
  markers_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  scene_ = pnh.advertise<std_msgs::String>("scene", 1, true);
  nh.param("/use_sim_time", use_sim_time_, false);
  if (use_sim_time_)
    clock_ = {nh.advertise<rosgraph_msgs::Clock>("/clock", 10), SampleClock(params.clock_rate)};
  std_msgs::String text;
  text.data = scene_text;
  scene_.publish(text);
}

void Publishers::restart(const World& world) {
  for (Channel* c : {&particles_, &blocks_, &poses_, &stats_, &image_, &clock_, &fem_, &fem_nodes_})
    c->clock.restart();
  stats_profile_ = world.profile();
}

void Publishers::blocksChanged(const World& world) {
  markers_.publish(conversions::toMarkers(world, params_.tf_prefix, ros::Time(0)));
}

void Publishers::publishClock(const std_msgs::Header& header) {
  rosgraph_msgs::Clock clock;
  clock.clock = header.stamp;
  clock_.pub.publish(clock);
}

void Publishers::publishStats(const World& world, const conversions::StatsInput& status,
                              const std_msgs::Header& header) {
  conversions::StatsInput in = status;
  in.profile = since(world.profile(), stats_profile_);
  const Diagnostics d = measure(world);
  if (const std::string w = machWarning(d, world.time()); !w.empty())
    ROS_WARN_ONCE("%s", w.c_str());
  stats_.pub.publish(conversions::toStats(world, d, in, header));
  stats_profile_ = world.profile();
}

void Publishers::publishIdle(const World& world, const conversions::StatsInput& status) {
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(world.time());
  header.frame_id = params_.fixed_frame;
  if (use_sim_time_) publishClock(header);
  publishStats(world, status, header);
}

void Publishers::publish(const World& world, const conversions::StatsInput& status, bool force) {
  const Real t = world.time();
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(t);
  header.frame_id = params_.fixed_frame;
  // Clock first, so that a listener's time has reached the stamps that follow it.
  if (clock_.due(t, force, true)) publishClock(header);
  if (particles_.due(t, force)) {
    conversions::toPointCloud(world, params_.cloud_decimation, header, cloud_);
    particles_.pub.publish(cloud_);
  }
  // Block states feed tf, which is always sent (other nodes look frames up without
  // subscribing to us).
  const bool blocks_due = blocks_.due(t, force, true);
  const bool poses_due = poses_.due(t, force);
  if ((blocks_due || poses_due) && world.blocks()) {
    const mpm_sdem::BlockStates states = conversions::toBlockStates(world, header);
    if (blocks_due) {
      blocks_.pub.publish(states);
      tf_.sendTransform(conversions::toTransforms(states, params_.tf_prefix));
    }
    if (poses_due) poses_.pub.publish(conversions::toPoseArray(states));
  }
  if (world.femBodies() && fem_.due(t, force))
    fem_.pub.publish(conversions::toFemMarker(world, header));
  if (world.femBodies() && fem_nodes_.due(t, force)) {
    conversions::toFemCloud(world, header, fem_cloud_);
    fem_nodes_.pub.publish(fem_cloud_);
  }
  // Always, like tf: latched, so that it answers a late `rostopic echo -n1`.
  if (stats_.due(t, force, true)) publishStats(world, status, header);
  if (image_.due(t, force)) {
    render::renderWorld(world, params_.image, frame_);
    sensor_msgs::Image img;
    img.header = header;
    sensor_msgs::fillImage(img, "bgr8", frame_.rows, frame_.cols, frame_.step, frame_.data);
    image_.pub.publish(img);
  }
}

}  // namespace mpm_sdem::node
