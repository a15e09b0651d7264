// mpm_sdem_plate: one intrusion of the RFT plate (cases::Plate, the report's cases `intrusion`
// and `intrusion_transfer`) at any cell, angle, direction, speed, gravity and transfer, for
// the runs the report cannot afford (1.25 mm: 256,000 points, 50-80 minutes each;
// docs/robots.md, Intrusion forces). Prints what the report measures of such a run: for a
// push (gamma > 0) the lines F = a + k z over its window and the mean force there, for a drag
// (gamma = 0) the mean force over its last 1.5 L; and the forces per mm of travel with
// --curve FILE. --checkpoint FILE: a checkpoint every 10 minutes of wall time, from which the
// same command continues a run that was stopped (cases::PlateCheckpoints).
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/terrain.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

int usage(const char* program, FILE* to = stderr) {
  std::fprintf(to,
               "usage: %s [--cell M] [--angle DEG] [--direction DEG] [--speed M/S] [--depth M]\n"
               "          [--gravity M/S2] [--friction-angle DEG] [--cohesion PA] [--reach M]\n"
               "          [--transfer apic|asflip] [--separation J (0: off, or > 1)]\n"
               "          [--threads N] [--curve FILE] [--surface FILE] [--checkpoint FILE]\n"
               "          [--kernel gimp|quadratic|cubic] [--points-per-cell N] [--scheme NAME]\n"
               "          [--thickness M] [--rounding M] [--friction MU] [--restitution E (0, 1]]\n"
               "          [--wake 0|1] [--average 0|1]\n"
               "          [--step-scale S (0, 1]: time.cfl and contact_factor times S]\n"
               "  defaults: cases::Plate's (5 mm, beta 0, gamma 90: the flat plate pushed\n"
               "  straight down at 0.1 m/s, the blade's sand under gravity, APIC); --depth is\n"
               "  a drag's (gamma 0) depth; --surface FILE: the layer's top at the end, per cell\n",
               program);
  return to == stderr ? 2 : 0;
}

// The kernels by the names --kernel takes, and as the run's line prints them.
struct KernelName {
  const char* option;
  KernelType kernel;
  const char* printed;
};
constexpr KernelName kKernels[] = {
    {"quadratic", KernelType::kQuadraticBSpline, "quadratic B-spline"},
    {"cubic", KernelType::kCubicBSpline, "cubic B-spline"},
    {"gimp", KernelType::kGimp, "GIMP"}};

const KernelName* kernelNamed(const char* option) {
  for (const KernelName& k : kKernels)
    if (!std::strcmp(k.option, option)) return &k;
  return nullptr;
}

const char* kernelName(KernelType kernel) {
  for (const KernelName& k : kKernels)
    if (k.kernel == kernel) return k.printed;
  return "?";
}

// The coupling scheme a scene names `name`, if any.
std::optional<CouplingScheme> schemeNamed(const char* name) {
  for (const SchemeTraits& t : couplingSchemes())
    if (!std::strcmp(t.name, name)) return t.scheme;
  return std::nullopt;
}

// The layer's top at the end of the run (heightProfile, per column of one cell), as heights
// above the bed's initial surface (m) written to f (then closed). Printed: the highest ahead of
// the plate (the heap it pushes) and the lowest within L behind it (the trough it leaves).
void writeSurface(const World& w, const cases::Plate& c, FILE* f) {
  const Real h = c.cell_size;
  const int columns = static_cast<int>(std::ceil(c.width / h));
  std::vector<Real> top;
  heightProfile(w.particles(), 0, h, columns, top);
  const Vec2 plate = w.blocks()->state(0).position;
  std::fprintf(f, "x_m,top_m\n");
  Real ahead = -c.bed, behind = c.bed;
  for (int k = 0; k < columns; ++k) {
    const Real x = (k + 0.5) * h, z = top[k] - c.bed;  // NaN: an empty column
    std::fprintf(f, "%.6f,%.6f\n", x, z);
    if (x > plate.x()) ahead = std::fmax(ahead, z);
    if (x < plate.x() && x > plate.x() - c.length) behind = std::fmin(behind, z);
  }
  std::fclose(f);
  std::printf("surface: heap ahead %.4f m, trough within L behind %.4f m (plate at x %.4f m)\n",
              ahead, behind, plate.x());
}

}  // namespace

