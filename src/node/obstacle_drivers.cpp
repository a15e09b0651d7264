#include "obstacle_drivers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/ros/conversions.hpp"
#include "sim_loop.hpp"
#include "throttle.hpp"

namespace mpm_sdem::node {

namespace {

Real wrapped(Real angle) {
  return std::remainder(angle, 2 * M_PI);
}

// The block of that id, or -1 when it is gone.
int place(const World& world, BlockId id) {
  return world.blocks() ? world.blocks()->indexOf(id) : -1;
}

}  // namespace

ObstacleDrivers::ObstacleDrivers(ros::NodeHandle& pnh, CommandQueue& queue,
                                 const NodeParams& params)
    : pnh_(pnh), queue_(queue), params_(params), listener_(tf_) {
  for (const auto& [name, frame] : params.follow_tf) {
    Follower f;
    f.name = name;
    f.frame = frame;
    followers_.push_back(f);
  }
}

void ObstacleDrivers::follow(const std::string& name, const std::string& frame,
                             const Eigen::Isometry3d* section) {
  auto f = std::find_if(followers_.begin(), followers_.end(),
                        [&](const Follower& g) { return g.name == name; });
  if (f == followers_.end()) {  // new (after a reset the same link's block keeps its own)
    followers_.emplace_back();
    f = followers_.end() - 1;
    f->name = name;
    f->frame = frame;
  }
  if (section) {
    f->has_section = true;
    f->section_rotation = Eigen::Quaterniond(section->rotation());
    f->section_height = section->translation().z();
  }
}

void ObstacleDrivers::sync(const World& world, bool fresh) {
  if (fresh) loads_.clear();
  // A reset takes the clock back: the samples in tf's buffer belong to the run before,
  // and a follower would go where its frame was at its end. tf2's listener clears its buffer
  // when it sees the clock go back, but only at the next message; cleared here at once.
  if (fresh) tf_.clear();
  const Blocks* B = world.blocks();
  auto gone = [&](BlockId id) { return fresh || place(world, id) < 0; };
  loads_.erase(
      std::remove_if(loads_.begin(), loads_.end(), [&](const Load& l) { return gone(l.id); }),
      loads_.end());
  commands_.erase(std::remove_if(commands_.begin(), commands_.end(),
                                 [&](const Command& c) { return gone(c.id); }),
                  commands_.end());
  // A follower found by name: after a reset, or when a block of its name is spawned again.
  for (Follower& f : followers_) {
    const BlockId id = B ? B->find(f.name) : BlockId();
    const bool kinematic = !id.isNull() && B->def(B->indexOf(id)).type == BodyType::kKinematic;
    if (!kinematic && !f.id.isNull())
      ROS_WARN("~follow_tf: block '%s' is gone or not kinematic; it follows %s no more",
               f.name.c_str(), f.frame.c_str());
    f.id = kinematic ? id : BlockId();
    if (kinematic) f.reach = blockReach(B->def(B->indexOf(id)));
    f.sampled = false;
  }
  for (int i = 0; B && i < B->count(); ++i) {
    const BlockDef& d = B->def(i);
    const bool follows = std::any_of(followers_.begin(), followers_.end(),
                                     [&](const Follower& f) { return f.name == d.name; });
    const bool known = std::any_of(commands_.begin(), commands_.end(),
                                   [&](const Command& c) { return c.id == B->id(i); });
    if (d.type != BodyType::kKinematic || follows || known) continue;
    Command c;
    c.id = B->id(i);
    c.name = d.name;
    const std::string name = d.name;
    c.sub = pnh_.subscribe<geometry_msgs::Twist>(
        "obstacles/" + name + "/cmd_vel", 10,
        [this, name](const geometry_msgs::Twist::ConstPtr& t) { onCmdVel(name, *t); });
    commands_.push_back(std::move(c));
  }
}

void ObstacleDrivers::checkFollowers(const World& world) const {
  const Blocks* B = world.blocks();
  for (const Follower& f : followers_) {
    const BlockId id = B ? B->find(f.name) : BlockId();
    if (id.isNull())
      throw std::runtime_error("parameter ~follow_tf: no block named '" + f.name +
                               "' in the scene (a kinematic block must follow " + f.frame + ")");
    if (B->def(B->indexOf(id)).type != BodyType::kKinematic)
      throw std::runtime_error("parameter ~follow_tf: block '" + f.name +
                               "' must be kinematic to follow a frame (body_type in the scene)");
  }
}

void ObstacleDrivers::onCmdVel(const std::string& name, const geometry_msgs::Twist& t) {
  // Callback thread: the loop applies it. Only the plane's components count (diff_drive's
  // rule for the ones it cannot follow: ignored).
  const Vec2 v_body(t.linear.x, t.linear.y);
  const Real w = t.angular.z;
  queue_.post([this, name, v_body, w](SimLoop& s) -> Reply {
    World& world = s.world();
    const auto it = std::find_if(commands_.begin(), commands_.end(),
                                 [&](const Command& c) { return c.name == name; });
    if (it == commands_.end() || place(world, it->id) < 0) return {false, "gone"};
    const Blocks& B = *world.blocks();
    const int i = place(world, it->id);
    const Vec2 v = rotated(B.state(i).angle, v_body);  // the block's axes -> fixed frame
    if (const Problem p = twistProblem(B.def(i), v, w); !p.empty()) {
      MPM_SDEM_WARN_THROTTLE(1, "~obstacles/%s/cmd_vel ignored: %s", name.c_str(),
                             p.message.c_str());
      return {false, p.message};
    }
    world.setBlockVelocity(it->id, v, w);
    it->last = world.time();
    it->moving = v.squaredNorm() > 0 || w != 0;
    return {true, ""};
  });
}

Reply ObstacleDrivers::addLoad(World& world, const std::string& name, const Vec2& force,
                               const Vec2& point, bool in_block_frame, Real torque, Real duration) {
  const BlockId id = world.blocks() ? world.blocks()->find(name) : BlockId();
  if (id.isNull()) return {false, "no block named '" + name + "'"};
  const Blocks& B = *world.blocks();
  if (B.def(B.indexOf(id)).type != BodyType::kDynamic)
    return {false, "block '" + name +
                       "' is not dynamic: a load moves only dynamic blocks (command a kinematic "
                       "one's velocity instead)"};
  // Each step adds every held load: a caller looping on requests must not slow the loop down.
  constexpr std::size_t kMaxLoads = 1000;
  if (loads_.size() >= kMaxLoads)
    return {false, "already " + std::to_string(kMaxLoads) +
                       " loads held; let some end or call ~clear_obstacle_wrenches"};
  const Real t = world.time();
  const Real until = duration < 0 ? std::numeric_limits<Real>::infinity() : t + duration;
  // With the loads held on it already: together they must not throw it past the speed cap.
  const Real acceleration = loadAcceleration(B.def(B.indexOf(id)), force, point, torque);
  std::vector<HeldLoad> held{{acceleration, until - t}};
  for (const Load& l : loads_)
    if (l.id == id && t < l.until) held.push_back({l.acceleration, l.until - t});
  if (const Problem p = heldLoadsProblem(held); !p.empty())
    return {false, "load on '" + name + "' refused: " + p.message +
                       (held.size() > 1 ? " (" + std::to_string(held.size() - 1) +
                                              " loads already held on it count too)"
                                        : std::string())};
  loads_.push_back({id, force, point, in_block_frame, torque, until, acceleration});
  return {true, "holding a load on '" + name + "' " +
                    (duration < 0 ? std::string("until cleared")
                                  : "until t = " + std::to_string(until) + " s")};
}

Reply ObstacleDrivers::clearLoads(const World& world, const std::string& name) {
  const BlockId id = world.blocks() && !name.empty() ? world.blocks()->find(name) : BlockId();
  if (!name.empty() && id.isNull()) return {false, "no block named '" + name + "'"};
  const std::size_t before = loads_.size();
  loads_.erase(std::remove_if(loads_.begin(), loads_.end(),
                              [&](const Load& l) { return name.empty() || l.id == id; }),
               loads_.end());
  return {true, "cleared " + std::to_string(before - loads_.size()) + " loads"};
}

void ObstacleDrivers::beforeStep(World& world, Real h) {
  const Real t = world.time();
  // A load acts in the steps that start before its end.
  loads_.erase(
      std::remove_if(loads_.begin(), loads_.end(),
                     [&](const Load& l) { return !(t < l.until) || place(world, l.id) < 0; }),
      loads_.end());
  for (const Load& l : loads_) {
    const Blocks& B = *world.blocks();
    const int i = place(world, l.id);
    const Real angle = B.state(i).angle;
    const Vec2 force = l.in_block_frame ? rotated(angle, l.force) : l.force;
    world.addBlockLoad(l.id, force, B.origin(i) + rotated(angle, l.point), l.torque);
  }
  for (Command& c : commands_) {
    if (!c.moving || !(params_.cmd_vel_timeout > 0) || t - c.last <= params_.cmd_vel_timeout)
      continue;
    c.moving = false;
    if (place(world, c.id) < 0) continue;
    world.setBlockVelocity(c.id, Vec2(0, 0), 0);
    ROS_INFO("~obstacles/%s/cmd_vel: no command for %g s; '%s' stopped at t = %.4f s",
             c.name.c_str(), params_.cmd_vel_timeout, c.name.c_str(), t);
  }
  for (Follower& f : followers_) steer(world, f, h);
  if (const Blocks* B = world.blocks())
    for (const int i : B->movingBlocks())
      if (B->def(i).type == BodyType::kKinematic) keepInside(world, i, h);
}

void ObstacleDrivers::keepInside(World& world, int i, Real h) {
  const Blocks& B = *world.blocks();
  const BlockState& s = B.state(i);
  Vec2 v = B.originVelocity(i);
  Real w = s.angular_velocity;
  if (v.squaredNorm() == 0 && w == 0) return;
  const DomainDef& domain = world.def().domain;
  // The outline's reach matters only to a spin (and costs the block's parts).
  const Real reach = w != 0 ? blockReach(B.def(i)) : 0;
  if (!keepInsideDomain(B.blockBounds(i), reach, h, domain.min, domain.max, v, w)) return;
  const std::string& name = B.def(i).name;
  const auto follower = std::find_if(followers_.begin(), followers_.end(),
                                     [&](const Follower& f) { return f.name == name; });
  const std::string who =
      "'" + name + "'" +
      (follower == followers_.end() ? std::string() : " (following " + follower->frame + ")");
  MPM_SDEM_WARN_THROTTLE(1, "%s stops at the domain's wall: its velocity towards it is cut",
                         who.c_str());
  world.setBlockVelocity(B.id(i), v, w);
}

void ObstacleDrivers::warnIfOutOfPlane(const Follower& f,
                                       const geometry_msgs::TransformStamped& ts) const {
  // The outline stays the frame's section while the frame moves in the plane: turns about its
  // normal (z) and shifts along x and y. Anything else changes the section. Tolerances: 1 deg
  // (a 10 cm deep solid's section moves by 1.7 mm) and 1 mm.
  const geometry_msgs::Quaternion& q = ts.transform.rotation;
  const Eigen::Quaterniond now(q.w, q.x, q.y, q.z);
  const Eigen::Vector3d normal = (now * f.section_rotation.inverse()) * Eigen::Vector3d::UnitZ();
  const Real tilt = std::acos(std::clamp(normal.z(), -1.0, 1.0));
  const Real shift = std::abs(ts.transform.translation.z - f.section_height);
  if (tilt > M_PI / 180 || shift > 1e-3)
    MPM_SDEM_WARN_THROTTLE(5,
                           "~robot_links: frame %s has tilted %.1f deg out of the plane and moved "
                           "%.1f mm along its normal since block '%s' was cut from it; the block "
                           "keeps that section (a link's section follows motions in the plane "
                           "only: joints about the plane's normal)",
                           f.frame.c_str(), tilt * 180 / M_PI, 1e3 * shift, f.name.c_str());
}

void ObstacleDrivers::steer(World& world, Follower& f, Real h) {
  const int i = place(world, f.id);
  if (i < 0) return;
  geometry_msgs::TransformStamped ts;
  try {
    ts = tf_.lookupTransform(params_.fixed_frame, f.frame, ros::Time(0));
  } catch (const tf2::TransformException& e) {
    MPM_SDEM_WARN_THROTTLE(5, "~follow_tf: '%s' holds still: no transform %s -> %s yet (%s)",
                           f.name.c_str(), params_.fixed_frame.c_str(), f.frame.c_str(), e.what());
    world.setBlockVelocity(f.id, Vec2(0, 0), 0);
    return;
  }
  const Vec2 p(ts.transform.translation.x, ts.transform.translation.y);
  const Real yaw = conversions::yaw(ts.transform.rotation);
  const Real max_speed = params_.follow_tf_max_speed;
  if (!f.sampled || ts.header.stamp != f.stamp) {  // a new sample
    // A frame that moves faster than the followers may (a jump, a reset of its publisher) is
    // closed on at that speed, not followed.
    if (f.sampled) {
      const Real gap = (ts.header.stamp - f.stamp).toSec();
      const Real moved = (p - f.position).norm() + std::abs(wrapped(yaw - f.angle)) * f.reach;
      if (!(moved <= max_speed * std::fmax(gap, 0.0)))
        MPM_SDEM_WARN_THROTTLE(1,
                               "~follow_tf: frame %s moved %.3g m in %.3g s, faster than "
                               "~follow_tf_max_speed %g m/s; '%s' closes in at that speed",
                               f.frame.c_str(), moved, gap, max_speed, f.name.c_str());
      else if (gap > params_.follow_tf_delay && moved > 0)
        MPM_SDEM_WARN_THROTTLE(5,
                               "~follow_tf: frame %s's samples come %.3g s apart, more than "
                               "~follow_tf_delay %g s: '%s' waits at each one (set the delay "
                               "above tf's period)",
                               f.frame.c_str(), gap, params_.follow_tf_delay, f.name.c_str());
    }
    if (f.has_section) warnIfOutOfPlane(f, ts);
    f.sampled = true, f.stamp = ts.header.stamp, f.position = p, f.angle = yaw;
  }
  // The block ends this step where the frame was ~follow_tf_delay before its end: tf's
  // interpolation between the samples that bracket that time. Samples come with gaps and
  // jitter, but a path sampled at any times is the same path, so the block's motion does not
  // depend on when they came, and it never runs past the frame: where the frame stops, it stops.
  // (A block run on at the frame's last speed until the next sample overshoots a frame that
  // stops, then pulls back, unloading what it pressed.) When that time is not bracketed (the
  // first sample, a sample late, tf slower than the delay), the block closes on the latest sample
  // in the delay instead: slower, and never past it.
  const Real delay = params_.follow_tf_delay;
  // With /use_sim_time the clock is the world's (this node publishes it): exact, where
  // ros::Time::now() is /clock as it came back, up to a millisecond behind.
  const ros::Time now =
      ros::Time::isSimTime() ? conversions::toRosTime(world.time()) : ros::Time::now();
  const ros::Time end = now + ros::Duration(h);
  Vec2 target = f.position;
  Real target_angle = f.angle;
  Real closing = std::fmax(delay, h);
  if (end.toSec() > delay) {
    try {
      const geometry_msgs::TransformStamped then =
          tf_.lookupTransform(params_.fixed_frame, f.frame, end - ros::Duration(delay));
      target = Vec2(then.transform.translation.x, then.transform.translation.y);
      target_angle = conversions::yaw(then.transform.rotation);
      closing = h;
    } catch (const tf2::TransformException&) {  // not bracketed: the latest sample
    }
  }
  const Blocks& B = *world.blocks();
  Vec2 v = (target - B.origin(i)) / closing;
  Real w = wrapped(target_angle - B.state(i).angle) / closing;
  // Far from its frame, a block closes in no faster than its fastest point may move.
  const Real speed = v.norm() + std::abs(w) * f.reach;
  if (speed > max_speed) {
    v *= max_speed / speed;
    w *= max_speed / speed;
  }
  world.setBlockVelocity(f.id, v, w);
}

}  // namespace mpm_sdem::node
