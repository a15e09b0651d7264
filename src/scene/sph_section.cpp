// The scene's SPH section (seed 001).
#include "scene_sections.hpp"

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem::scene {

void parseSph(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("sph")) return;
  MapReader r(ctx, top.node("sph"), "sph",
              {"regions", "bodies", "kernel", "smoothing_length", "viscosity_alpha",
               "viscosity_beta", "corrected_gradient"});
  SphDef& d = s.world.sph;
  if (r.has("regions")) {
    const YAML::Node list = r.node("regions");
    if (!list.IsSequence()) ctx.fail(list, r.path("regions"), "expected a list of shapes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = r.path("regions") + "[" + std::to_string(i) + "]";
      MapReader region(ctx, list[i], path, {"shape", "min", "max", "vertices", "center", "radius"});
      d.regions.push_back(parseShape(ctx, region));
    }
  }
  if (r.has("bodies")) {
    const YAML::Node list = r.node("bodies");
    if (!list.IsSequence()) ctx.fail(list, r.path("bodies"), "expected a list of body names");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string name = list[i].IsScalar() ? list[i].Scalar() : "";
      int found = -1;
      for (std::size_t b = 0; b < s.world.bodies.size(); ++b)
        if (s.world.bodies[b].name == name) found = static_cast<int>(b);
      if (found < 0)
        ctx.fail(list[i], r.path("bodies") + "[" + std::to_string(i) + "]",
                 "no body named '" + name + "'; name a body of the bodies list");
      d.bodies.push_back(found);
    }
  }
  r.require(d.enabled(), "regions", "give at least one region or body, or leave out sph");
  d.kernel = r.choice<SphKernel>(
      "kernel",
      {{"cubic_spline", SphKernel::kCubicSpline}, {"wendland_c2", SphKernel::kWendlandC2}},
      d.kernel);
  d.smoothing_length = r.number("smoothing_length", "m", s.world.cell_size);
  d.viscosity_alpha = r.number("viscosity_alpha", "(dimensionless)", d.viscosity_alpha);
  d.viscosity_beta = r.number("viscosity_beta", "(dimensionless)", d.viscosity_beta);
  d.corrected_gradient = r.boolean("corrected_gradient", d.corrected_gradient);
  const Problem p = sphProblem(d, s.world.cell_size);
  r.require(p.empty(), p.key.c_str(), p.message);
}

// The pictures' quantity and the top of their colour scale; max_value alone colours speeds.

}  // namespace mpm_sdem::scene
