#include "mpm_sdem/scene/scene.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/mesh/mesher.hpp"
#include "yaml_reader.hpp"

namespace mpm_sdem {

namespace {

using scene::Context;
using scene::MapReader;

constexpr Real kDeg = M_PI / 180;

std::string num(Real v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// An override as messages show it: a long one (a pasted file, a 100 kB value) is cut.
std::string shown(const std::string& spec) {
  return spec.size() <= 120
             ? spec
             : spec.substr(0, 120) + "... (" + std::to_string(spec.size()) + " characters)";
}

void applyOverride(YAML::Node root, const std::string& spec, Context& ctx) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError("--set " + shown(spec) + ": expected key=value, e.g. --set time.end=0.5");
  }
  std::vector<std::string> parts;
  std::stringstream keys(spec.substr(0, eq));
  for (std::string part; std::getline(keys, part, '.');) parts.push_back(part);
  YAML::Node cur;
  cur.reset(root);
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& key = parts[i];
    const bool last = i + 1 == parts.size();
    YAML::Node next;
    if (cur.IsSequence()) {
      // A list element by index or by its name field.
      bool found = false;
      for (std::size_t k = 0; k < cur.size() && !found; ++k) {
        const YAML::Node el = cur[k];
        if (key == std::to_string(k) || (el.IsMap() && el["name"] && el["name"].Scalar() == key)) {
          next.reset(el);
          found = true;
        }
      }
      if (!found || last) {
        throw SceneError("--set " + shown(spec) + ": '" + walked + "' has no element '" + key +
                         "' to set a key in (use an index or a name, then a key)");
      }
    } else if (cur.IsMap() || !cur.IsDefined() || cur.IsNull()) {
      if (last) {
        YAML::Node value = YAML::Load(spec.substr(eq + 1));
        cur[key] = value;
        for (const auto& kv : cur) {
          if (kv.first.Scalar() == key) {
            ctx.addOverride(kv.first, shown(spec));
            ctx.addOverride(kv.second, shown(spec));
          }
        }
        return;
      }
      const YAML::Node& const_cur = cur;
      if (!const_cur[key]) cur[key] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[key]);
    } else {
      throw SceneError("--set " + shown(spec) + ": '" + walked + "' is a value, not a section");
    }
    walked += (walked.empty() ? "" : ".") + key;
    cur.reset(next);
  }
}

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
  const std::string memory = sizeProblem(s.world.domain, h, {});
  g.require(memory.empty(), "cell_size", "the grid " + memory);
  s.world.cell_size = h;
}

void parseSolver(const Context& ctx, const MapReader& top, Scene& s) {
  if (!top.has("solver")) return;
  MapReader r(ctx, top.node("solver"), "solver",
              {"kernel", "transfer", "pic_fraction", "asflip_relaxation_time", "stress_update",
               "gravity", "damping"});
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
  r.require(limits::rangeProblem(sol.gravity.norm(), limits::kGravity).empty(), "gravity",
            "its magnitude " + limits::rangeProblem(sol.gravity.norm(), limits::kGravity));
  sol.damping = r.number("damping", "(dimensionless)", sol.damping);
  r.require(
      sol.damping >= 0 && sol.damping < 1, "damping",
      "must be in [0, 1) (0 = none; 0.05 to 0.2 settles a static state), got " + num(sol.damping));
}

void parseTime(const Context& ctx, const MapReader& top, Scene& s) {
  MapReader t(ctx, top.node("time"), "time", {"end", "dt", "cfl", "dt_max", "contact_factor"});
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
}

