// The scene's domain (walls, side walls), grid, solver and time sections.
#include "scene_sections.hpp"

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::scene {

namespace {

WallDef parseWall(const Context& ctx, const MapReader& walls, const char* side) {
  WallDef w;
  if (!walls.has(side)) return w;
  const YAML::Node n = walls.node(side);
  const std::string path = walls.path(side);
  auto type = [&](const YAML::Node& t, const std::string& p) {
    return walls.choiceOf<WallType>(t, p,
                                    {{"sticky", WallType::kSticky},
                                     {"slip", WallType::kSlip},
                                     {"friction", WallType::kFriction},
                                     {"periodic", WallType::kPeriodic}});
  };
  if (n.IsScalar()) {
    w.type = type(n, path);
    if (w.type == WallType::kFriction) {
      ctx.fail(n, path, "a friction wall needs a coefficient: {type: friction, friction: 0.3}");
    }
    return w;
  }
  MapReader m(ctx, n, path, {"type", "friction"});
  w.type = type(m.node("type"), m.path("type"));
  if (w.type == WallType::kFriction) {
    w.friction = m.number("friction", limits::kFriction);
  }
  return w;
}

}  // namespace

void parseDomain(const Context& ctx, const MapReader& top, Scene& s) {
  MapReader d(ctx, top.node("domain"), "domain", {"min", "max", "walls", "sidewalls"});
  DomainDef& dom = s.world.domain;
  dom.min = d.vec2("min", limits::kCoordinate);
  dom.max = d.vec2("max", limits::kCoordinate);
  d.require(dom.max.x() > dom.min.x() && dom.max.y() > dom.min.y(), "max",
            "must exceed domain.min in both x and y");
  if (d.has("walls")) {
    MapReader w(ctx, d.node("walls"), "domain.walls", {"left", "right", "bottom", "top"});
    dom.left = parseWall(ctx, w, "left");
    dom.right = parseWall(ctx, w, "right");
    dom.bottom = parseWall(ctx, w, "bottom");
    dom.top = parseWall(ctx, w, "top");
  }
  if (d.has("sidewalls")) {
    MapReader sw(ctx, d.node("sidewalls"), d.path("sidewalls"), {"width", "friction"});
    dom.sidewalls.width = sw.number("width", "m");
    sw.require(dom.sidewalls.width > 0 && dom.sidewalls.width <= 100, "width",
               "must be in (0, 100] m (the channel's width between its side walls), got " +
                   num(dom.sidewalls.width));
    dom.sidewalls.friction = sw.number("friction", limits::kFriction);
  }
}

void parseGrid(const Context& ctx, const MapReader& top, Scene& s) {
  MapReader g(ctx, top.node("grid"), "grid", {"cell_size"});
  const Real h = g.number("cell_size", limits::kCellSize);
  const Vec2 size = s.world.domain.max - s.world.domain.min;
  for (int a = 0; a < 2; ++a) {
    const Real n = size[a] / h;
    if (std::abs(n - std::round(n)) > 1e-6 * std::max<Real>(1, n)) {
      g.require(false, "cell_size",
                "the domain " + std::string(a == 0 ? "width " : "height ") + num(size[a]) +
                    " m is not a whole number of cells of " + num(h) + " m; use e.g. " +
                    num(size[a] / std::ceil(n)) + " or make the domain " + num(std::round(n) * h) +
                    " m");
    }
  }
  const Problem memory = sizeProblem(s.world.domain, h, {});
  g.require(memory.empty(), "cell_size", "the grid " + memory.message);
  s.world.cell_size = h;
}

void parseSolver(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("solver")) return;
  MapReader r(ctx, top.node("solver"), "solver",
              {"kernel", "transfer", "pic_fraction", "asflip_relaxation_time", "stress_update",
               "gravity", "damping", "inertia_scale", "sleep_speed", "sleep_time", "sleep_margin",
               "volume_fit", "volumetric_average"});
  SolverDef& sol = s.world.solver;
  sol.kernel = r.choice<KernelType>("kernel",
                                    {{"quadratic_bspline", KernelType::kQuadraticBSpline},
                                     {"cubic_bspline", KernelType::kCubicBSpline},
                                     {"gimp", KernelType::kGimp}},
                                    sol.kernel);
  sol.transfer = r.choice<TransferScheme>("transfer",
                                          {{"apic", TransferScheme::kApic},
                                           {"pic", TransferScheme::kPic},
                                           {"flip", TransferScheme::kFlip},
                                           {"asflip", TransferScheme::kAsflip}},
                                          sol.transfer);
  if (r.has("pic_fraction")) {
    r.require(sol.transfer == TransferScheme::kFlip, "pic_fraction",
              "applies only to transfer: flip (it is alpha of seed 000 eq. 28)");
    sol.pic_fraction = r.number("pic_fraction", "(dimensionless)");
    r.require(sol.pic_fraction >= 0 && sol.pic_fraction <= 1, "pic_fraction",
              "must be in [0, 1] (0 = FLIP, 1 = PIC), got " + num(sol.pic_fraction));
  }
  if (r.has("asflip_relaxation_time")) {
    r.require(sol.transfer == TransferScheme::kAsflip, "asflip_relaxation_time",
              "applies only to transfer: asflip");
    sol.asflip_relaxation_time = r.number("asflip_relaxation_time", "s");
    r.require(
        sol.asflip_relaxation_time >= 0 && sol.asflip_relaxation_time <= 1e3,
        "asflip_relaxation_time",
        "must be in [0, 1000] s (0 = never: pure ASFLIP), got " + num(sol.asflip_relaxation_time));
  }
  sol.stress_update = r.choice<StressUpdate>(
      "stress_update", {{"usf", StressUpdate::kUsf}, {"usl", StressUpdate::kUsl}},
      sol.stress_update);
  sol.gravity = r.vec2("gravity", "m/s^2", sol.gravity);
  r.require("gravity", limits::rangeProblem(sol.gravity.norm(), limits::kGravity),
            "its magnitude ");
  sol.damping = r.number("damping", "(dimensionless)", sol.damping);
  r.require(
      sol.damping >= 0 && sol.damping < 1, "damping",
      "must be in [0, 1) (0 = none; 0.05 to 0.2 settles a static state), got " + num(sol.damping));
  sol.inertia_scale = r.number("inertia_scale", limits::kInertiaScale, sol.inertia_scale);
  sol.sleep.speed = r.number("sleep_speed", limits::kSleepSpeed, sol.sleep.speed);
  sol.sleep.time = r.number("sleep_time", limits::kSleepTime, sol.sleep.time);
  sol.sleep.margin = r.number("sleep_margin", limits::kSleepMargin, sol.sleep.margin);
  for (const char* key : {"sleep_time", "sleep_margin"})
    r.require(!r.has(key) || sol.sleep.on(), key, "applies only with sleep_speed > 0");
  sol.volume_fit = r.boolean("volume_fit", sol.volume_fit);
  sol.volumetric_average = r.boolean("volumetric_average", sol.volumetric_average);
}

