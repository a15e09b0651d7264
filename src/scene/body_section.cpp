// The scene's bodies section (material point bodies and their shapes).
#include "scene_sections.hpp"

#include <cmath>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/initial_stress.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"

namespace mpm_sdem::scene {

ShapeDef parseShape(const Context& ctx, const MapReader& r) {
  ShapeDef sh;
  sh.type = r.choiceOf<ShapeType>(r.node("shape"), r.path("shape"),
                                  {{"rectangle", ShapeType::kRectangle},
                                   {"polygon", ShapeType::kPolygon},
                                   {"disk", ShapeType::kDisk}});
  const std::pair<const char*, ShapeType> owner[] = {{"min", ShapeType::kRectangle},
                                                     {"max", ShapeType::kRectangle},
                                                     {"vertices", ShapeType::kPolygon},
                                                     {"center", ShapeType::kDisk},
                                                     {"radius", ShapeType::kDisk}};
  const char* shape_names[] = {"rectangle", "polygon", "disk"};
  for (const auto& [key, type] : owner) {
    r.require(type == sh.type || !r.has(key), key,
              std::string("applies only to shape: ") + shape_names[static_cast<int>(type)]);
  }
  switch (sh.type) {
    case ShapeType::kRectangle:
      sh.min = r.vec2("min", "m");
      sh.max = r.vec2("max", "m");
      r.require(sh.max.x() > sh.min.x() && sh.max.y() > sh.min.y(), "max",
                "must exceed min in both x and y");
      break;
    case ShapeType::kDisk:
      sh.center = r.vec2("center", "m");
      sh.radius = r.number("radius", "m");
      r.require(sh.radius > 0, "radius", "must be > 0 m, got " + num(sh.radius));
      break;
    case ShapeType::kPolygon: {
      const YAML::Node v = r.node("vertices");
      if (!v.IsSequence() || v.size() < 3) {
        ctx.fail(v, r.path("vertices"), "expected a list of at least 3 [x, y] points in m");
      }
      for (std::size_t i = 0; i < v.size(); ++i) {
        sh.vertices.push_back(
            MapReader::toVec2(ctx, v[i], r.path("vertices") + "[" + std::to_string(i) + "]", "m"));
      }
      r.require(std::abs(signedArea(sh.vertices)) > 0, "vertices",
                "the polygon has zero area; list the corners of a region");
      r.require(!selfIntersects(sh.vertices), "vertices",
                "the polygon's edges cross; list the corners in order around the outline");
      break;
    }
  }
  return sh;
}

void parseBodies(const Context& ctx, const MapReader& top, Scene& s,
                 const std::map<std::string, int>& materials) {
  const YAML::Node list = top.node("bodies");
  if (!list.IsSequence() || list.size() == 0) {
    ctx.fail(list, "bodies", "expected a list of at least one body");
  }
  const DomainDef& dom = s.world.domain;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "bodies[" + std::to_string(i) + "]";
    MapReader r(ctx, list[i], path,
                {"name", "material", "shape", "min", "max", "vertices", "center", "radius",
                 "points_per_cell", "velocity", "initial_stress"});
    BodyDef b;
    b.name = r.name("name");
    const std::string mat = r.text("material");
    const auto it = materials.find(mat);
    if (it == materials.end()) {
      std::string names;
      for (const auto& m : materials) names += (names.empty() ? "" : ", ") + m.first;
      r.require(false, "material", "no material named '" + mat + "'; defined: " + names);
    }
    b.material = it->second;
    b.shape = parseShape(ctx, r);
    b.points_per_cell = r.integer("points_per_cell", b.points_per_cell);
    r.require(b.points_per_cell >= 1 && b.points_per_cell <= 8, "points_per_cell",
              "must be a whole number in [1, 8] (points per cell per direction), got " +
                  std::to_string(b.points_per_cell));
    b.velocity = r.vec2("velocity", "m/s", b.velocity);
    r.require("velocity", limits::rangeProblem(b.velocity.norm(), limits::kSpeed),
              "its magnitude ");
    b.geostatic = r.choice<bool>("initial_stress", {{"none", false}, {"geostatic", true}}, false);
    if (b.geostatic) {
      const std::string why = geostaticProblem(s.world.materials[b.material]);
      r.require(why.empty(), "initial_stress", "geostatic: " + why);
    }

    Vec2 lo, hi;
    bounds(b.shape, lo, hi);
    if (lo.x() < dom.min.x() || lo.y() < dom.min.y() || hi.x() > dom.max.x() ||
        hi.y() > dom.max.y()) {
      ctx.fail(list[i], path,
               "body '" + b.name + "' reaches outside the domain [" + num(dom.min.x()) + ", " +
                   num(dom.max.x()) + "] x [" + num(dom.min.y()) + ", " + num(dom.max.y()) +
                   "] m; move it inside or enlarge domain.min/max");
    }
    std::vector<BodyDef> so_far = s.world.bodies;
    so_far.push_back(b);
    const Problem size = sizeProblem(dom, s.world.cell_size, so_far);
    if (!size.empty())
      ctx.fail(list[i], path, "with body '" + b.name + "' the world " + size.message);
    const auto points = fillPoints(b.shape, dom.min, s.world.cell_size, b.points_per_cell);
    if (points.empty()) {
      ctx.fail(list[i], path,
               "body '" + b.name +
                   "' contains no material point; make it larger "
                   "than a cell or raise points_per_cell");
    }
    for (std::size_t k = 0; k < s.world.bodies.size(); ++k) {
      for (const Vec2& p : points) {
        if (contains(s.world.bodies[k].shape, p)) {
          ctx.fail(list[i], path,
                   "body '" + b.name + "' overlaps body '" + s.world.bodies[k].name +
                       "'; move or shrink one of them so that no region is "
                       "filled twice");
        }
      }
      if (s.world.bodies[k].name == b.name) {
        ctx.fail(list[i], path, "a body named '" + b.name + "' exists already");
      }
    }
    s.world.bodies.push_back(std::move(b));
  }
}

}  // namespace mpm_sdem::scene