MaterialDef parseMaterial(const Context& ctx, const YAML::Node& n, const std::string& path) {
  MapReader r(ctx, n, path,
              {"name",           "model",         "density",          "youngs_modulus",
               "poisson_ratio",  "bulk_modulus",  "shear_modulus",    "friction_angle",
               "dilation_angle", "cohesion",      "tensile_strength", "separation_volume_ratio",
               "sound_speed",    "tait_exponent", "viscosity",        "mu_s",
               "mu_2",           "i_0",           "grain_diameter",   "solid_fraction"});
  MaterialDef m;
  m.name = r.name("name");
  m.model = r.choiceOf<MaterialModel>(r.node("model"), r.path("model"),
                                      {{"linear_elastic", MaterialModel::kLinearElastic},
                                       {"drucker_prager", MaterialModel::kDruckerPrager},
                                       {"granular", MaterialModel::kGranular},
                                       {"fluid", MaterialModel::kFluid}});
  m.density = r.number("density", limits::kDensity);
  const bool fluid = m.model == MaterialModel::kFluid;
  const std::vector<const char*> solid_keys = {"youngs_modulus", "poisson_ratio", "bulk_modulus",
                                               "shear_modulus"};
  const std::vector<const char*> fluid_keys = {"sound_speed", "tait_exponent", "viscosity"};
  for (const char* k : fluid ? solid_keys : fluid_keys) {
    r.require(!r.has(k), k,
              fluid ? "applies only to a solid; a fluid's stiffness is its sound_speed"
                    : "applies only to model: fluid");
  }
  const bool e_nu = r.has("youngs_modulus") || r.has("poisson_ratio");
  const bool k_g = r.has("bulk_modulus") || r.has("shear_modulus");
  if (fluid) {
    const Real c = r.number("sound_speed", limits::kSoundSpeed);
    m.bulk_modulus = m.density * c * c;
    r.require(m.bulk_modulus >= limits::kModulus.min && m.bulk_modulus <= limits::kModulus.max,
              "sound_speed",
              "gives a bulk modulus density * sound_speed^2 = " + num(m.bulk_modulus) +
                  " Pa outside [1, 1e13] Pa");
    m.tait_exponent = r.number("tait_exponent", limits::kTaitExponent, 7);
    m.viscosity = r.number("viscosity", limits::kViscosity, 0);
    m.tensile_strength = r.number("tensile_strength", limits::kStrength, 0);
  } else if (e_nu == k_g) {
    ctx.fail(n, path,
             "give the elasticity either as youngs_modulus and poisson_ratio or as "
             "bulk_modulus and shear_modulus (Pa)");
  } else if (e_nu) {
    const Real E = r.number("youngs_modulus", limits::kModulus);
    const Real nu = r.number("poisson_ratio", "(dimensionless)");
    r.require(nu > -1 && nu < 0.5, "poisson_ratio",
              "must be in (-1, 0.5) (0.5 is incompressible), got " + num(nu));
    m.bulk_modulus = E / (3 * (1 - 2 * nu));
    m.shear_modulus = E / (2 * (1 + nu));
  } else {
    m.bulk_modulus = r.number("bulk_modulus", limits::kModulus);
    m.shear_modulus = r.number("shear_modulus", limits::kModulus);
  }
  const char* plastic_keys[] = {"friction_angle", "dilation_angle", "cohesion", "tensile_strength",
                                "separation_volume_ratio"};
  if (m.model == MaterialModel::kDruckerPrager) {
    const Real phi = r.number("friction_angle", "deg");
    r.require(phi >= 0 && phi <= kMaxFrictionAngle / kDeg, "friction_angle",
              "must be in [0, " + num(kMaxFrictionAngle / kDeg) + "] deg, got " + num(phi) +
                  ": the plane-strain Drucker-Prager cone (seed 000 eq. 35) holds no flowing "
                  "slope steeper than 60 deg (docs/scene_reference.md)");
    const Real psi = r.number("dilation_angle", "deg", 0);
    r.require(psi >= 0 && psi <= phi, "dilation_angle",
              "must be in [0, friction_angle] deg, got " + num(psi));
    m.friction_angle = phi * kDeg;
    m.dilation_angle = psi * kDeg;
    m.cohesion = r.number("cohesion", limits::kStrength, 0);
    m.tensile_strength = r.number("tensile_strength", limits::kStrength, 0);
    m.separation_volume_ratio = r.number("separation_volume_ratio", "(dimensionless)", 0);
    r.require(m.separation_volume_ratio == 0 || m.separation_volume_ratio > 1,
              "separation_volume_ratio",
              "must be > 1 (a volume ratio V / V0 looser than the initial packing) or 0 for "
              "off, got " +
                  num(m.separation_volume_ratio));
  } else {
    for (const char* k : plastic_keys) {
      if (fluid && std::string(k) == "tensile_strength") continue;
      r.require(!r.has(k), k, "applies only to model: drucker_prager");
    }
  }
  const char* granular_keys[] = {"mu_s", "mu_2", "i_0", "grain_diameter", "solid_fraction"};
  if (m.model == MaterialModel::kGranular) {
    // Glass beads (Jop, Forterre & Pouliquen 2006): mu_s = tan 20.9 deg = 0.382, mu_2 = tan
    // 32.76 deg = 0.643, I_0 = 0.279, d = 0.53 mm, phi = 0.6.
    m.mu_s = r.number("mu_s", "(dimensionless)");
    r.require(m.mu_s >= 0 && m.mu_s <= 2, "mu_s",
              "must be in [0, 2] (tan of the static friction angle), got " + num(m.mu_s));
    m.mu_2 = r.number("mu_2", "(dimensionless)");
    r.require(m.mu_2 >= m.mu_s && m.mu_2 <= 4, "mu_2",
              "must be in [mu_s, 4] (the friction at large inertial number), got " + num(m.mu_2));
    m.inertial_i0 = r.number("i_0", "(dimensionless)");
    r.require(m.inertial_i0 > 0 && m.inertial_i0 <= 10, "i_0",
              "must be in (0, 10] (0.279 for glass beads), got " + num(m.inertial_i0));
    m.grain_diameter = r.number("grain_diameter", "m");
    r.require(m.grain_diameter > 0 && m.grain_diameter <= 1, "grain_diameter",
              "must be in (0, 1] m, got " + num(m.grain_diameter));
    m.solid_fraction = r.number("solid_fraction", "(dimensionless)", 0.6);
    r.require(m.solid_fraction > 0 && m.solid_fraction < 1, "solid_fraction",
              "must be in (0, 1) (the grains' share of the volume at the critical packing), got " +
                  num(m.solid_fraction));
  } else {
    for (const char* k : granular_keys) r.require(!r.has(k), k, "applies only to model: granular");
  }
  return m;
}

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
                 "points_per_cell", "velocity"});
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
    r.require(limits::rangeProblem(b.velocity.norm(), limits::kSpeed).empty(), "velocity",
              "its magnitude " + limits::rangeProblem(b.velocity.norm(), limits::kSpeed));

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
    const std::string size = sizeProblem(dom, s.world.cell_size, so_far);
    if (!size.empty()) ctx.fail(list[i], path, "with body '" + b.name + "' the world " + size);
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
    c.scheme = r.choice<CouplingScheme>("scheme",
                                        {{"imp", CouplingScheme::kImp},
                                         {"imp_grid", CouplingScheme::kImpGrid},
                                         {"multi_velocity", CouplingScheme::kMultiVelocity},
                                         {"particle_surface", CouplingScheme::kParticleSurface},
                                         {"partitioned", CouplingScheme::kPartitioned}},
                                        c.scheme);
    readSprings(r, c.normal_stiffness, c.tangential_stiffness);
    c.stiffness_per = r.choice<SpringBasis>(
        "stiffness_per", {{"point", SpringBasis::kPerPoint}, {"length", SpringBasis::kPerLength}},
        c.stiffness_per);
    r.require(c.stiffness_per == SpringBasis::kPerPoint || c.scheme == CouplingScheme::kImp ||
                  c.scheme == CouplingScheme::kImpGrid,
              "stiffness_per", "'length' applies to the imp and imp_grid schemes only");
    c.normal_integration =
        r.choice<ContactIntegration>("normal_integration",
                                     {{"explicit", ContactIntegration::kExplicit},
                                      {"exact", ContactIntegration::kExact},
                                      {"subcycled", ContactIntegration::kSubcycled}},
                                     c.normal_integration);
    r.require(c.normal_integration == ContactIntegration::kExplicit ||
                  c.scheme == CouplingScheme::kImp || c.scheme == CouplingScheme::kImpGrid,
              "normal_integration",
              std::string(c.normal_integration == ContactIntegration::kExact ? "'exact'"
                                                                             : "'subcycled'") +
                  " applies to the imp and imp_grid schemes only");
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
  const CouplingScheme scheme = s.world.coupling.scheme;
  if (!s.world.fem_bodies.empty() &&
      (scheme == CouplingScheme::kMultiVelocity || scheme == CouplingScheme::kPartitioned))
    ctx.fail(top.node("coupling")["scheme"], "coupling.scheme",
             std::string(couplingSchemeName(scheme)) +
                 " cannot meet FEM bodies (it needs a body's interior lattice or a wall of its "
                 "own); use particle_surface (seed 002's) or imp");
}

