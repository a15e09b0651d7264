// The scene's FEM bodies section (meshed by CGAL through mesher.hpp).
#include "scene_sections.hpp"

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/mesh/mesher.hpp"

namespace mpm_sdem::scene {

void parseFemBodies(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("fem_bodies")) return;
  const YAML::Node list = top.node("fem_bodies");
  if (!list.IsSequence()) ctx.fail(list, "fem_bodies", "expected a list of FEM bodies");
  const DomainDef& dom = s.world.domain;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "fem_bodies[" + std::to_string(i) + "]";
    MapReader r(
        ctx, list[i], path,
        {"name", "shape", "size", "position", "vertices", "element_size", "model", "density",
         "youngs_modulus", "poisson_ratio", "mass_damping", "stiffness_damping", "friction",
         "restitution", "velocity", "angular_velocity", "held", "held_velocity"});
    FemBodyDef b;
    b.name = r.text("name");
    enum class Kind { kBox, kPolygon };
    const Kind kind = r.choiceOf<Kind>(r.node("shape"), r.path("shape"),
                                       {{"box", Kind::kBox}, {"polygon", Kind::kPolygon}});
    r.require(kind == Kind::kBox || (!r.has("size") && !r.has("position")),
              r.has("size") ? "size" : "position", "applies only to shape: box");
    r.require(kind == Kind::kPolygon || !r.has("vertices"), "vertices",
              "applies only to shape: polygon");
    std::vector<Vec2> outline;
    if (kind == Kind::kBox) {
      const Vec2 half = r.vec2("size", "m") / 2, c = r.vec2("position", "m");
      outline = {c - half, Vec2(c.x() + half.x(), c.y() - half.y()), c + half,
                 Vec2(c.x() - half.x(), c.y() + half.y())};
    } else {
      const YAML::Node v = r.node("vertices");
      if (!v.IsSequence()) ctx.fail(v, r.path("vertices"), "expected a list of [x, y] points in m");
      for (std::size_t k = 0; k < v.size(); ++k)
        outline.push_back(
            MapReader::toVec2(ctx, v[k], r.path("vertices") + "[" + std::to_string(k) + "]", "m"));
    }
    const Real size = r.number("element_size", limits::kLength);
    try {
      b.mesh = meshPolygon(outline, size);
    } catch (const std::invalid_argument& e) {
      const char* key = std::string(e.what()).find("element_size") != std::string::npos
                            ? "element_size"
                            : (kind == Kind::kBox ? "size" : "vertices");
      ctx.fail(r.node(key), r.path(key), e.what());
    }
    b.model = r.has("model") ? r.choiceOf<FemModel>(r.node("model"), r.path("model"),
                                                    {{"linear", FemModel::kLinear},
                                                     {"corotational", FemModel::kCorotational}})
                             : FemModel::kCorotational;
    b.density = r.number("density", "kg/m^3", b.density);
    b.youngs_modulus = r.number("youngs_modulus", "Pa");
    b.poisson_ratio = r.number("poisson_ratio", "(dimensionless)");
    b.mass_damping = r.number("mass_damping", "1/s", 0);
    b.stiffness_damping = r.number("stiffness_damping", "s", 0);
    b.friction = r.number("friction", "(dimensionless)", b.friction);
    b.restitution = r.number("restitution", "(dimensionless)", b.restitution);
    b.velocity = r.vec2("velocity", "m/s", Vec2(0, 0));
    b.angular_velocity = r.number("angular_velocity", "rad/s", 0);
    b.held_velocity = r.vec2("held_velocity", "m/s", Vec2(0, 0));
    if (r.has("held")) {
      // Boxes [x_min, y_min, x_max, y_max] (m): the nodes inside are held.
      const YAML::Node h = r.node("held");
      if (!h.IsSequence())
        ctx.fail(h, r.path("held"), "expected a list of [x_min, y_min, x_max, y_max] boxes in m");
      for (std::size_t k = 0; k < h.size(); ++k) {
        const std::string at = r.path("held") + "[" + std::to_string(k) + "]";
        if (!h[k].IsSequence() || h[k].size() != 4)
          ctx.fail(h[k], at, "expected [x_min, y_min, x_max, y_max] in m");
        Real x[4];
        for (int c = 0; c < 4; ++c) x[c] = MapReader::toNumber(ctx, h[k][c], at, "m");
        const Box box{Vec2(x[0], x[1]), Vec2(x[2], x[3])};
        bool holds = false;
        for (const Vec2& v : b.mesh.nodes)
          holds = holds ||
                  ((v.array() >= box.min.array()).all() && (v.array() <= box.max.array()).all());
        if (!holds)
          ctx.fail(h[k], at, "holds no node of the mesh; widen the box (nodes lie on the outline)");
        b.held.push_back(box);
      }
    }
    if (Problem p = femBodyProblem(b); !p.empty()) {
      const std::string key = p.key == "mesh" || p.key == "outline"
                                  ? (kind == Kind::kBox ? "size" : "vertices")
                                  : p.key;
      ctx.fail(list[i][key] ? list[i][key] : list[i], path + "." + key, p.message);
    }
    for (const Vec2& v : b.mesh.nodes) {
      if ((v.array() < dom.min.array()).any() || (v.array() > dom.max.array()).any())
        ctx.fail(list[i], path, "FEM body '" + b.name + "' reaches outside the domain");
    }
    for (const FemBodyDef& other : s.world.fem_bodies)
      if (other.name == b.name)
        ctx.fail(list[i], path, "an FEM body named '" + b.name + "' exists already");
    s.world.fem_bodies.push_back(std::move(b));
  }
}

// The SPH region or bodies (seed 001): regions as body shapes, bodies by name.

}  // namespace mpm_sdem::scene
