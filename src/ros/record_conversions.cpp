// Conversions of what bags record for re-simulation: world commands and block definitions.
// Every number is a float64 field, so a command read back is the command applied.
#include "mpm_sdem/ros/conversions.hpp"

namespace mpm_sdem::conversions {

namespace {

geometry_msgs::Point toPoint(const Vec2& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  return p;
}

Vec2 fromPoint(const geometry_msgs::Point& p) {
  return {p.x, p.y};
}

}  // namespace

mpm_sdem::BlockDefinition toMsg(const BlockDef& d) {
  mpm_sdem::BlockDefinition m;
  m.name = d.name;
  for (const Vec2& v : d.core) m.core.push_back(toPoint(v));
  m.rounding = d.rounding;
  for (const Disc& disc : d.discs) {
    m.disc_centres.push_back(toPoint(disc.centre));
    m.disc_radii.push_back(disc.radius);
  }
  m.pose.x = d.position.x();
  m.pose.y = d.position.y();
  m.pose.theta = d.angle;
  m.twist.linear.x = d.velocity.x();
  m.twist.linear.y = d.velocity.y();
  m.twist.angular.z = d.angular_velocity;
  m.body_type = fromBodyType(d.type);
  m.density = d.density;
  m.friction = d.friction;
  m.restitution = d.restitution;
  m.adhesion = d.adhesion;
  m.hold_vx = d.drive.hold_vx;
  m.hold_vy = d.drive.hold_vy;
  m.hold_angular = d.drive.hold_angular;
  m.drive.linear.x = d.drive.velocity.x();
  m.drive.linear.y = d.drive.velocity.y();
  m.drive.angular.z = d.drive.angular_velocity;
  return m;
}

BlockDef fromMsg(const mpm_sdem::BlockDefinition& m) {
  BlockDef d;
  d.name = m.name;
  for (const geometry_msgs::Point& p : m.core) d.core.push_back(fromPoint(p));
  d.rounding = m.rounding;
  for (std::size_t k = 0; k < m.disc_centres.size() && k < m.disc_radii.size(); ++k)
    d.discs.push_back({fromPoint(m.disc_centres[k]), m.disc_radii[k]});
  d.position = {m.pose.x, m.pose.y};
  d.angle = m.pose.theta;
  d.velocity = {m.twist.linear.x, m.twist.linear.y};
  d.angular_velocity = m.twist.angular.z;
  bool ok = true;
  d.type = toBodyType(m.body_type, ok);
  if (!ok) d.type = BodyType::kStatic;
  d.density = m.density;
  d.friction = m.friction;
  d.restitution = m.restitution;
  d.adhesion = m.adhesion;
  d.drive.hold_vx = m.hold_vx;
  d.drive.hold_vy = m.hold_vy;
  d.drive.hold_angular = m.hold_angular;
  d.drive.velocity = {m.drive.linear.x, m.drive.linear.y};
  d.drive.angular_velocity = m.drive.angular.z;
  return d;
}

mpm_sdem::RecordedCommand toMsg(const WorldCommand& c, const std::string& frame) {
  mpm_sdem::RecordedCommand m;
  m.header.stamp = toRosTime(c.time);
  m.header.frame_id = frame;
  m.time = c.time;
  m.step = c.step;
  m.sequence = c.sequence;
  m.kind = static_cast<std::uint8_t>(c.kind);
  m.block = c.block;
  m.vector.x = c.vector.x();
  m.vector.y = c.vector.y();
  m.point = toPoint(c.point);
  m.scalar = c.scalar;
  if (c.kind == WorldCommand::Kind::kAddBlock) m.definition = toMsg(c.def);
  return m;
}

WorldCommand fromMsg(const mpm_sdem::RecordedCommand& m) {
  WorldCommand c;
  c.kind = static_cast<WorldCommand::Kind>(m.kind);
  c.time = m.time;
  c.step = m.step;
  c.sequence = m.sequence;
  c.block = m.block;
  c.vector = {m.vector.x, m.vector.y};
  c.point = fromPoint(m.point);
  c.scalar = m.scalar;
  if (c.kind == WorldCommand::Kind::kAddBlock) c.def = fromMsg(m.definition);
  return c;
}

}  // namespace mpm_sdem::conversions