// The SPH region or bodies (seed 001): regions as body shapes, bodies by name.
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
  const CouplingScheme scheme = s.world.coupling.scheme;
  const Problem p = sphProblem(
      d, s.world.cell_size, s.world.solver.stress_update == StressUpdate::kUsf,
      scheme == CouplingScheme::kMultiVelocity || scheme == CouplingScheme::kPartitioned);
  r.require(p.empty(), p.key.c_str(), p.message);
}

// The pictures' quantity and the top of their colour scale; max_value alone colours speeds.
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
    const std::string problem = render::maxValueProblem(c, v);
    r.require(problem.empty(), "max_value",
              problem + " (the top of the " + render::colorByName(c) +
                  " colours; leave it out for the scene's default)");
    s.view.max_value = v;
  }
}

Scene parseTree(const YAML::Node& root, const Context& ctx, const std::string& source) {
  Scene s;
  s.source = source;
  MapReader top(
      ctx, root, "",
      {"name", "description", "domain", "grid", "solver", "time", "materials", "bodies", "output",
       "limits", "blocks", "block_contact", "coupling", "fem_bodies", "sph", "view"});
  s.name = top.has("name") ? top.name("name") : "";
  s.description = top.text("description", "");
  top.require(s.description.size() <= 4096, "description",
              "must be at most 4096 characters, got " + std::to_string(s.description.size()));
  parseDomain(ctx, top, s);
  parseGrid(ctx, top, s);
  parseSolver(ctx, top, s);
  parseTime(ctx, top, s);

  const YAML::Node mats = top.node("materials");
  if (!mats.IsSequence() || mats.size() == 0) {
    ctx.fail(mats, "materials", "expected a list of at least one material");
  }
  std::map<std::string, int> by_name;
  for (std::size_t i = 0; i < mats.size(); ++i) {
    const std::string path = "materials[" + std::to_string(i) + "]";
    MaterialDef m = parseMaterial(ctx, mats[i], path);
    if (by_name.count(m.name))
      ctx.fail(mats[i], path, "a material named '" + m.name + "' exists already");
    by_name[m.name] = static_cast<int>(s.world.materials.size());
    s.world.materials.push_back(std::move(m));
  }
  parseBodies(ctx, top, s, by_name);
  parseBlocks(ctx, top, s);
  parseFemBodies(ctx, top, s);
  parseSph(ctx, top, s);
  if (const std::string p = periodicProblem(s.world); !p.empty())
    ctx.fail(top.node("domain")["walls"], "domain.walls", p.substr(p.find(": ") + 2));

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
        if (!limits::nameProblem(name).empty())
          ctx.fail(kv.first, "output.gauges." + name, limits::nameProblem(name));
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
  parseView(ctx, top, s);
  if (top.has("limits")) {
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
  return s;
}

}  // namespace

