// The scene's output, limits and view sections.
#include "scene_sections.hpp"

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem::scene {

void parseOutput(const Context& ctx, const MapReader& top, Scene& s) {
  if (top.has("output")) {
    MapReader o(ctx, top.node("output"), "output", {"interval", "particles", "gauges"});
    s.output.interval = o.number("interval", limits::kTimeStep, 0);
    o.require(
        s.output.interval <= s.end_time, "interval",
        "must be at most time.end = " + num(s.end_time) + " s, got " + num(s.output.interval));
    s.output.particles = o.boolean("particles", s.output.particles);
    if (o.has("gauges")) {
      const YAML::Node gauges = o.node("gauges");
      if (!gauges.IsMap())
        ctx.fail(gauges, "output.gauges", "expected a map of named gauges (outlet: {below: 0.2})");
      for (const auto& kv : gauges) {
        const std::string name = kv.first.Scalar();
        if (const Problem p = limits::nameProblem(name); !p.empty())
          ctx.fail(kv.first, "output.gauges." + name, p.message);
        MapReader g(ctx, kv.second, "output.gauges." + name, {"below", "right_of"});
        g.require(g.has("below") != g.has("right_of"), "below",
                  "give one of below (y, m) or right_of (x, m)");
        const bool below = g.has("below");
        const Real at = g.number(below ? "below" : "right_of", limits::kCoordinate);
        s.output.gauges.push_back(
            {name, below ? MassGauge::Side::kBelow : MassGauge::Side::kRightOf, at});
      }
    }
  }
  if (s.output.interval <= 0) s.output.interval = s.end_time / 100;
}

void parseLimits(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("limits")) return;
  MapReader l(ctx, top.node("limits"), "limits", {"energy_growth", "step_collapse"});
  s.limits.energy_growth =
      l.number("energy_growth", "(fraction of the initial energy)", s.limits.energy_growth);
  l.require(s.limits.energy_growth > 0, "energy_growth",
            "must be > 0, got " + num(s.limits.energy_growth));
  s.limits.step_collapse =
      l.number("step_collapse", "(fraction of the first step)", s.limits.step_collapse);
  l.require(s.limits.step_collapse > 0 && s.limits.step_collapse < 1, "step_collapse",
            "must lie in (0, 1), got " + num(s.limits.step_collapse));
}

void parseView(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("view")) return;
  MapReader r(ctx, top.node("view"), "view", {"color_by", "max_value"});
  using render::ColorBy;
  if (r.has("color_by") || r.has("max_value")) {
    s.view.color_by = r.choice<ColorBy>(
        "color_by",
        {{"speed", ColorBy::kSpeed}, {"pressure", ColorBy::kPressure}, {"kind", ColorBy::kKind}},
        ColorBy::kSpeed);
  }
  if (r.has("max_value")) {
    const ColorBy c = *s.view.color_by;
    r.require(c != ColorBy::kKind, "max_value",
              "applies only to color_by speed or pressure; leave it out with color_by kind");
    const Real v = r.number("max_value", render::colorByUnit(c));
    const Problem problem = render::maxValueProblem(c, v);
    r.require(problem.empty(), "max_value",
              problem.message + " (the top of the " + render::colorByName(c) +
                  " colours; leave it out for the scene's default)");
    s.view.max_value = v;
  }
}

}  // namespace mpm_sdem::scene
