#include "publishers.hpp"

#include <geometry_msgs/WrenchStamped.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/fill_image.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <unordered_map>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/terrain.hpp"

namespace mpm_sdem::node {

bool Publishers::Channel::due(Real t, bool force, bool always) {
  if (force && latched) return clock.due(t, true);
  // The schedule before the listeners: roscpp finds a topic's listeners by its name among all
  // the node's topics (a thousand with a thousand obstacles' wrenches), once per channel and
  // step otherwise. A listener that comes between two samples waits for the next.
  if (!clock.due(t, force)) return false;
  return always || pub.getNumSubscribers() > 0;
}

Publishers::Publishers(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params,
                       const std::string& scene_text, const World& world)
    : params_(params), pnh_(pnh) {
  particles_ = {pnh.advertise<sensor_msgs::PointCloud2>("particles", 2, true), SampleClock(), true};
  blocks_ = {pnh.advertise<mpm_sdem::BlockStates>("blocks", 10), SampleClock()};
  poses_ = {pnh.advertise<geometry_msgs::PoseArray>("block_poses", 10), SampleClock()};
  // Latched: a late listener (rostopic echo -n1) gets the last one at once, paused or not.
  stats_ = {pnh.advertise<mpm_sdem::SimStats>("stats", 10, true), SampleClock()};
  image_ = {pnh.advertise<sensor_msgs::Image>("image", 1), SampleClock()};
  // FEM bodies' triangles coloured by von Mises stress, at the blocks' rate; latched, so a
  // late listener sees them while paused.
  if (world.femBodies()) {
    fem_ = {pnh.advertise<visualization_msgs::Marker>("fem_mesh", 2, true), SampleClock(), true};
    fem_nodes_ = {pnh.advertise<sensor_msgs::PointCloud2>("fem_nodes", 2, true), SampleClock(),
                  true};
  }
  markers_ = {pnh.advertise<visualization_msgs::MarkerArray>("markers", 1, true), SampleClock(),
              true};
  arrows_ = {pnh.advertise<visualization_msgs::MarkerArray>("force_arrows", 1, true), SampleClock(),
             true};
  terrain_ = {pnh.advertise<sensor_msgs::PointCloud2>("terrain", 2, true), SampleClock(), true};
  // What a listener needs to read the numbers (latched on the parameter server).
  pnh.setParam("convention/plane",
               "2D plane strain in the x-y plane of the fixed frame, y up against gravity; z is "
               "out of the plane (z = 0 everywhere)");
  pnh.setParam("convention/thickness_m", 1.0);
  pnh.setParam("convention/force", "N per metre of out-of-plane thickness (N/m)");
  pnh.setParam("convention/torque", "N m per metre of thickness, about z (N m/m)");
  pnh.setParam("convention/mass", "kg per metre of thickness (kg/m)");
  pnh.setParam("convention/wrench",
               "~obstacles/<name>/wrench: the contact load of the material and the other blocks, "
               "at the block frame's origin in its axes");
  scene_ = pnh.advertise<std_msgs::String>("scene", 1, true);
  bool use_sim_time = false;
  nh.param("/use_sim_time", use_sim_time, false);
  if (use_sim_time) clock_thread_ = std::make_unique<ClockPublisher>(nh);
  setRates();
  std_msgs::String text;
  text.data = scene_text;
  scene_.publish(text);
}

void Publishers::setRates() {
  const NodeParams& p = params_;
  particles_.clock = SampleClock(p.particles_rate);
  stats_.clock = SampleClock(p.stats_rate);
  image_.clock = SampleClock(p.image_rate);
  terrain_.clock = SampleClock(p.terrain_rate);
  for (Channel* c : {&blocks_, &poses_, &fem_, &fem_nodes_, &markers_, &arrows_})
    c->clock = SampleClock(p.blocks_rate);
  clock_.clock = SampleClock(clock_thread_ ? p.clock_rate : 0);  // only with /use_sim_time
}

void Publishers::restart(const World& world) {
  for (Channel* c : {&particles_, &blocks_, &poses_, &stats_, &image_, &clock_, &fem_, &fem_nodes_,
                     &markers_, &arrows_, &terrain_})
    c->clock.restart();
  stats_profile_ = world.profile();
}

void Publishers::blocksChanged(const World& world) {
  const Blocks* B = world.blocks();
  // One wrench topic per block, made and dropped with it (by name: a thousand obstacles make a
  // thousand topics, each looked up once).
  std::unordered_map<std::string, Obstacle> before;
  for (Obstacle& o : obstacles_) before.emplace(o.name, std::move(o));
  std::vector<Obstacle> kept;
  for (int i = 0; B && i < B->count(); ++i) {
    const std::string& name = B->def(i).name;
    if (auto it = before.find(name); it != before.end()) {
      kept.push_back(std::move(it->second));
      continue;
    }
    auto listeners = std::make_shared<std::atomic<int>>(0);
    ros::AdvertiseOptions o = ros::AdvertiseOptions::create<geometry_msgs::WrenchStamped>(
        "obstacles/" + name + "/wrench", 10,
        [listeners](const ros::SingleSubscriberPublisher&) { ++*listeners; },
        [listeners](const ros::SingleSubscriberPublisher&) { --*listeners; }, ros::VoidConstPtr(),
        nullptr);
    kept.push_back({name, pnh_.advertise(o), listeners});
  }
  obstacles_.swap(kept);
  // The arrows' scale: the whole weight (material and dynamic blocks) a fifth of the domain.
  Real mass = 0;
  for (Real m : world.particles().mass) mass += m;
  for (int i = 0; B && i < B->count(); ++i)
    if (B->def(i).type == BodyType::kDynamic) mass += B->massProperties(i).mass;
  const Vec2 extent = world.def().domain.max - world.def().domain.min;
  const Real weight = mass * world.def().solver.gravity.norm();
  arrow_scale_ = params_.force_arrow_scale > 0 ? params_.force_arrow_scale
                 : weight > 0                  ? 0.2 * extent.maxCoeff() / weight
                                               : 0;
  // The domain's frame and the static blocks on /tf_static: the new ones added to the latched
  // message, or all of them anew (a new broadcaster) when one went or moved. (tf2_ros matches
  // each frame sent against those it holds, one by one: resending a thousand each time a block
  // came cost 60% of a spawn.)
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(world.time());
  header.frame_id = params_.fixed_frame;
  std::vector<geometry_msgs::TransformStamped> fixed = conversions::toTransforms(
      conversions::toBlockStates(world, header), params_.tf_prefix, conversions::Frames::kStatic);
  fixed.push_back(conversions::domainTransform(world, header, params_.tf_prefix));
  std::vector<geometry_msgs::TransformStamped> added;
  std::size_t kept_frames = 0;
  bool changed = false;
  for (const geometry_msgs::TransformStamped& t : fixed) {
    const auto it = static_sent_.find(t.child_frame_id);
    if (it == static_sent_.end()) {
      added.push_back(t);
    } else if (it->second == t.transform) {
      ++kept_frames;
    } else {
      changed = true;
    }
  }
  if (changed || kept_frames < static_sent_.size() || !tf_static_) {
    tf_static_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    static_sent_.clear();
    added = fixed;
  }
  if (added.empty()) return;
  for (const geometry_msgs::TransformStamped& t : added)
    static_sent_[t.child_frame_id] = t.transform;
  tf_static_->sendTransform(added);
}

void Publishers::publishClock(const std_msgs::Header& header) {
  clock_thread_->post(header.stamp);
}

void Publishers::publishStats(const World& world, const conversions::StatsInput& status,
                              const std_msgs::Header& header) {
  conversions::StatsInput in = status;
  in.profile = world.profile().since(stats_profile_);
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
  if (clock_thread_) publishClock(header);
  publishStats(world, status, header);
}

void Publishers::publishBlocks(const World& world, const std_msgs::Header& header, bool force) {
  const Real t = world.time();
  // Block states feed tf and the wrenches, which are always sent (other nodes look frames up
  // without subscribing to us, and a wrench topic has its own listeners).
  const bool blocks_due = blocks_.due(t, force, true);
  const bool poses_due = poses_.due(t, force);
  const bool markers_due = markers_.due(t, force);
  const bool arrows_due = arrows_.due(t, force);
  if (!world.blocks()) {
    if (markers_due) markers_.pub.publish(conversions::toMarkers(world, header));
    return;
  }
  if (!(blocks_due || poses_due || markers_due || arrows_due)) return;
  const mpm_sdem::BlockStates states = conversions::toBlockStates(world, header);
  if (blocks_due) {
    blocks_.pub.publish(states);
    const auto moving =
        conversions::toTransforms(states, params_.tf_prefix, conversions::Frames::kMoving);
    if (!moving.empty()) tf_.sendTransform(moving);
    for (std::size_t i = 0; i < states.blocks.size() && i < obstacles_.size(); ++i) {
      if (obstacles_[i].name != states.blocks[i].name || *obstacles_[i].listeners == 0) continue;
      geometry_msgs::WrenchStamped w;
      w.header.stamp = header.stamp;
      w.header.frame_id = conversions::blockFrame(params_.tf_prefix, states.blocks[i].name);
      w.wrench = conversions::toWrench(states.blocks[i]);
      obstacles_[i].wrench.publish(w);
    }
  }
  if (poses_due) poses_.pub.publish(conversions::toPoseArray(states));
  if (markers_due) markers_.pub.publish(conversions::toMarkers(world, header));
  if (arrows_due) arrows_.pub.publish(conversions::toForceArrows(states, arrow_scale_));
}

Real Publishers::terrainColumn(const World& world) const {
  return params_.terrain_resolution > 0 ? params_.terrain_resolution : world.def().cell_size;
}

int Publishers::terrainColumns(const World& world) const {
  const DomainDef& d = world.def().domain;
  return static_cast<int>(std::ceil((d.max.x() - d.min.x()) / terrainColumn(world) - 1e-9));
}

Problem Publishers::terrainProblem(const World& world) const {
  // A message of 12 bytes a column: 1e5 columns is 1.2 MB at rates/terrain.
  constexpr double kMaxColumns = 1e5;
  const DomainDef& d = world.def().domain;
  if ((d.max.x() - d.min.x()) / terrainColumn(world) <= kMaxColumns) return "";
  return "parameter ~terrain/resolution " + std::to_string(params_.terrain_resolution) +
         " m cuts the domain into more than 100000 columns; use at least " +
         std::to_string((d.max.x() - d.min.x()) / kMaxColumns) + " m (0: the cell size)";
}

void Publishers::publishTerrain(const World& world, const std_msgs::Header& header) {
  const Real x0 = world.def().domain.min.x(), dx = terrainColumn(world);
  heightProfile(world.particles(), x0, dx, terrainColumns(world), heights_);
  conversions::toTerrainCloud(heights_, x0, dx, header, terrain_cloud_);
  terrain_.pub.publish(terrain_cloud_);
}

void Publishers::publish(const World& world, const conversions::StatsInput& status, bool force) {
  const Real t = world.time();
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(t);
  header.frame_id = params_.fixed_frame;
  // Clock first; its thread sends it within a millisecond of wall time (ClockPublisher).
  if (clock_thread_ && clock_.due(t, force, true)) publishClock(header);
  if (particles_.due(t, force)) {
    conversions::toPointCloud(world, params_.cloud_decimation, header, cloud_);
    particles_.pub.publish(cloud_);
  }
  publishBlocks(world, header, force);
  if (terrain_.due(t, force)) publishTerrain(world, header);
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