namespace {

// Scene::state_text of a parsed tree.
std::string stateText(const YAML::Node& root) {
  YAML::Node state = YAML::Clone(root);
  for (const char* key : {"name", "description", "output", "limits", "view"}) state.remove(key);
  if (state["time"] && state["time"].IsMap()) state["time"].remove("end");
  YAML::Emitter out;
  out << state;
  return out.c_str();
}

}  // namespace

Scene parseScene(const std::string& yaml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw SceneError(source_name + ":" + std::to_string(e.mark.line + 1) + ":" +
                     std::to_string(e.mark.column + 1) + ": not valid YAML: " + e.msg);
  }
  Context ctx(source_name);
  if (!root.IsMap())
    throw SceneError(source_name + ": expected a map of sections (domain, grid, ...)");
  for (const std::string& o : overrides) {
    try {
      applyOverride(root, o, ctx);
    } catch (const YAML::Exception& e) {
      throw SceneError("--set " + shown(o) + ": the value is not valid YAML: " + e.msg);
    }
  }
  Scene s = parseTree(root, ctx, source_name);
  s.state_text = stateText(root);
  return s;
}

namespace {

// A node as one line of YAML, for messages.
std::string flow(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "(absent)";
  YAML::Emitter out;
  out << YAML::Flow << n;
  return out.c_str();
}

// List items are named by their name key when they have one (materials.sand).
std::string itemKey(const YAML::Node& item, std::size_t i) {
  if (item.IsMap() && item["name"] && item["name"].IsScalar()) return item["name"].Scalar();
  return std::to_string(i);
}

void differences(const YAML::Node& a, const YAML::Node& b, const std::string& key,
                 std::vector<std::string>& out) {
  const std::string prefix = key.empty() ? "" : key + ".";
  if (a.IsMap() && b.IsMap()) {
    std::vector<std::string> keys;
    for (const auto& kv : a) keys.push_back(kv.first.Scalar());
    for (const auto& kv : b)
      if (!a[kv.first.Scalar()]) keys.push_back(kv.first.Scalar());
    for (const std::string& k : keys) differences(a[k], b[k], prefix + k, out);
  } else if (a.IsSequence() && b.IsSequence() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      differences(a[i], b[i], prefix + itemKey(b[i], i), out);
  } else if (flow(a) != flow(b)) {
    out.push_back((key.empty() ? "the scene" : key) + ": " + flow(a) + " in the checkpoint, " +
                  flow(b) + " here");
  }
}

}  // namespace

