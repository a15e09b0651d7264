#include "mpm_sdem/robot/robot_obstacles.hpp"

#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/robot/mesh_hull.hpp"
#include "mpm_sdem/robot/plane_section.hpp"

namespace mpm_sdem::robot {

namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(p.position.x, p.position.y, p.position.z));
  t.rotate(Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z));
  return t;
}

// The solid of a collision element, or a RobotError naming the link.
Solid solidOf(const urdf::Geometry& g, const std::string& link, const MeshPath& mesh_path) {
  Solid s;
  switch (g.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(g);
      s.kind = Solid::Kind::kBox;
      s.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      return s;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(g);
      s.kind = Solid::Kind::kCylinder;
      s.radius = cylinder.radius;
      s.length = cylinder.length;
      return s;
    }
    case urdf::Geometry::SPHERE:
      s.kind = Solid::Kind::kSphere;
      s.radius = static_cast<const urdf::Sphere&>(g).radius;
      return s;
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(g);
      s.kind = Solid::Kind::kConvex;
      std::string file;
      try {
        file = mesh_path(mesh.filename);
        s.corners =
            meshHullCorners(file, Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
      } catch (const std::exception& e) {  // RobotError from mesh_path, runtime_error
        // The URI as the description writes it, when it named another file.
        const std::string uri =
            file.empty() || file == mesh.filename ? "" : "(" + mesh.filename + ") ";
        throw RobotError("link '" + link + "': its collision " + uri + e.what());
      }
      return s;
    }
    default:
      throw RobotError("link '" + link + "': its collision geometry is of an unknown kind");
  }
}

// A convex polygon with at most `n` corners: the corner whose removal loses the least area
// goes first, until that many are left.
void keepCorners(std::vector<Vec2>& polygon, std::size_t n) {
  while (polygon.size() > n) {
    std::size_t best = 0;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Vec2& a = polygon[(i + polygon.size() - 1) % polygon.size()];
      const Vec2& b = polygon[i];
      const Vec2& c = polygon[(i + 1) % polygon.size()];
      const Vec2 ab = b - a, ac = c - a;
      const double area = std::abs(ab.x() * ac.y() - ab.y() * ac.x());
      if (area < least) least = area, best = i;
    }
    polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(best));
  }
}

}  // namespace

std::string meshFilePath(const std::string& uri) {
  const std::string file = "file://", package = "package://";
  if (uri.compare(0, file.size(), file) == 0) return uri.substr(file.size());
  if (uri.compare(0, package.size(), package) == 0)
    throw RobotError("mesh '" + uri +
                     "' is in a ROS package, which only the node can find (give the file's path)");
  return uri;
}

RobotDescription::RobotDescription(const std::string& urdf_xml, MeshPath mesh_path)
    : mesh_path_(std::move(mesh_path)) {
  model_ = urdf::parseURDF(urdf_xml);
  if (!model_)
    throw RobotError(
        "the robot description is not valid URDF (urdfdom's parser refused it; its message is "
        "on the console)");
}

const std::string& RobotDescription::name() const {
  return model_->getName();
}

Eigen::Isometry3d RobotDescription::restPose(const std::string& link) const {
  urdf::LinkConstSharedPtr l = model_->getLink(link);
  if (!l) throw RobotError("link '" + link + "' is not in the robot description");
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (; l->parent_joint; l = l->getParent())
    t = toIsometry(l->parent_joint->parent_to_joint_origin_transform) * t;
  return t;
}

// A collision solid and where it sits in its link's frame.
struct RobotDescription::Collision {
  Solid solid;
  Eigen::Isometry3d origin;
};

// A link's collision elements with geometry; RobotError naming it when it has none, the
// description lacks it or a solid cannot be made.
std::vector<RobotDescription::Collision> RobotDescription::collisionsOf(
    const std::string& name) const {
  urdf::LinkConstSharedPtr link = model_->getLink(name);
  if (!link)
    throw RobotError("link '" + name + "' is not in the robot description of '" +
                     model_->getName() + "'");
  std::vector<urdf::CollisionSharedPtr> elements;
  for (const urdf::CollisionSharedPtr& c : link->collision_array)
    if (c && c->geometry) elements.push_back(c);
  if (elements.empty() && link->collision && link->collision->geometry)
    elements.push_back(link->collision);
  if (elements.empty())
    throw RobotError("link '" + name + "' has no collision geometry to meet the material");
  std::vector<Collision> out;
  for (const urdf::CollisionSharedPtr& c : elements)
    out.push_back({solidOf(*c->geometry, name, mesh_path_), toIsometry(c->origin)});
  return out;
}

void RobotDescription::check(const RobotObstaclesDef& def) const {
  for (const std::string& name : def.links) collisionsOf(name);
}

std::vector<LinkBlock> RobotDescription::obstacles(const RobotObstaclesDef& def,
                                                   const LinkPose& pose) const {
  std::vector<LinkBlock> out;
  for (const std::string& name : def.links) {
    const std::vector<Collision> collisions = collisionsOf(name);
    const Eigen::Isometry3d frame = pose(name);
    // The link's frame as follow_tf sees it: its origin and its yaw in the plane.
    const Vec2 origin(frame.translation().x(), frame.translation().y());
    const double angle = std::atan2(frame.linear()(1, 0), frame.linear()(0, 0));
    double nearest = std::numeric_limits<double>::infinity();
    int made = 0;
    for (const Collision& c : collisions) {
      Section section = sectionByPlane(c.solid, frame * c.origin);
      if (section.empty()) {
        nearest = std::min(nearest, section.gap);
        continue;
      }
      keepCorners(section.polygon, kMaxBlockVertices);
      LinkBlock b;
      b.link = name;
      b.block.name = made == 0 ? name : name + "_" + std::to_string(made + 1);
      b.block.type = BodyType::kKinematic;
      b.block.friction = def.friction;
      b.block.position = origin;
      b.block.angle = angle;
      outlineInFrame(section, origin, angle, def.rounding, b.block);
      if (const Problem p = coreProblem(b.block.core); !p.empty())
        throw RobotError("link '" + name + "': its section by the plane makes no block (" +
                         p.message + ")");
      out.push_back(std::move(b));
      ++made;
    }
    if (made == 0) {
      char gap[64];
      std::snprintf(gap, sizeof gap, "%.4g m", nearest);
      throw RobotError("link '" + name +
                       "': its collision geometry does not cross the simulation plane (z = 0 of "
                       "the fixed frame; the nearest solid stays " +
                       gap + " from it)");
    }
  }
  return out;
}

}  // namespace mpm_sdem::robot
