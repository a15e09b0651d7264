// Core state <-> ROS messages, as free functions (the grid_map convention). Used by the node, the
// bag recorder and the headless runner; the core itself never sees a ROS type.
#pragma once

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Wrench.h>
#include <mpm_sdem/BlockDefinition.h>
#include <mpm_sdem/BlockStates.h>
#include <mpm_sdem/RecordedCommand.h>
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
// The rotation about z of an orientation (rad): a planar pose's angle, or the heading of a 3D
// frame (a robot's link) seen from above.
Real yaw(const geometry_msgs::Quaternion& q);

// Every decimation-th material point as an unordered cloud (height 1) in the header's frame:
// float32 x, y, z (z = 0, m), vx, vy, speed (m/s), pressure (Pa, positive in compression) and
// von_mises (Pa, plane strain), uint16 material (index in the scene's materials).
void toPointCloud(const World& world, int decimation, const std_msgs::Header& header,
                  sensor_msgs::PointCloud2& cloud);

mpm_sdem::BlockStates toBlockStates(const World& world, const std_msgs::Header& header);
geometry_msgs::PoseArray toPoseArray(const mpm_sdem::BlockStates& states);
// A block's contact load (material and other blocks) as a wrench at its frame's origin in its
// own axes (geometry_msgs/WrenchStamped convention): force x, y (N/m) and torque z (N m/m),
// per metre of out-of-plane thickness.
geometry_msgs::Wrench toWrench(const mpm_sdem::RigidBlockState& block);
// One ARROW per block from its centre of mass along its contact force (material and blocks),
// metres_per_newton long per N/m, in the states' frame; DELETE for a block without load.
visualization_msgs::MarkerArray toForceArrows(const mpm_sdem::BlockStates& states,
                                              Real metres_per_newton);
// A height profile (core/terrain.hpp) as a cloud of one point per column: float32 x (the
// column's centre), y (the height; NaN for an empty column), z = 0, in the header's frame.
void toTerrainCloud(const std::vector<Real>& height, Real x0, Real dx,
                    const std_msgs::Header& header, sensor_msgs::PointCloud2& cloud);
// One transform per block of the kind asked for: header frame -> "<prefix>/<name>" (prefix may
// be empty). Static blocks belong on /tf_static, the others on /tf.
enum class Frames { kStatic, kMoving };
std::vector<geometry_msgs::TransformStamped> toTransforms(const mpm_sdem::BlockStates& states,
                                                          const std::string& prefix, Frames which);
// The domain's frame, "<prefix>/domain": its lower-left corner, axes of the header's frame. On
// /tf_static from the start, so the fixed frame exists for tf listeners (rviz) in every scene.
geometry_msgs::TransformStamped domainTransform(const World& world, const std_msgs::Header& header,
                                                const std::string& prefix);
std::string blockFrame(const std::string& prefix, const std::string& name);

// A LINE_STRIP per block (per disc of a cluster) tracing its rounded outline, posed at the
// block's frame in the header's (fixed) frame, and its name just above it; line width and
// text size in proportion to the domain. DELETEALL first removes blocks that disappeared. In the
// fixed frame, not the blocks' tf frames: rviz draws them without tf (a late rviz while paused).
visualization_msgs::MarkerArray toMarkers(const World& world, const std_msgs::Header& header);
// The FEM bodies' triangles as one TRIANGLE_LIST in the header's (fixed) frame, each coloured by
// its von Mises stress on a fixed scale: blue at 0 to red at 1% of its body's Young's modulus
// (the stress of 1% strain) and beyond; the same colours in every message.
visualization_msgs::Marker toFemMarker(const World& world, const std_msgs::Header& header);
// The FEM bodies' nodes as an unordered cloud in the header's frame: float32 x, y, z (z = 0, m),
// ux, uy (displacement from the reference mesh, m), vx, vy (m/s), von_mises (Pa, the mean of
// the node's triangles), uint16 body (index in the scene's fem_bodies).
void toFemCloud(const World& world, const std_msgs::Header& header,
                sensor_msgs::PointCloud2& cloud);

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

// A world command for bags and back, exact (record_conversions.cpp). fromMsg of a definition
// with an unknown body type gives a static block (the world then checks the definition).
mpm_sdem::RecordedCommand toMsg(const WorldCommand& command, const std::string& frame);
WorldCommand fromMsg(const mpm_sdem::RecordedCommand& msg);
mpm_sdem::BlockDefinition toMsg(const BlockDef& def);
BlockDef fromMsg(const mpm_sdem::BlockDefinition& msg);

}  // namespace mpm_sdem::conversions
