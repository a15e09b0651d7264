/// @file
/// A robot's links as kinematic blocks in the simulation plane (as gazebo_ros's spawn_model
/// -urdf makes a robot's links bodies): each chosen link's collision solids (URDF box, cylinder,
/// sphere, a mesh's convex hull) cut by the plane z = 0 of the simulation's fixed frame, one block
/// per solid that crosses it, in the link's frame as projected on the plane, so that the node's
/// follow_tf moves it with the link. No ROS: the description is URDF text, the links' poses come
/// from the caller (tf in the node; restPose in tests and for a description read from a file).
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"

namespace urdf {
class ModelInterface;
}

namespace mpm_sdem::robot {

/// A description or a link that cannot become blocks; the message names the link.
class RobotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Which links become blocks and how they meet the material and the other blocks.
struct RobotObstaclesDef {
  std::vector<std::string> links;  ///< the links to cut by the plane (names in the description)
  double rounding = 0.002;         ///< m: a section's corners are rounded by at most this
  double friction = 0.5;           ///< Coulomb coefficient with the material and the blocks
};

/// A block made from a link: the link's name and the block (named after the link, with _2,
/// _3, ... for a link's second and further solids).
struct LinkBlock {
  std::string link;
  BlockDef block;
};

/// A link's frame in the plane's frame (the simulation's fixed frame, its x-y plane the
/// simulation's).
using LinkPose = std::function<Eigen::Isometry3d(const std::string& link)>;

/// A mesh's URI as written in a description (package://pkg/file, file:///file or a path) as the
/// path of a file to read; throws RobotError when it cannot tell (the message is put after the
/// link's name).
using MeshPath = std::function<std::string(const std::string& uri)>;

/// The default MeshPath, without ROS: file:// URIs and paths as they are; package:// refused
/// (the node resolves those through the ROS package path).
std::string meshFilePath(const std::string& uri);

/// A parsed URDF robot description.
class RobotDescription {
 public:
  /// Parses URDF text; throws RobotError when it is not a valid description. Collision meshes
  /// are read (mesh_hull.hpp) from the files `mesh_path` names.
  explicit RobotDescription(const std::string& urdf_xml, MeshPath mesh_path = meshFilePath);
  /// The robot's name.
  const std::string& name() const;
  /// A link's frame in its root link's frame with every joint at zero; throws RobotError for a
  /// link the description does not have.
  Eigen::Isometry3d restPose(const std::string& link) const;
  /// Throws RobotError, naming the link, for a chosen link that is not in the description, has
  /// no collision geometry, or a mesh that cannot be read or spans no volume: what can be told
  /// before the links' poses are known.
  void check(const RobotObstaclesDef& def) const;
  /// The chosen links' blocks, with each link at `pose(link)`. Throws RobotError as check(), and
  /// for a link whose solids all miss the plane (with how far the nearest stays from it). Solids of
  /// a link that miss the plane are skipped when another crosses it. A section with more corners
  /// than a block may have (kMaxBlockVertices) loses the corners whose removal loses the least
  /// area.
  std::vector<LinkBlock> obstacles(const RobotObstaclesDef& def, const LinkPose& pose) const;

 private:
  struct Collision;
  std::vector<Collision> collisionsOf(const std::string& link) const;
  std::shared_ptr<urdf::ModelInterface> model_;
  MeshPath mesh_path_;
};

}  // namespace mpm_sdem::robot