std::vector<std::string> sceneDifferences(const std::string& checkpoint, const std::string& here,
                                          std::size_t max) {
  if (checkpoint == here) return {};
  std::vector<std::string> out;
  try {
    differences(YAML::Load(checkpoint), YAML::Load(here), "", out);
  } catch (const YAML::Exception&) {
    out = {"the scene: the checkpoint's text is not a scene"};
  }
  if (out.empty()) out.push_back("the scene: the same settings, written differently");
  if (out.size() > max) {
    const std::size_t more = out.size() - max;
    out.resize(max);
    out.push_back("and " + std::to_string(more) + " more");
  }
  return out;
}

namespace {

// Why a checkpoint cannot continue a run of this scene: "" or the message.
std::string resumeProblem(const Scene& scene, const CheckpointHeader& h) {
  if (h.build != buildId())
    return "it was written by another build of mpm_sdem: " + buildDifference(h.build, buildId()) +
           ". Continue it with the build that wrote it, or start the run again";
  if (h.scene_hash == sceneHash(scene.state_text) && h.scene == scene.state_text) return "";
  std::string why = "it was written for other scene settings (hash " + h.scene_hash + ", here " +
                    sceneHash(scene.state_text) + "):";
  for (const std::string& d : sceneDifferences(h.scene, scene.state_text)) why += "\n  " + d;
  return why +
         "\nResume with the scene file and --set values it was written with (time.end, output, "
         "limits and view may change)";
}

}  // namespace

void resumeWorld(World& world, const Scene& scene, const std::string& bytes,
                 const std::string& from) {
  if (const std::string p = resumeProblem(scene, readCheckpointHeader(bytes)); !p.empty())
    throw CheckpointError("cannot continue from " + from + ": " + p);
  restoreCheckpoint(world, bytes);
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  // Only a regular file of bounded size: a FIFO would block for ever, /dev/zero never end.
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) throw SceneError(path + ": no such scene file");
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(path + ": not a regular file (a scene is a YAML file)");
  const auto bytes = std::filesystem::file_size(path, error);
  if (error || bytes > limits::kMaxSceneBytes)
    throw SceneError(path + ": " + std::to_string(bytes) + " bytes, more than a scene file's " +
                     std::to_string(limits::kMaxSceneBytes) + "; is this the scene?");
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path, overrides);
}

}  // namespace mpm_sdem
