#include "mpm_sdem/ros/conversions.hpp"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mpm_sdem/core/mpm/constitutive.hpp"

namespace mpm_sdem::conversions {

namespace {

geometry_msgs::Pose planarPose(const Vec2& p, Real angle) {
  geometry_msgs::Pose pose;
  pose.position.x = p.x();
  pose.position.y = p.y();
  pose.orientation.z = std::sin(0.5 * angle);
  pose.orientation.w = std::cos(0.5 * angle);
  return pose;
}

}  // namespace

ros::Time toRosTime(Real t) {
  return ros::Time(t);
}

Real yaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

void toPointCloud(const World& world, int decimation, const std_msgs::Header& header,
                  sensor_msgs::PointCloud2& cloud) {
  const Particles& P = world.particles();
  const std::size_t step = static_cast<std::size_t>(std::max(1, decimation));
  const std::size_t n = (P.size() + step - 1) / step;
  cloud.header = header;
  sensor_msgs::PointCloud2Modifier mod(cloud);
  mod.setPointCloud2Fields(
      10, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z",
      1, sensor_msgs::PointField::FLOAT32, "vx", 1, sensor_msgs::PointField::FLOAT32, "vy", 1,
      sensor_msgs::PointField::FLOAT32, "speed", 1, sensor_msgs::PointField::FLOAT32, "pressure", 1,
      sensor_msgs::PointField::FLOAT32, "von_mises", 1, sensor_msgs::PointField::FLOAT32,
      "material", 1, sensor_msgs::PointField::UINT16, "kind", 1, sensor_msgs::PointField::UINT8);
  mod.resize(n);  // height 1, width n, dense
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), vx(cloud, "vx"), p(cloud, "pressure");
  sensor_msgs::PointCloud2Iterator<std::uint16_t> mat(cloud, "material");
  sensor_msgs::PointCloud2Iterator<std::uint8_t> kind(cloud, "kind");  // 0 material point, 1 SPH
  for (std::size_t i = 0; i < P.size(); i += step, ++x, ++vx, ++p, ++mat, ++kind) {
    x[0] = static_cast<float>(P.x[i]);
    x[1] = static_cast<float>(P.y[i]);
    x[2] = 0.f;
    vx[0] = static_cast<float>(P.vx[i]);
    vx[1] = static_cast<float>(P.vy[i]);
    vx[2] = static_cast<float>(std::hypot(P.vx[i], P.vy[i]));  // rviz colours by one field
    const Stress s{P.sxx[i], P.syy[i], P.sxy[i], P.szz[i]};
    p[0] = static_cast<float>(pressure(s));
    p[1] = static_cast<float>(vonMises(s));
    *mat = P.material[i];
    *kind = P.kind[i];
  }
}

std::uint8_t fromBodyType(BodyType type) {
  switch (type) {
    case BodyType::kStatic:
      return mpm_sdem::RigidBlockState::STATIC;
    case BodyType::kKinematic:
      return mpm_sdem::RigidBlockState::KINEMATIC;
    case BodyType::kDynamic:
      return mpm_sdem::RigidBlockState::DYNAMIC;
  }
  return mpm_sdem::RigidBlockState::STATIC;
}

BodyType toBodyType(std::uint8_t type, bool& ok) {
  ok = true;
  switch (type) {
    case mpm_sdem::RigidBlockState::STATIC:
      return BodyType::kStatic;
    case mpm_sdem::RigidBlockState::KINEMATIC:
      return BodyType::kKinematic;
    case mpm_sdem::RigidBlockState::DYNAMIC:
      return BodyType::kDynamic;
  }
  ok = false;
  return BodyType::kStatic;
}

