#include "services.hpp"

#include <tf2/LinearMath/Transform.h>

#include <cmath>
#include <cstdio>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/ros/conversions.hpp"
#include "sim_loop.hpp"
#include "throttle.hpp"

namespace mpm_sdem::node {

namespace {

// A reply, and the log line of a refusal, hold at most this much: a request's bad field is
// echoed as a bounded prefix (the checks cut names and frames already; this is the backstop).
constexpr std::size_t kMaxReply = 1024;

template <class Res>
bool answer(Res& res, const Reply& r) {
  res.success = r.success;
  res.message = r.message.size() <= kMaxReply
                    ? r.message
                    : r.message.substr(0, kMaxReply) + "... (" + std::to_string(r.message.size()) +
                          " characters in all)";
  // Throttled: a caller looping on a bad request must not flood the log (it gets every reply).
  if (!r.success) MPM_SDEM_WARN_THROTTLE(1, "request refused: %s", res.message.c_str());
  return true;  // the call itself succeeded; success says whether the request did
}

// A problem in the words of the requests: their fields, not the scene file's keys.
std::string inRequestTerms(const Problem& p) {
  static const std::pair<const char*, const char*> fields[] = {
      {"velocity", "twist"},
      {"angular_velocity", "twist.angular.z"},
      {"position", "pose"},
      {"angle", "pose.theta"},
      {"rounding", "rounding (with disk_radius for a disk)"}};
  for (const auto& [key, field] : fields) {
    if (p.key == key) return std::string(field) + ": " + p.message;
  }
  return p.text();
}

// Sets a block's velocity from a twist of its frame origin: refused for a static block and
// for a twist that would collapse the step (twistProblem).
Reply applyTwist(World& w, BlockId id, const geometry_msgs::Twist& t) {
  const BlockDef& def = w.blocks()->def(w.blocks()->indexOf(id));
  const Vec2 v(t.linear.x, t.linear.y);
  if (const Problem p = twistProblem(def, v, t.angular.z); !p.empty())
    return {false, "block '" + def.name + "': " + inRequestTerms(p)};
  w.setBlockVelocity(id, v, t.angular.z);
  return {true, ""};
}

std::string describe(const geometry_msgs::Twist& t) {
  char s[128];
  std::snprintf(s, sizeof s, "(%.3g, %.3g) m/s, %.3g rad/s", t.linear.x, t.linear.y, t.angular.z);
  return s;
}

// The block of that name, or the null id.
BlockId findBlock(World& w, const std::string& name) {
  return w.blocks() ? w.blocks()->find(name) : BlockId();
}

}  // namespace

Services::Services(ros::NodeHandle& pnh, CommandQueue& queue) : queue_(queue) {
  servers_.push_back(pnh.advertiseService("spawn_obstacle", &Services::spawn, this));
  servers_.push_back(pnh.advertiseService("remove_obstacle", &Services::remove, this));
  servers_.push_back(pnh.advertiseService("set_obstacle_state", &Services::setState, this));
  servers_.push_back(pnh.advertiseService("list_obstacles", &Services::list, this));
  servers_.push_back(pnh.advertiseService("step", &Services::step, this));
  using Trigger = std_srvs::Trigger;
  auto trigger = [this, &pnh](const char* name, Reply (SimLoop::*f)()) {
    servers_.push_back(pnh.advertiseService<Trigger::Request, Trigger::Response>(
        name, [this, f](Trigger::Request&, Trigger::Response& res) {
          return answer(res, queue_.call([f](SimLoop& s) { return (s.*f)(); }));
        }));
  };
  trigger("pause", &SimLoop::pause);
  trigger("resume", &SimLoop::resume);
  trigger("reset", &SimLoop::reset);
  // gazebo_ros's names, std_srvs/Empty: no reply to read, so a refusal is logged (answer()).
  using Empty = std_srvs::Empty;
  auto empty = [this, &pnh](const char* name, Reply (SimLoop::*f)()) {
    servers_.push_back(pnh.advertiseService<Empty::Request, Empty::Response>(
        name, [this, f, name](Empty::Request&, Empty::Response&) {
          const Reply r = queue_.call([f](SimLoop& s) { return (s.*f)(); });
          if (!r.success) MPM_SDEM_WARN_THROTTLE(1, "~%s refused: %s", name, r.message.c_str());
          return true;
        }));
  };
  empty("pause_physics", &SimLoop::pause);
  empty("unpause_physics", &SimLoop::resume);
  empty("reset_simulation", &SimLoop::reset);
  servers_.push_back(pnh.advertiseService("get_obstacle_state", &Services::getState, this));
  servers_.push_back(pnh.advertiseService("apply_obstacle_wrench", &Services::applyWrench, this));
  servers_.push_back(
      pnh.advertiseService("clear_obstacle_wrenches", &Services::clearWrenches, this));
  command_sub_ = pnh.subscribe("obstacle_cmd", 10, &Services::obstacleCommand, this);
}

bool Services::spawn(mpm_sdem::SpawnObstacle::Request& req,
                     mpm_sdem::SpawnObstacle::Response& res) {
  bool known_type = false;
  conversions::toBodyType(req.body_type, known_type);
  if (!known_type)
    return answer(res, {false, "body_type must be 0 (STATIC), 1 (KINEMATIC) or 2 (DYNAMIC), got " +
                                   std::to_string(req.body_type)});
  if (req.vertices.empty() && !(req.disk_radius >= 0))
    return answer(res, {false, "disk_radius must be >= 0 m"});
  // Every other value is judged by the world's rules, the scene file's (blockProblem).
  const BlockDef def = conversions::toBlockDef(req);
  const std::string twist = describe(req.twist);
  return answer(res, queue_.call([def, twist](SimLoop& s) -> Reply {
    World& w = s.world();
    const Problem problem = w.placementProblem(def, s.params().allow_overlap);
    const std::string name = limits::nameProblem(def.name).empty() ? def.name : "(bad name)";
    if (!problem.empty()) return {false, "cannot spawn '" + name + "': " + inRequestTerms(problem)};
    const BlockId id = w.addBlock(def);
    // A block so light or small that its springs' stable step would stop the clock.
    if (const TimeStepChoice dt = w.chooseTimeStep(); !(dt.dt >= limits::kMinTimeStep)) {
      w.removeBlock(id);
      return {false, "cannot spawn '" + def.name + "': the time step would fall to " +
                         std::to_string(dt.dt) + " s (" + stepLimitName(dt.limit) +
                         " term); make it heavier or larger"};
    }
    s.blocksChanged();
    s.noteRequest("~spawn_obstacle '" + def.name + "' with twist " + twist);
    return {true, "spawned '" + def.name + "' at t = " + std::to_string(w.time()) + " s"};
  }));
}

bool Services::remove(mpm_sdem::RemoveObstacle::Request& req,
                      mpm_sdem::RemoveObstacle::Response& res) {
  if (const Problem p = limits::nameProblem(req.name); !p.empty())
    return answer(res, {false, "name " + p.message});
  const std::string name = req.name;
  return answer(res, queue_.call([name](SimLoop& s) -> Reply {
    const BlockId id = findBlock(s.world(), name);
    if (id.isNull()) return {false, "no block named '" + name + "'"};
    if (const std::string link = s.robotLinks().linkOf(name); !link.empty())
      return {false, "'" + name + "' is the block of robot link '" + link +
                         "' (~robot_links): it follows the robot and would be spawned again; "
                         "start the node without the link to simulate without it"};
    s.world().removeBlock(id);
    s.blocksChanged();
    s.noteRequest("~remove_obstacle '" + name + "'");
    return {true, "removed '" + name + "'"};
  }));
}

bool Services::setState(mpm_sdem::SetObstacleState::Request& req,
                        mpm_sdem::SetObstacleState::Response& res) {
  if (!req.set_pose && !req.set_twist)
    return answer(res, {false, "nothing to do: set set_pose and/or set_twist"});
  if (const Problem p = limits::nameProblem(req.name); !p.empty())
    return answer(res, {false, "name " + p.message});
  const mpm_sdem::SetObstacleState::Request r = req;
  return answer(res, queue_.call([r](SimLoop& s) -> Reply {
    World& w = s.world();
    const BlockId id = findBlock(w, r.name);
    if (id.isNull()) return {false, "no block named '" + r.name + "'"};
    const BlockDef& def = w.blocks()->def(w.blocks()->indexOf(id));
    // Both checked before either is applied: a refused request changes nothing.
    if (r.set_twist) {
      const Problem p =
          twistProblem(def, Vec2(r.twist.linear.x, r.twist.linear.y), r.twist.angular.z);
      if (!p.empty())
        return {false, "cannot set the twist of '" + r.name + "': " + inRequestTerms(p)};
    }
    if (r.set_pose) {
      BlockDef moved = def;
      moved.position = Vec2(r.pose.x, r.pose.y);
      moved.angle = r.pose.theta;
      const Problem problem = w.placementProblem(moved, s.params().allow_overlap, id);
      if (!problem.empty())
        return {false, "cannot move '" + r.name + "' there: " + inRequestTerms(problem)};
      w.setBlockPose(id, moved.position, moved.angle);
    }
    if (r.set_twist) applyTwist(w, id, r.twist);
    // A moved block's frames (a static one's on /tf_static) and outline; a twist alone changes
    // neither (like ~obstacle_cmd and cmd_vel), so a replay can tell the two apart.
    if (r.set_pose) s.blocksChanged();
    s.noteRequest("~set_obstacle_state '" + r.name + "'" +
                  (r.set_twist ? " with twist " + describe(r.twist) : std::string()));
    return {true, "set the state of '" + r.name + "'"};
  }));
}

bool Services::list(mpm_sdem::ListObstacles::Request&, mpm_sdem::ListObstacles::Response& res) {
  mpm_sdem::BlockStates states;
  const Reply r = queue_.call([&states](SimLoop& s) -> Reply {
    std_msgs::Header h;
    h.stamp = conversions::toRosTime(s.world().time());
    h.frame_id = s.params().fixed_frame;
    states = conversions::toBlockStates(s.world(), h);
    return {true, std::to_string(states.blocks.size()) + " blocks"};
  });
  // The loop has run the command (or refused it without touching states) before call returns.
  res.states = states;
  return answer(res, r);
}

bool Services::step(mpm_sdem::StepSimulation::Request& req,
                    mpm_sdem::StepSimulation::Response& res) {
  if (req.steps < 1 || req.steps > 1000000)
    return answer(res, {false, "steps must be 1 to 1000000, got " + std::to_string(req.steps)});
  const long n = req.steps;
  std::uint64_t step = 0;  // where the steps start: the loop takes them after this answer
  double time = 0;
  const Reply r = queue_.call([n, &step, &time](SimLoop& s) -> Reply {
    const Reply out = s.step(n);
    step = static_cast<std::uint64_t>(s.world().stepCount());
    time = s.world().time();
    return out;
  });
  res.step = step;
  res.sim_time = time;
  return answer(res, r);
}

bool Services::getState(mpm_sdem::GetObstacleState::Request& req,
                        mpm_sdem::GetObstacleState::Response& res) {
  if (const Problem p = limits::nameProblem(req.name); !p.empty())
    return answer(res, {false, "name " + p.message});
  if (!req.reference_frame.empty())
    if (const Problem p = frameProblem(req.reference_frame); !p.empty())
      return answer(res, {false, "reference_frame " + p.message});
  const std::string name = req.name, frame = req.reference_frame;
  mpm_sdem::GetObstacleState::Response out;
  const Reply r = queue_.call([&](SimLoop& s) -> Reply {
    World& w = s.world();
    const BlockId id = findBlock(w, name);
    if (id.isNull()) return {false, "no block named '" + name + "'"};
    const std::string& fixed = s.params().fixed_frame;
    std_msgs::Header h;
    h.stamp = conversions::toRosTime(w.time());
    h.frame_id = fixed;
    const mpm_sdem::RigidBlockState b =
        conversions::toBlockStates(w, h).blocks[w.blocks()->indexOf(id)];
    // The reference frame's pose in the fixed frame, from tf (latest): pose and twist into it.
    geometry_msgs::TransformStamped into;
    into.transform.rotation.w = 1;
    if (!frame.empty() && frame != fixed) {
      try {
        into = s.drivers().tf().lookupTransform(frame, fixed, ros::Time(0));
      } catch (const tf2::TransformException& e) {
        return {false, "reference_frame '" + frame + "': no transform from " + fixed + " (" +
                           e.what() + ")"};
      }
    }
    out.header = h;
    out.header.frame_id = frame.empty() ? fixed : frame;
    out.state = b;
    const auto& q = into.transform.rotation;
    const auto& t = into.transform.translation;
    const tf2::Transform T(tf2::Quaternion(q.x, q.y, q.z, q.w), tf2::Vector3(t.x, t.y, t.z));
    const auto& bq = b.pose.orientation;
    const auto& bp = b.pose.position;
    const tf2::Transform pose =
        T * tf2::Transform(tf2::Quaternion(bq.x, bq.y, bq.z, bq.w), tf2::Vector3(bp.x, bp.y, bp.z));
    out.pose.position.x = pose.getOrigin().x();
    out.pose.position.y = pose.getOrigin().y();
    out.pose.position.z = pose.getOrigin().z();
    const tf2::Quaternion pq = pose.getRotation();
    out.pose.orientation.x = pq.x();
    out.pose.orientation.y = pq.y();
    out.pose.orientation.z = pq.z();
    out.pose.orientation.w = pq.w();
    // Velocities are vectors: rotated into the reference frame's axes only.
    const tf2::Vector3 v = T.getBasis() * tf2::Vector3(b.twist.linear.x, b.twist.linear.y, 0);
    const tf2::Vector3 spin = T.getBasis() * tf2::Vector3(0, 0, b.twist.angular.z);
    out.twist.linear.x = v.x(), out.twist.linear.y = v.y(), out.twist.linear.z = v.z();
    out.twist.angular.x = spin.x(), out.twist.angular.y = spin.y(), out.twist.angular.z = spin.z();
    out.wrench = conversions::toWrench(b);
    return {true, "state of '" + name + "' at t = " + std::to_string(w.time()) + " s"};
  });
  if (r.success) res = out;
  return answer(res, r);
}

bool Services::applyWrench(mpm_sdem::ApplyObstacleWrench::Request& req,
                           mpm_sdem::ApplyObstacleWrench::Response& res) {
  if (const Problem p = limits::nameProblem(req.name); !p.empty())
    return answer(res, {false, "name " + p.message});
  const geometry_msgs::Wrench& wr = req.wrench;
  const double values[] = {wr.force.x,
                           wr.force.y,
                           wr.force.z,
                           wr.torque.x,
                           wr.torque.y,
                           wr.torque.z,
                           req.reference_point.x,
                           req.reference_point.y,
                           req.duration};
  for (double v : values)
    if (!std::isfinite(v)) return answer(res, {false, "every number must be finite"});
  if (wr.force.z != 0 || wr.torque.x != 0 || wr.torque.y != 0)
    return answer(res, {false,
                        "wrench.force.z, torque.x and torque.y must be 0: the simulation is the "
                        "x-y plane (a load out of it does nothing)"});
  if (req.duration == 0)
    return answer(res, {false, "duration must be > 0 s, or < 0 to hold until cleared"});
  const mpm_sdem::ApplyObstacleWrench::Request r = req;
  return answer(res, queue_.call([r](SimLoop& s) -> Reply {
    const Reply out =
        s.drivers().addLoad(s.world(), r.name, Vec2(r.wrench.force.x, r.wrench.force.y),
                            Vec2(r.reference_point.x, r.reference_point.y), r.in_block_frame,
                            r.wrench.torque.z, r.duration);
    if (out.success) s.noteRequest("~apply_obstacle_wrench on '" + r.name + "'");
    return out;
  }));
}

bool Services::clearWrenches(mpm_sdem::ClearObstacleWrenches::Request& req,
                             mpm_sdem::ClearObstacleWrenches::Response& res) {
  if (!req.name.empty())
    if (const Problem p = limits::nameProblem(req.name); !p.empty())
      return answer(res, {false, "name " + p.message});
  const std::string name = req.name;
  return answer(res, queue_.call([name](SimLoop& s) -> Reply {
    return s.drivers().clearLoads(s.world(), name);
  }));
}

void Services::obstacleCommand(const mpm_sdem::ObstacleCommand::ConstPtr& msg) {
  if (const Problem p = limits::nameProblem(msg->name); !p.empty()) {
    MPM_SDEM_WARN_THROTTLE(1, "~obstacle_cmd ignored: name %s", p.message.c_str());
    return;
  }
  const std::string name = msg->name;
  const geometry_msgs::Twist twist = msg->twist;
  queue_.post([name, twist](SimLoop& s) -> Reply {
    const BlockId id = findBlock(s.world(), name);
    const Reply r = id.isNull() ? Reply{false, "no block named '" + name + "'"}
                                : applyTwist(s.world(), id, twist);
    if (!r.success)
      MPM_SDEM_WARN_THROTTLE(1, "~obstacle_cmd ignored: %s", r.message.c_str());
    else
      s.noteRequest("~obstacle_cmd '" + name + "' twist " + describe(twist));
    return r;
  });
}

}  // namespace mpm_sdem::node
