#include "mpm_sdem/ros/recorded_commands.hpp"

#include <mpm_sdem/RecordedCommand.h>
#include <rosbag/bag.h>
#include <rosbag/query.h>
#include <rosbag/view.h>

#include <algorithm>
#include <stdexcept>

#include "mpm_sdem/ros/conversions.hpp"

namespace mpm_sdem {

std::vector<WorldCommand> readRecordedCommands(const std::string& path, Real from, Real to) {
  std::vector<WorldCommand> out;
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
    const std::string type = ros::message_traits::DataType<mpm_sdem::RecordedCommand>::value();
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TypeQuery(type))) {
      const auto msg = m.instantiate<mpm_sdem::RecordedCommand>();
      // Kinds a later build may add are not this build's to apply.
      if (!msg || msg->kind > mpm_sdem::RecordedCommand::SET_GRAVITY) continue;
      if (msg->time >= from && msg->time <= to) out.push_back(conversions::fromMsg(*msg));
    }
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot read the bag " + path + ": " + e.what());
  }
  std::stable_sort(out.begin(), out.end(), [](const WorldCommand& a, const WorldCommand& b) {
    return a.sequence < b.sequence;
  });
  return out;
}

}  // namespace mpm_sdem
