#include "services.hpp"

#include <cmath>

#include "mpm_sdem/ros/conversions.hpp"
#include "sim_loop.hpp"

namespace mpm_sdem::node {

namespace {

template <class Res>
bool answer(Res& res, const Reply& r) {
  res.success = r.success;
  res.message = r.message;
  if (!r.success) ROS_WARN("request refused: %s", r.message.c_str());
  return true;  // the call itself succeeded; success says whether the request did
}

bool finite(double v) {
  return std::isfinite(v);
}
bool finitePose(const geometry_msgs::Pose2D& p) {
  return finite(p.x) && finite(p.y) && finite(p.theta);
}
bool finiteTwist(const geometry_msgs::Twist& t) {
  return finite(t.linear.x) && finite(t.linear.y) && finite(t.angular.z);
}

// Sets a block's velocity from a twist of its frame origin, refusing a static block.
Reply applyTwist(World& w, int i, const geometry_msgs::Twist& t) {
  if (w.blocks()->def(i).type == BodyType::kStatic)
    return {false, "block '" + w.blocks()->def(i).name +
                       "' is static and cannot move; spawn it kinematic to command its twist"};
  w.blocks()->setVelocity(i, Vec2(t.linear.x, t.linear.y), t.angular.z);
  return {true, ""};
}

int findBlock(World& w, const std::string& name) {
  return w.blocks() ? w.blocks()->find(name) : -1;
}

}  // namespace

Services::Services(ros::NodeHandle& pnh, CommandQueue& queue) : queue_(queue) {
  servers_.push_back(pnh.advertiseService("spawn_obstacle", &Services::spawn, this));
  servers_.push_back(pnh.advertiseService("remove_obstacle", &Services::remove, this));
  servers_.push_back(pnh.advertiseService("set_obstacle_state", &Services::setState, this));
  servers_.push_back(pnh.advertiseService("list_obstacles", &Services::list, this));
  servers_.push_back(pnh.advertiseService("step", &Services::step, this));
  using Trigger = std_srvs::Trigger;
  auto trigger = [this, &pnh](const char* name, Reply (Simulation::*f)()) {
    servers_.push_back(pnh.advertiseService<Trigger::Request, Trigger::Response>(
        name, [this, f](Trigger::Request&, Trigger::Response& res) {
          return answer(res, queue_.call([f](Simulation& s) { return (s.*f)(); }));
        }));
  };
  trigger("pause", &Simulation::pause);
  trigger("resume", &Simulation::resume);
  trigger("reset", &Simulation::reset);
  command_sub_ = pnh.subscribe("obstacle_cmd", 10, &Services::obstacleCommand, this);
}

bool Services::spawn(mpm_sdem::SpawnObstacle::Request& req,
                     mpm_sdem::SpawnObstacle::Response& res) {
  bool known_type = false;
  conversions::toBodyType(req.body_type, known_type);
  if (!known_type)
    return answer(res, {false, "body_type must be 0 (STATIC), 1 (KINEMATIC) or 2 (DYNAMIC), got " +
                                   std::to_string(req.body_type)});
  if (req.name.empty() || req.name.find_first_of(" /") != std::string::npos)
    return answer(res, {false,
                        "name must be non-empty, without spaces or '/' (it names a tf "
                        "frame), got '" +
                            req.name + "'"});
  if (!finitePose(req.pose) || !finiteTwist(req.twist) || !finite(req.rounding) ||
      !finite(req.disk_radius) || !finite(req.density) || !finite(req.friction) ||
      !finite(req.restitution))
    return answer(res, {false, "every number must be finite (no NaN or infinity)"});
  if (req.vertices.empty() && !(req.disk_radius >= 0))
    return answer(res, {false, "disk_radius must be >= 0 m"});
  const BlockDef def = conversions::toBlockDef(req);
  const std::string shape = coreProblem(def.core);
  if (!shape.empty()) return answer(res, {false, "vertices: " + shape});
  return answer(res, queue_.call([def](Simulation& s) -> Reply {
    World& w = s.world();
    const std::string problem = w.placementProblem(def, s.params().allow_overlap);
    if (!problem.empty()) return {false, "cannot spawn '" + def.name + "': " + problem};
    w.addBlock(def);
    s.blocksChanged();
    return {true, "spawned '" + def.name + "' at t = " + std::to_string(w.time()) + " s"};
  }));
}

bool Services::remove(mpm_sdem::RemoveObstacle::Request& req,
                      mpm_sdem::RemoveObstacle::Response& res) {
  const std::string name = req.name;
  return answer(res, queue_.call([name](Simulation& s) -> Reply {
    const int i = findBlock(s.world(), name);
    if (i < 0) return {false, "no block named '" + name + "'"};
    s.world().removeBlock(i);
    s.blocksChanged();
    return {true, "removed '" + name + "'"};
  }));
}

bool Services::setState(mpm_sdem::SetObstacleState::Request& req,
                        mpm_sdem::SetObstacleState::Response& res) {
  if (!req.set_pose && !req.set_twist)
    return answer(res, {false, "nothing to do: set set_pose and/or set_twist"});
  if ((req.set_pose && !finitePose(req.pose)) || (req.set_twist && !finiteTwist(req.twist)))
    return answer(res, {false, "pose and twist must be finite (no NaN or infinity)"});
  const mpm_sdem::SetObstacleState::Request r = req;
  return answer(res, queue_.call([r](Simulation& s) -> Reply {
    World& w = s.world();
    const int i = findBlock(w, r.name);
    if (i < 0) return {false, "no block named '" + r.name + "'"};
    if (r.set_twist && w.blocks()->def(i).type == BodyType::kStatic)
      return applyTwist(w, i, r.twist);  // refused, before any change
    if (r.set_pose) {
      BlockDef moved = w.blocks()->def(i);
      moved.position = Vec2(r.pose.x, r.pose.y);
      moved.angle = r.pose.theta;
      const std::string problem = w.placementProblem(moved, s.params().allow_overlap, i);
      if (!problem.empty()) return {false, "cannot move '" + r.name + "' there: " + problem};
      w.blocks()->setPose(i, moved.position, moved.angle);
    }
    if (r.set_twist) applyTwist(w, i, r.twist);
    s.blocksChanged();
    return {true, "set the state of '" + r.name + "'"};
  }));
}

bool Services::list(mpm_sdem::ListObstacles::Request&, mpm_sdem::ListObstacles::Response& res) {
  mpm_sdem::BlockStates states;
  const Reply r = queue_.call([&states](Simulation& s) -> Reply {
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
  std::uint64_t step = 0;
  double time = 0;
  const Reply r = queue_.call([n, &step, &time](Simulation& s) -> Reply {
    const Reply out = s.step(n);
    step = static_cast<std::uint64_t>(s.world().stepCount());
    time = s.world().time();
    return out;
  });
  res.step = step;
  res.sim_time = time;
  return answer(res, r);
}

void Services::obstacleCommand(const mpm_sdem::ObstacleCommand::ConstPtr& msg) {
  if (!finiteTwist(msg->twist)) {
    ROS_WARN_THROTTLE(1, "~obstacle_cmd for '%s' ignored: the twist is not finite",
                      msg->name.c_str());
    return;
  }
  const std::string name = msg->name;
  const geometry_msgs::Twist twist = msg->twist;
  queue_.post([name, twist](Simulation& s) -> Reply {
    const int i = findBlock(s.world(), name);
    const Reply r =
        i < 0 ? Reply{false, "no block named '" + name + "'"} : applyTwist(s.world(), i, twist);
    if (!r.success) ROS_WARN_THROTTLE(1, "~obstacle_cmd ignored: %s", r.message.c_str());
    return r;
  });
}

}  // namespace mpm_sdem::node