mpm_sdem::BlockStates toBlockStates(const World& world, const std_msgs::Header& header) {
  mpm_sdem::BlockStates out;
  out.header = header;
  const Blocks* B = world.blocks();
  if (!B) return out;
  out.blocks.resize(B->count());
  for (int i = 0; i < B->count(); ++i) {
    mpm_sdem::RigidBlockState& m = out.blocks[i];
    const BlockState& s = B->state(i);
    const Vec2 origin = B->origin(i);
    m.id = static_cast<std::uint32_t>(i);
    m.name = B->def(i).name;
    m.body_type = fromBodyType(B->def(i).type);
    m.pose = planarPose(origin, s.angle);
    const Vec2 v = B->velocityAt(B->firstShape(i), origin);  // a shape's, any of the block's
    m.twist.linear.x = v.x();
    m.twist.linear.y = v.y();
    m.twist.angular.z = s.angular_velocity;
    m.center_of_mass.x = s.position.x();
    m.center_of_mass.y = s.position.y();
    const Blocks::Load& c = B->coupling()[i];
    m.coupling_force.x = c.force.x();
    m.coupling_force.y = c.force.y();
    m.coupling_torque = c.torque;
    m.contact_count = static_cast<std::uint32_t>(c.contacts);
    const Blocks::Load& k = B->blockContact(i);
    m.block_force.x = k.force.x();
    m.block_force.y = k.force.y();
    m.block_torque = k.torque;
    m.block_contact_count = static_cast<std::uint32_t>(k.contacts);
  }
  return out;
}

geometry_msgs::Wrench toWrench(const mpm_sdem::RigidBlockState& b) {
  // About the frame's origin instead of the centre of mass, then in the block's axes.
  const Vec2 f(b.coupling_force.x + b.block_force.x, b.coupling_force.y + b.block_force.y);
  const Vec2 r(b.center_of_mass.x - b.pose.position.x, b.center_of_mass.y - b.pose.position.y);
  const Vec2 f_block = rotated(-yaw(b.pose.orientation), f);
  geometry_msgs::Wrench w;
  w.force.x = f_block.x();
  w.force.y = f_block.y();
  w.torque.z = b.coupling_torque + b.block_torque + cross(r, f);
  return w;
}

visualization_msgs::MarkerArray toForceArrows(const mpm_sdem::BlockStates& states,
                                              Real metres_per_newton) {
  visualization_msgs::MarkerArray out;
  for (std::size_t i = 0; i < states.blocks.size(); ++i) {
    const mpm_sdem::RigidBlockState& b = states.blocks[i];
    visualization_msgs::Marker m;
    m.header = states.header;
    m.ns = "force";
    m.id = static_cast<int>(i);
    m.type = visualization_msgs::Marker::ARROW;
    const Vec2 f(b.coupling_force.x + b.block_force.x, b.coupling_force.y + b.block_force.y);
    // A block without load has no arrow (DELETE removes the one it had).
    const Real length = f.norm() * metres_per_newton;
    m.action = length > 0 ? visualization_msgs::Marker::ADD : visualization_msgs::Marker::DELETE;
    geometry_msgs::Point from = b.center_of_mass, to = from;
    to.x += f.x() * metres_per_newton;
    to.y += f.y() * metres_per_newton;
    m.points = {from, to};
    m.pose.orientation.w = 1;
    // Shaft and head widths (m) in proportion to the arrow, within limits that stay visible.
    m.scale.x = std::clamp(0.05 * length, 0.002, 0.02);
    m.scale.y = 2 * m.scale.x;
    m.scale.z = 3 * m.scale.x;
    m.color.r = 1;
    m.color.g = 0.85f;
    m.color.a = 1;
    out.markers.push_back(m);
  }
  return out;
}

void toTerrainCloud(const std::vector<Real>& height, Real x0, Real dx,
                    const std_msgs::Header& header, sensor_msgs::PointCloud2& cloud) {
  cloud.header = header;
  sensor_msgs::PointCloud2Modifier mod(cloud);
  mod.setPointCloud2FieldsByString(1, "xyz");
  mod.resize(height.size());
  cloud.is_dense = false;  // empty columns are NaN
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  for (std::size_t c = 0; c < height.size(); ++c, ++x) {
    x[0] = static_cast<float>(x0 + (c + 0.5) * dx);
    x[1] = static_cast<float>(height[c]);
    x[2] = 0.f;
  }
}

geometry_msgs::PoseArray toPoseArray(const mpm_sdem::BlockStates& states) {
  geometry_msgs::PoseArray out;
  out.header = states.header;
  for (const auto& b : states.blocks) out.poses.push_back(b.pose);
  return out;
}

std::string blockFrame(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "/" + name;
}

std::vector<geometry_msgs::TransformStamped> toTransforms(const mpm_sdem::BlockStates& states,
                                                          const std::string& prefix, Frames which) {
  std::vector<geometry_msgs::TransformStamped> out;
  for (const auto& b : states.blocks) {
    const bool fixed = b.body_type == mpm_sdem::RigidBlockState::STATIC;
    if (fixed != (which == Frames::kStatic)) continue;
    geometry_msgs::TransformStamped t;
    t.header = states.header;
    t.child_frame_id = blockFrame(prefix, b.name);
    t.transform.translation.x = b.pose.position.x;
    t.transform.translation.y = b.pose.position.y;
    t.transform.rotation = b.pose.orientation;
    out.push_back(t);
  }
  return out;
}

