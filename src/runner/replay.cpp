#include "replay.hpp"

#include <mpm_sdem/RecordedCommand.h>
#include <rosbag/bag.h>
#include <rosbag/query.h>
#include <rosbag/view.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "mpm_sdem/ros/conversions.hpp"

namespace mpm_sdem::runner {

CommandReplay::CommandReplay(const std::string& path, Real start) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
    const std::string type = ros::message_traits::DataType<mpm_sdem::RecordedCommand>::value();
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TypeQuery(type))) {
      const auto msg = m.instantiate<mpm_sdem::RecordedCommand>();
      if (!msg || msg->kind > mpm_sdem::RecordedCommand::ADD_LOAD) continue;
      if (msg->time >= start) commands_.push_back(conversions::fromMsg(*msg));
    }
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot read the bag " + path + ": " + e.what());
  }
  std::stable_sort(
      commands_.begin(), commands_.end(),
      [](const WorldCommand& a, const WorldCommand& b) { return a.sequence < b.sequence; });
}

bool CommandReplay::applyDue(World& world) {
  bool changed = false;
  for (; next_ < commands_.size() && commands_[next_].time <= world.time(); ++next_) {
    const WorldCommand& c = commands_[next_];
    const std::string problem = applyCommand(world, c);
    if (problem.empty()) {
      ++applied_;
      changed = changed || c.kind == WorldCommand::Kind::kAddBlock ||
                c.kind == WorldCommand::Kind::kRemoveBlock ||
                c.kind == WorldCommand::Kind::kSetPose;
      continue;
    }
    if (skipped_++ < 10)
      std::fprintf(stderr, "\nwarning: command %ld (t = %.6g s) not applied: %s\n", c.sequence,
                   c.time, problem.c_str());
  }
  return changed;
}

}  // namespace mpm_sdem::runner