void parseTime(const Context& ctx, const MapReader& top, Scene& s) {
  MapReader t(ctx, top.node("time"), "time",
              {"end", "dt", "cfl", "dt_max", "contact_factor", "fem_integration"});
  s.end_time = t.number("end", limits::kEndTime);
  TimeStepDef& ts = s.world.time_step;
  if (t.has("dt") && !(t.node("dt").IsScalar() && t.node("dt").Scalar() == "auto")) {
    ts.automatic = false;
    ts.fixed = t.number("dt", limits::kTimeStep);
    t.require(ts.fixed <= s.end_time, "dt",
              "must be at most time.end = " + num(s.end_time) + " s, or 'auto'");
  }
  if (t.has("cfl")) {
    t.require(ts.automatic, "cfl", "applies only with dt: auto");
    ts.cfl = t.number("cfl", "(dimensionless)");
    t.require(ts.cfl > 0 && ts.cfl <= 1, "cfl", "must be in (0, 1], got " + num(ts.cfl));
  }
  if (t.has("contact_factor")) {
    t.require(ts.automatic, "contact_factor", "applies only with dt: auto");
    ts.contact_factor = t.number("contact_factor", "(dimensionless)");
    t.require(ts.contact_factor > 0 && ts.contact_factor <= 0.3, "contact_factor",
              "must be in (0, 0.3] (kappa_2 of seed 000 eq. 51; 0.1 is usual), got " +
                  num(ts.contact_factor));
  }
  if (t.has("dt_max")) {
    t.require(ts.automatic, "dt_max", "applies only with dt: auto");
    ts.max = t.number("dt_max", limits::kTimeStep);
  }
  ts.fem_subcycled = t.choice<bool>("fem_integration", {{"explicit", false}, {"subcycled", true}},
                                    ts.fem_subcycled);
}

}  // namespace mpm_sdem::scene