geometry_msgs::TransformStamped domainTransform(const World& world, const std_msgs::Header& header,
                                                const std::string& prefix) {
  geometry_msgs::TransformStamped t;
  t.header = header;
  t.child_frame_id = blockFrame(prefix, "domain");
  t.transform.translation.x = world.def().domain.min.x();
  t.transform.translation.y = world.def().domain.min.y();
  t.transform.rotation.w = 1;
  return t;
}

visualization_msgs::Marker toFemMarker(const World& world, const std_msgs::Header& header) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = "fem";
  m.type = visualization_msgs::Marker::TRIANGLE_LIST;
  m.pose.orientation.w = 1;
  m.scale.x = m.scale.y = m.scale.z = 1;
  m.color.a = 1;
  const FemBodies* F = world.femBodies();
  if (!F) return m;
  for (int b = 0; b < F->count(); ++b) {
    const Real full = 0.01 * F->def(b).youngs_modulus;
    for (int e = F->firstElement(b); e < F->firstElement(b) + F->elementCount(b); ++e) {
      const float s =
          static_cast<float>(std::min(FemBodies::vonMises(F->stress(e)) / full, Real(1)));
      std_msgs::ColorRGBA c;
      c.r = s;
      c.g = 0.2f;
      c.b = 1 - s;
      c.a = 1;
      for (const int k : F->elementNodes(e)) {
        geometry_msgs::Point q;
        q.x = F->position(k).x();
        q.y = F->position(k).y();
        m.points.push_back(q);
        m.colors.push_back(c);
      }
    }
  }
  return m;
}

void toFemCloud(const World& world, const std_msgs::Header& header,
                sensor_msgs::PointCloud2& cloud) {
  cloud.header = header;
  sensor_msgs::PointCloud2Modifier mod(cloud);
  mod.setPointCloud2Fields(
      9, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z", 1,
      sensor_msgs::PointField::FLOAT32, "ux", 1, sensor_msgs::PointField::FLOAT32, "uy", 1,
      sensor_msgs::PointField::FLOAT32, "vx", 1, sensor_msgs::PointField::FLOAT32, "vy", 1,
      sensor_msgs::PointField::FLOAT32, "von_mises", 1, sensor_msgs::PointField::FLOAT32, "body", 1,
      sensor_msgs::PointField::UINT16);
  const FemBodies* F = world.femBodies();
  mod.resize(F ? F->totalNodes() : 0);
  if (!F) return;
  std::vector<Real> von_mises;
  F->nodalVonMises(von_mises);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), u(cloud, "ux"), v(cloud, "vx"),
      s(cloud, "von_mises");
  sensor_msgs::PointCloud2Iterator<std::uint16_t> body(cloud, "body");
  for (int b = 0; b < F->count(); ++b) {
    for (int k = F->firstNode(b); k < F->firstNode(b) + F->nodeCount(b);
         ++k, ++x, ++u, ++v, ++s, ++body) {
      const Vec2 p = F->position(k), d = p - F->reference(k), w = F->velocity(k);
      x[0] = static_cast<float>(p.x());
      x[1] = static_cast<float>(p.y());
      x[2] = 0.f;
      u[0] = static_cast<float>(d.x());
      u[1] = static_cast<float>(d.y());
      v[0] = static_cast<float>(w.x());
      v[1] = static_cast<float>(w.y());
      *s = static_cast<float>(von_mises[k]);
      *body = static_cast<std::uint16_t>(b);
    }
  }
}

