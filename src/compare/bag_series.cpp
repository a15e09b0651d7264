#include "bag_series.hpp"

#include <mpm_sdem/SimStats.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <stdexcept>

namespace mpm_sdem::compare {

RunSeries readRun(const std::string& path) {
  RunSeries run;
  run.path = path;
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(path + ": " + e.what() +
                             (path.size() > 7 && path.substr(path.size() - 7) == ".active"
                                  ? " (an unfinished bag: run `rosbag reindex` on it first)"
                                  : ""));
  }
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    if (auto b = m.instantiate<mpm_sdem::BlockStates>()) {
      run.blocks.push_back(*b);
    } else if (auto c = m.instantiate<sensor_msgs::PointCloud2>()) {
      const std::string& topic = m.getTopic();
      const bool fem =
          topic.size() >= 10 && topic.compare(topic.size() - 10, 10, "/fem_nodes") == 0;
      Cloud cloud;
      cloud.time = c->header.stamp.toSec();
      cloud.xy.reserve(2 * c->width * c->height);
      for (sensor_msgs::PointCloud2ConstIterator<float> it(*c, "x"); it != it.end(); ++it) {
        cloud.xy.push_back(it[0]);
        cloud.xy.push_back(it[1]);
      }
      bool has_kind = false;  // bags recorded before SPH particles existed have no kind
      for (const sensor_msgs::PointField& f : c->fields) has_kind = has_kind || f.name == "kind";
      if (has_kind) {
        std::size_t k = 0;
        for (sensor_msgs::PointCloud2ConstIterator<std::uint8_t> it(*c, "kind"); it != it.end();
             ++it, k += 2) {
          if (*it != 1) continue;
          cloud.sph_xy.push_back(cloud.xy[k]);
          cloud.sph_xy.push_back(cloud.xy[k + 1]);
        }
      }
      (fem ? run.fem_nodes : run.clouds).push_back(std::move(cloud));
    } else if (auto s = m.instantiate<mpm_sdem::SimStats>()) {
      run.energy.push_back({s->header.stamp.toSec(), s->total_energy, s->kinetic_energy});
    }
  }
  if (run.blocks.empty() && run.clouds.empty())
    throw std::runtime_error(path +
                             ": no mpm_sdem/BlockStates or sensor_msgs/PointCloud2 "
                             "messages; is it a bag recorded by mpm_sdem?");
  return run;
}

}  // namespace mpm_sdem::compare
