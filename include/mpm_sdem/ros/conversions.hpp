// Core state <-> ROS messages, as free functions (the grid_map convention). Used by the node, the
// bag recorder and the headless runner; the core itself never sees a ROS type.
#pragma once

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <mpm_sdem/BlockStates.h>
#include <mpm_sdem/SimStats.h>
#include <mpm_sdem/SpawnObstacle.h>
#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::conversions {

// Simulation time (s) as a ROS stamp.
ros::Time toRosTime(Real t);

// Every decimation-th material point as an unordered cloud (height 1) in the header's frame:
// float32 x, y, z (z = 0, m), vx, vy (m/s), pressure (Pa, positive in compression) and
// von_mises (Pa, plane strain), uint16 material (index in the scene's materials).
void toPointCloud(const World& world, int decimation, const std_msgs::Header& header,
                  sensor_msgs::PointCloud2& cloud);

mpm_sdem::BlockStates toBlockStates(const World& world, const std_msgs::Header& header);
geometry_msgs::PoseArray toPoseArray(const mpm_sdem::BlockStates& states);
// One transform per block: header frame -> "<prefix>/<name>" (prefix may be empty).
std::vector<geometry_msgs::TransformStamped> toTransforms(const mpm_sdem::BlockStates& states,
                                                          const std::string& prefix);
std::string blockFrame(const std::string& prefix, const std::string& name);

// A LINE_STRIP per block tracing its rounded outline in the block's own tf frame (frame_locked,
// so rviz moves it with tf), plus a text label. Blocks that disappeared get DELETEALL first.
// The FEM bodies' triangles as one TRIANGLE_LIST in the header's (fixed) frame, each coloured by
// its von Mises stress on a fixed scale: blue at 0 to red at 1% of its body's Young's modulus
// (the stress of 1% strain) and beyond; the same colours in every message.
visualization_msgs::Marker toFemMarker(const World& world, const std_msgs::Header& header);
// The FEM bodies' nodes as an unordered cloud in the header's frame: float32 x, y, z (z = 0, m),
// ux, uy (displacement from the reference mesh, m), vx, vy (m/s), von_mises (Pa, the mean of
// the node's triangles), uint16 body (index in the scene's fem_bodies).
void toFemCloud(const World& world, const std_msgs::Header& header,
                sensor_msgs::PointCloud2& cloud);

visualization_msgs::MarkerArray toMarkers(const World& world, const std::string& tf_prefix,
                                          const ros::Time& stamp);

struct StatsInput {
  TimeStepChoice dt;
  Real real_time_factor = 0;
  bool paused = false;
  Profile profile;  // stage seconds and steps since the last message
};
mpm_sdem::SimStats toStats(const World& world, const Diagnostics& d, const StatsInput& in,
                           const std_msgs::Header& header);

// A spawn request as a block definition; the world's placementProblem judges the values. An
// unknown body_type comes out as static: check it with toBodyType first.
BlockDef toBlockDef(const mpm_sdem::SpawnObstacle::Request& req);
BodyType toBodyType(std::uint8_t type, bool& ok);
std::uint8_t fromBodyType(BodyType type);

}  // namespace mpm_sdem::conversions