int main(int argc, char** argv) {
  cases::Plate c;
  std::string curve, surface;
  cases::PlateCheckpoints checkpoints;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") return usage(argv[0], stdout);
    if (i + 1 >= argc) return usage(argv[0]);
    const char* v = argv[++i];
    char* end = nullptr;
    const double x = std::strtod(v, &end);
    const bool number = end != v && *end == '\0';
    if (a == "--curve")
      curve = v;
    else if (a == "--surface")
      surface = v;
    else if (a == "--checkpoint")
      checkpoints.path = v;
    else if (a == "--transfer" && !std::strcmp(v, "apic"))
      c.transfer = TransferScheme::kApic;
    else if (a == "--transfer" && !std::strcmp(v, "asflip"))
      c.transfer = TransferScheme::kAsflip;
    else if (a == "--kernel" && kernelNamed(v))
      c.kernel = kernelNamed(v)->kernel;
    else if (a == "--scheme" && schemeNamed(v))
      c.scheme = *schemeNamed(v);
    else if (!number)
      return usage(argv[0]);
    else if (a == "--cell" && x >= 1e-4)
      c.cell_size = x;
    else if (a == "--angle" && x >= -90 && x <= 90)
      c.angle = x;
    else if (a == "--direction" && x >= 0 && x <= 90)
      c.direction = x;
    else if (a == "--speed" && x > 0)
      c.speed = x;
    else if (a == "--depth" && x > 0 && x < c.bed)
      c.depth = x;
    else if (a == "--separation" && (x == 0 || x > 1))
      c.separation = x;
    else if (a == "--cohesion" && x >= 0)
      c.cohesion = x;
    else if (a == "--reach" && x > 0 && x < c.bed)
      c.reach = x;
    else if (a == "--gravity" && x >= 0)
      c.gravity = x;
    else if (a == "--friction-angle" && x >= 0 && x < 60)
      c.friction_angle = x;
    else if (a == "--points-per-cell" && x >= 1 && x <= 8 && x == static_cast<int>(x))
      c.points_per_cell = static_cast<int>(x);
    else if (a == "--thickness" && x > 0)
      c.thickness = x;
    else if (a == "--rounding" && x > 0)
      c.rounding = x;
    else if (a == "--friction" && x >= 0)
      c.friction = x;
    else if (a == "--restitution" && x > 0 && x <= 1)
      c.restitution = x;
    else if (a == "--wake" && (x == 0 || x == 1))
      c.wake = x == 1;
    else if (a == "--average" && (x == 0 || x == 1))
      c.volumetric_average = x == 1;
    else if (a == "--step-scale" && x > 0 && x <= 1)
      c.step_scale = x;
    else if (a == "--threads" && x >= 1)
      omp_set_num_threads(static_cast<int>(x));
    else
      return usage(argv[0]);
  }
  // Opened before the run, so that a path that cannot be written does not cost a long run.
  FILE* curve_file = curve.empty() ? nullptr : std::fopen(curve.c_str(), "w");
  if (!curve.empty() && !curve_file)
    return std::fprintf(stderr, "cannot write %s\n", curve.c_str()), 1;
  FILE* surface_file = surface.empty() ? nullptr : std::fopen(surface.c_str(), "w");
  if (!surface.empty() && !surface_file)
    return std::fprintf(stderr, "cannot write %s\n", surface.c_str()), 1;
  const WorldDef def = cases::plateIntrusion(c);
  const Real rho_l_v2 = def.materials.at(0).density * c.length * c.speed * c.speed;
  World w(def);
  const cases::PlateRun r = cases::movePlate(w, c, checkpoints);
  std::printf(
      "h %g m, beta %g deg, gamma %g deg, v %g m/s, g %g m/s^2, phi %g deg, %s: %zu points, "
      "%ld steps, %.0f s\n",
      c.cell_size, c.angle, c.direction, c.speed, c.gravity, c.friction_angle,
      c.transfer == TransferScheme::kAsflip ? "ASFLIP" : "APIC", r.points, r.steps, r.seconds);
  std::printf("%s, %d points per cell side, %s, plate %g m thick (rounding %g m), mu %g%s\n",
              kernelName(c.kernel), c.points_per_cell, couplingSchemeName(c.scheme), c.thickness,
              c.rounding, c.friction, c.wake ? "" : ", no sand behind it");
  const Real L = c.length;
  if (c.volumetric_average) std::printf("divergence averaged over the nodes\n");
  if (c.cohesion > 0)
    std::printf("cohesion %g Pa: Prandtl's (2 + pi) c L = %.2f N/m\n", c.cohesion,
                (2 + M_PI) * c.cohesion * L);
  if (c.direction > 0) {
    const cases::PlateLines l = cases::pushLines(c, r);
    const Vec2 m = cases::pushMean(c, r);
    std::printf(
        "push: F_z = %.2f N/m + %.1f N/m^2 z (alpha_z %.4g N/m^3), F_x = %.2f + %.1f z, "
        "|F| as z^%.3f\n",
        l.az, l.kz, l.kz / L, l.ax, l.kx, l.exponent);
    std::printf("mean over z %.4f m to the reach: F_x %.2f, F_z %.2f N/m, F_z / (rho L v^2) %.4f\n",
                cases::pushWindowStart(c), m.x(), m.y(), m.y() / rho_l_v2);
  } else {
    const Vec2 m = cases::dragMean(c, r);
    std::printf("drag at %g m: F_x %.2f, F_z %.2f N/m, alpha_x %.4g N/m^3\n", c.depth, m.x(), m.y(),
                -m.x() / (c.depth * L));
  }
  if (surface_file) writeSurface(w, c, surface_file);
  if (FILE* f = curve_file) {
    std::fprintf(f, "travel_m,depth_m,fx_n_m,fz_n_m\n");
    for (std::size_t k = 0; k < r.depth.size(); ++k)
      std::fprintf(f, "%.6f,%.6f,%.4f,%.4f\n", r.travel[k], r.depth[k], r.fx[k], r.fz[k]);
    std::fclose(f);
  }
  return 0;
}
