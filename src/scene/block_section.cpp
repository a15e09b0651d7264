// The scene's blocks, block_contact and coupling sections.
#include "scene_sections.hpp"

#include <cmath>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/core/rigid/spheropolygon.hpp"

namespace mpm_sdem::scene {

namespace {

BlockDef parseBlock(const Context& ctx, const YAML::Node& n, const std::string& path) {
  MapReader r(ctx, n, path,
              {"name", "type", "shape", "size", "vertices", "radius", "rounding", "discs",
               "disc_radius", "disc_pitch", "position", "angle", "velocity", "angular_velocity",
               "density", "friction", "restitution", "adhesion", "drive"});
  BlockDef b;
  b.name = r.text("name");
  b.type = r.choiceOf<BodyType>(r.node("type"), r.path("type"),
                                {{"static", BodyType::kStatic},
                                 {"kinematic", BodyType::kKinematic},
                                 {"dynamic", BodyType::kDynamic}});
  enum class Kind { kBox, kPolygon, kDisk, kCluster };
  const Kind kind = r.choiceOf<Kind>(r.node("shape"), r.path("shape"),
                                     {{"box", Kind::kBox},
                                      {"polygon", Kind::kPolygon},
                                      {"disk", Kind::kDisk},
                                      {"cluster", Kind::kCluster}});
  r.require(kind == Kind::kCluster || !r.has("discs"), "discs", "applies only to shape: cluster");
  r.require(
      kind == Kind::kCluster || kind == Kind::kDisk || !r.has("disc_pitch") || r.has("disc_radius"),
      "disc_pitch", "needs disc_radius (the discs that fill the shape)");
  r.require((kind != Kind::kCluster && kind != Kind::kDisk) ||
                (!r.has("disc_radius") && !r.has("disc_pitch")),
            r.has("disc_radius") ? "disc_radius" : "disc_pitch",
            "applies only to shape: box or polygon (filled with discs)");
  r.require(kind == Kind::kBox || !r.has("size"), "size", "applies only to shape: box");
  r.require(kind == Kind::kPolygon || !r.has("vertices"), "vertices",
            "applies only to shape: polygon");
  r.require(kind == Kind::kDisk || !r.has("radius"), "radius", "applies only to shape: disk");
  r.require(kind != Kind::kDisk || !r.has("rounding"), "rounding",
            "a disk is a point swept by its radius: give radius only");
  // The values' ranges are checked with the contact model, in parseBlocks (blockProblem).
  r.require(kind != Kind::kCluster || !r.has("rounding"), "rounding",
            "a cluster's outline is its discs: give discs only");
  if (kind == Kind::kDisk) {
    b.rounding = r.number("radius", "m");
    b.core = {Vec2(0, 0)};
  } else if (kind == Kind::kCluster) {
    // Seed 003 sec. 2.2: a rigid cluster of discs, each [x, y, radius] in the block frame (m).
    const YAML::Node v = r.node("discs");
    if (!v.IsSequence() || v.size() == 0)
      ctx.fail(v, r.path("discs"), "expected a list of discs, each [x, y, radius] in m");
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string at = r.path("discs") + "[" + std::to_string(i) + "]";
      if (!v[i].IsSequence() || v[i].size() != 3)
        ctx.fail(v[i], at, "expected [x, y, radius] in m");
      Real x[3];
      for (int k = 0; k < 3; ++k) x[k] = MapReader::toNumber(ctx, v[i][k], at, "m");
      b.discs.push_back({Vec2(x[0], x[1]), x[2]});
    }
  } else {
    b.rounding = r.number("rounding", "m");
  }
  if (kind == Kind::kBox) {
    const Vec2 size = r.vec2("size", "m");
    const Real a = b.rounding;
    r.require(size.x() > 2 * a && size.y() > 2 * a, "size",
              "the outer size must exceed twice the rounding (" + num(2 * a) + " m) in x and y");
    const Vec2 c = size / 2 - Vec2(a, a);
    b.core = {Vec2(-c.x(), -c.y()), Vec2(c.x(), -c.y()), Vec2(c.x(), c.y()), Vec2(-c.x(), c.y())};
  } else if (kind == Kind::kPolygon) {
    const YAML::Node v = r.node("vertices");
    if (!v.IsSequence()) ctx.fail(v, r.path("vertices"), "expected a list of [x, y] points in m");
    for (std::size_t i = 0; i < v.size(); ++i) {
      b.core.push_back(
          MapReader::toVec2(ctx, v[i], r.path("vertices") + "[" + std::to_string(i) + "]", "m"));
    }
  }
  if (r.has("disc_radius")) {
    // The shape filled with discs on a square lattice (seed 003's 8 x 8 wooden blocks): the
    // block becomes their cluster.
    const Real radius = r.number("disc_radius", "m");
    const Real pitch = r.number("disc_pitch", "m", 2 * radius);
    r.require(radius > 0 && std::isfinite(radius), "disc_radius", "must be a positive length");
    r.require(pitch > 0 && pitch <= 2 * radius, "disc_pitch",
              "must lie in (0, 2 disc_radius]: the discs touch or overlap, so the cluster holds "
              "together");
    std::vector<Vec2> core = b.core;
    makeCounterClockwise(core);
    if (coreProblem(core).empty()) {
      b.discs = fillWithDiscs({core, b.rounding}, radius, pitch);
      r.require(!b.discs.empty(), "disc_radius",
                "not one disc of radius " + num(radius) + " m fits inside the shape");
      b.core.clear();
    }
  }
  b.position = r.vec2("position", "m");
  b.angle = r.number("angle", "deg", 0) * kDeg;
  b.velocity = r.vec2("velocity", "m/s", b.velocity);
  b.angular_velocity = r.number("angular_velocity", "rad/s", 0);
  b.density = r.number("density", "kg/m^3");
  b.friction = r.number("friction", "(dimensionless)", b.friction);
  b.restitution = r.number("restitution", "(dimensionless)", b.restitution);
  b.adhesion = r.number("adhesion", "Pa", b.adhesion);
  if (r.has("drive")) {
    MapReader d(ctx, r.node("drive"), r.path("drive"),
                {"velocity_x", "velocity_y", "angular_velocity"});
    BlockDrive& drive = b.drive;
    drive.hold_vx = d.has("velocity_x");
    drive.hold_vy = d.has("velocity_y");
    drive.hold_angular = d.has("angular_velocity");
    drive.velocity = Vec2(d.number("velocity_x", "m/s", 0), d.number("velocity_y", "m/s", 0));
    drive.angular_velocity = d.number("angular_velocity", "rad/s", 0);
    r.require(drive.any(), "drive", "give velocity_x, velocity_y and/or angular_velocity");
  }
  return b;
}

// The normal and tangential spring constants of a contact model (N/m per metre of thickness).
void readSprings(const MapReader& r, Real& normal, Real& tangential) {
  normal = r.number("normal_stiffness", limits::kStiffness, normal);
  tangential = r.number("tangential_stiffness", limits::kStiffness, tangential);
}

}  // namespace