visualization_msgs::MarkerArray toMarkers(const World& world, const std_msgs::Header& header) {
  visualization_msgs::MarkerArray out;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  const Blocks* B = world.blocks();
  if (!B) return out;
  // Sizes that read at the scale of the whole domain: lines 0.3% of its larger side, names 1%
  // (larger names cover small blocks' outlines).
  const Vec2 extent = world.def().domain.max - world.def().domain.min;
  const Real line = 0.003 * extent.maxCoeff(), text = 0.01 * extent.maxCoeff();
  int id = 0;
  for (int i = 0; i < B->count(); ++i) {
    const BlockDef& d = B->def(i);
    visualization_msgs::Marker m;
    m.header = header;
    m.ns = "outline";
    m.type = visualization_msgs::Marker::LINE_STRIP;
    m.pose = planarPose(B->origin(i), B->state(i).angle);  // the points are in the block frame
    m.color.a = 1;
    m.color.r = d.type == BodyType::kDynamic ? 0.9f : 0.5f;
    m.color.g = d.type == BodyType::kKinematic ? 0.8f : 0.5f;
    m.color.b = 0.5f;
    for (const Spheropolygon& part : B->parts(i)) {  // one outline per disc of a cluster
      m.id = id++;
      m.scale.x = line;
      m.points.clear();
      for (const Vec2& p : roundedOutline(part.core, part.rounding, 6)) {
        geometry_msgs::Point q;
        q.x = p.x();
        q.y = p.y();
        m.points.push_back(q);
      }
      out.markers.push_back(m);
    }
    visualization_msgs::Marker label = m;
    label.ns = "name";
    label.id = i;
    label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    label.points.clear();
    label.text = d.name;
    label.scale.z = text;
    // Just above the block, clear of its outline.
    const Box box = B->blockBounds(i);
    label.pose = planarPose(Vec2(0.5 * (box.min.x() + box.max.x()), box.max.y() + text), 0);
    label.color.r = label.color.g = label.color.b = 1;
    out.markers.push_back(label);
  }
  return out;
}

mpm_sdem::SimStats toStats(const World& world, const Diagnostics& d, const StatsInput& in,
                           const std_msgs::Header& header) {
  mpm_sdem::SimStats s;
  s.header = header;
  s.step = static_cast<std::uint64_t>(world.stepCount());
  s.sim_time = world.time();
  s.dt = in.dt.dt;
  s.dt_limit = stepLimitName(in.dt.limit);
  s.real_time_factor = in.real_time_factor;
  s.particles = static_cast<std::uint32_t>(world.particles().size());
  s.blocks = world.blocks() ? static_cast<std::uint32_t>(world.blocks()->count()) : 0;
  s.coupling = couplingSchemeName(world.def().coupling.scheme);
  s.contacts =
      world.coupling() ? static_cast<std::uint32_t>(world.coupling()->activeContacts()) : 0;
  s.paused = in.paused;
  s.kinetic_energy = d.kinetic;
  s.elastic_energy = d.elastic;
  s.gravity_energy = d.gravity;
  s.total_energy = d.total();
  s.block_kinetic_energy = d.block_kinetic;
  for (const Stage stage : in.profile.usedStages()) {
    const double seconds = in.profile.seconds[static_cast<int>(stage)];
    s.stage_names.push_back(stageName(stage));
    s.stage_ms.push_back(in.profile.steps ? 1e3 * seconds / in.profile.steps : 0.0);
  }
  return s;
}

BlockDef toBlockDef(const mpm_sdem::SpawnObstacle::Request& req) {
  BlockDef d;
  d.name = req.name;
  if (req.vertices.empty()) {
    d.core = {Vec2(0, 0)};
    d.rounding = req.disk_radius + req.rounding;
  } else {
    for (const auto& v : req.vertices) d.core.emplace_back(v.x, v.y);
    d.rounding = req.rounding;
  }
  d.position = Vec2(req.pose.x, req.pose.y);
  d.angle = req.pose.theta;
  bool known = false;
  d.type = toBodyType(req.body_type, known);
  // The request gives the velocity of the frame origin; a block definition that of its
  // centre of mass: v_c = v_o + w x (c - o).
  d.angular_velocity = req.twist.angular.z;
  Vec2 centroid(0, 0);
  if (coreProblem(d.core).empty()) {
    std::vector<Vec2> core = d.core;
    makeCounterClockwise(core);
    centroid = spheropolygonMass(core, std::max(d.rounding, Real(0)), 1).centroid;
  }
  const Real c = std::cos(d.angle), s = std::sin(d.angle);
  const Vec2 r(c * centroid.x() - s * centroid.y(), s * centroid.x() + c * centroid.y());
  d.velocity =
      Vec2(req.twist.linear.x, req.twist.linear.y) + d.angular_velocity * Vec2(-r.y(), r.x());
  d.density = req.density;
  d.friction = req.friction;
  d.restitution = req.restitution;
  return d;
}

}  // namespace mpm_sdem::conversions