void parseBlocks(const Context& ctx, const MapReader& top, Scene& s) {
  // block_contact and coupling apply to obstacles spawned at run time too, so a scene without
  // blocks may set them.
  const YAML::Node list =
      top.has("blocks") ? top.node("blocks") : YAML::Node(YAML::NodeType::Sequence);
  if (!list.IsSequence()) ctx.fail(list, "blocks", "expected a list of blocks");
  std::vector<BlockDef> blocks;
  for (std::size_t i = 0; i < list.size(); ++i)
    blocks.push_back(parseBlock(ctx, list[i], "blocks[" + std::to_string(i) + "]"));
  if (top.has("block_contact")) {
    MapReader r(ctx, top.node("block_contact"), "block_contact",
                {"model", "normal_stiffness", "tangential_stiffness"});
    BlockContactDef& c = s.world.block_contact;
    c.model = r.choice<BlockContactModel>(
        "model", {{"penalty", BlockContactModel::kPenalty}, {"box2d", BlockContactModel::kBox2D}},
        c.model);
    readSprings(r, c.normal_stiffness, c.tangential_stiffness);
  }
  const DomainDef& dom = s.world.domain;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    BlockDef& b = blocks[i];
    const std::string path = "blocks[" + std::to_string(i) + "]";
    Problem problem = blockProblem(b, s.world.block_contact.model);
    if (problem.empty()) problem = domainProblem(b, dom.min, dom.max);
    if (!problem.empty()) {
      // The core's own keys, as this block's shape spells them.
      std::string key = problem.key;
      if (key == "rounding" && list[i]["radius"]) key = "radius";
      if (key == "vertices" && list[i]["size"]) key = "size";
      if (key == "discs" && list[i]["disc_radius"]) key = "disc_radius";
      const YAML::Node at = list[i][key] ? list[i][key] : list[i];
      ctx.fail(at, path + "." + key, problem.message);
    }
    makeCounterClockwise(b.core);
    const std::vector<Spheropolygon> parts = placedParts(b);
    for (const BlockDef& other : s.world.blocks) {
      if (other.name == b.name)
        ctx.fail(list[i], path, "a block named '" + b.name + "' exists already");
      if (mayOverlap(b, other)) continue;
      if (const Real depth = startingOverlap(parts, placedParts(other)); depth > 0) {
        ctx.fail(list[i], path,
                 "block '" + b.name + "' overlaps block '" + other.name + "' by " + num(depth) +
                     " m; move it so that the rounded outlines at most touch");
      }
    }
    for (const BodyDef& body : s.world.bodies) {
      for (const Vec2& p :
           fillPoints(body.shape, dom.min, s.world.cell_size, body.points_per_cell)) {
        if (insideOutline(parts, p)) {
          ctx.fail(list[i], path,
                   "block '" + b.name + "' overlaps the material of body '" + body.name +
                       "'; move the block or shrink the body");
        }
      }
    }
    s.world.blocks.push_back(std::move(b));
  }
  if (top.has("coupling")) {
    MapReader r(ctx, top.node("coupling"), "coupling",
                {"scheme", "normal_stiffness", "tangential_stiffness", "stiffness_per",
                 "normal_integration", "contact_radius", "verlet_distance", "block_points_per_cell",
                 "boundary_inset"});
    CouplingDef& c = s.world.coupling;
    std::vector<std::pair<const char*, CouplingScheme>> schemes;
    for (const SchemeTraits& t : couplingSchemes()) schemes.emplace_back(t.name, t.scheme);
    c.scheme = r.choice<CouplingScheme>("scheme", schemes, c.scheme);
    readSprings(r, c.normal_stiffness, c.tangential_stiffness);
    c.stiffness_per = r.choice<SpringBasis>(
        "stiffness_per", {{"point", SpringBasis::kPerPoint}, {"length", SpringBasis::kPerLength}},
        c.stiffness_per);
    c.normal_integration =
        r.choice<ContactIntegration>("normal_integration",
                                     {{"explicit", ContactIntegration::kExplicit},
                                      {"exact", ContactIntegration::kExact},
                                      {"subcycled", ContactIntegration::kSubcycled}},
                                     c.normal_integration);
    c.block_points_per_cell = r.integer("block_points_per_cell", c.block_points_per_cell);
    r.require(c.block_points_per_cell >= 1 && c.block_points_per_cell <= 8, "block_points_per_cell",
              "must be 1 to 8 points per cell side, got " + num(c.block_points_per_cell));
    const Real h = s.world.cell_size;
    if (r.has("contact_radius")) {
      c.contact_radius = r.number("contact_radius", "m");
      r.require(c.contact_radius > 0 && c.contact_radius < h, "contact_radius",
                "must be in (0, cell_size = " + num(h) + ") m (seed 000 eq. 45), got " +
                    num(c.contact_radius));
    }
    if (r.has("boundary_inset")) {
      c.boundary_inset = r.number("boundary_inset", "m");
      r.require(
          c.boundary_inset > 0 && c.boundary_inset < 0.5 * h, "boundary_inset",
          "must be in (0, cell_size / 2 = " + num(0.5 * h) + ") m, got " + num(c.boundary_inset));
    }
    if (r.has("verlet_distance")) {
      c.verlet_distance = r.number("verlet_distance", "m");
      r.require(c.verlet_distance > 0 && c.verlet_distance <= 5 * h, "verlet_distance",
                "must be in (0, 5 cell sizes = " + num(5 * h) +
                    "] m (a longer one lists far points every step), got " +
                    num(c.verlet_distance));
    }
  }
}

// Deformable FEM bodies (seed 002 sec. 2.3): an outline meshed at element_size by CGAL.

}  // namespace mpm_sdem::scene
