// Seed 000 sec. 5.4 (Fig. 17-18), extended to every coupling scheme: a one-dimensional elastic
// rod of 400 material points at 2 cm/s hits a free rigid rod of equal mass; the energy the
// contact loses or creates is measured against the grid size d_g = 0.1 to 1.0 cm, with the time
// per step. Table 1 material (hard: K = 5 MPa, G = 3.7 MPa, rho = 2000 kg/m^3), k_n = 6e3 N/m,
// k_t = 3e2 N/m (Table 1 read in cgs, see test/test_imp_collision.cpp), r_p = V_d/2 = 1 mm.
//
// Geometry (the seed gives the point count, the speed, equal masses and that the rigid rod is
// one 1 cm cell long at d_g = 1 cm; the rest is ours): the elastic rod is 4 cm long and one
// point (0.1 mm) thick, the rigid rod a 1 cm capsule of radius 1 mm, its density set for equal
// mass. The rods start 2 mm apart (more than the IMP reach r_p), no gravity; the run ends 60 ms
// after the free approach would close the gap, when the rods have separated.
//
// Reported per scheme and grid size:
//   energy error = |E(end) - E(0)| / E(0), E the kinetic energy of both rods plus the rod's
//                  strain energy (what the contact dissipates or creates);
//   v2 error     = |sum m v^2 (end) - sum m v^2 (0)| / sum m v^2 (0) (the seed's measure; it
//                  also counts the rod's vibration as a loss);
//   block speed  = the rigid rod's speed after the collision (2 cm/s for a perfect exchange);
//   us per step  = wall time per step, and the steps taken (the step is set by CFL and, for
//                  spring schemes, the contact term).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

struct Result {
  Real energy_error, v2_error, block_speed, us_per_step;
  long steps;
};

Result run(CouplingScheme scheme, Real h) {
  const Real L1 = 0.04, s = L1 / 400, L2 = 0.01, a = 0.001, v = 0.02, rho = 2000;
  const Real gap = 0.002;
  WorldDef def;
  def.cell_size = h;
  const Real width = std::ceil((L1 + gap + L2 + 0.04) / h) * h;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(width, std::ceil(0.02 / h) * h);
  def.solver.gravity = Vec2(0, 0);
  // Quadratic B-spline, not seed 000's GIMP: with GIMP this one-point-thick rod at 50 to 100
  // points per cell (l_p = 0.01 to 0.005 cells) became non-finite within 32 steps, before any
  // contact, at d_g = 0.5, 0.6 and 1.0 cm (README, Limitations).
  def.solver.kernel = KernelType::kQuadraticBSpline;
  MaterialDef m;
  m.name = "rod";
  m.density = rho;
  m.bulk_modulus = 5e6;
  m.shear_modulus = 3.7e6;
  def.materials.push_back(m);
  const int ppc = static_cast<int>(std::lround(h / s));  // 10 to 100: one row of 0.1 mm points
  const Real x0 = std::round(0.01 / s) * s;
  const Real y0 = std::round(0.5 * def.domain.max.y() / s) * s;  // a lattice row at y0 + s/2
  BodyDef rod;
  rod.name = "rod";
  rod.shape.type = ShapeType::kRectangle;
  rod.shape.min = Vec2(x0, y0);
  rod.shape.max = Vec2(x0 + L1, y0 + s);
  rod.points_per_cell = ppc;
  rod.velocity = Vec2(v, 0);
  def.bodies.push_back(rod);
  const Real yc = y0 + s / 2;
  // The rod's last points sit s/2 inside its end; the gap is counted from them.
  const Real tip = x0 + L1 - s / 2;
  BlockDef b;
  b.name = "rigid_rod";
  b.core = {Vec2(0, 0), Vec2(L2 - 2 * a, 0)};
  b.rounding = a;
  b.position = Vec2(tip + gap + a, yc);
  b.restitution = 1;
  b.friction = 0.1;
  const Real rod_mass = rho * L1 * s;
  b.density = rod_mass / spheropolygonMass(b.core, a, 1).mass;
  def.blocks.push_back(b);
  def.coupling.scheme = scheme;
  def.coupling.normal_stiffness = 6e3;
  def.coupling.tangential_stiffness = 3e2;
  def.coupling.contact_radius = 0.001;
  def.coupling.verlet_distance = 0.002;
  World w(def);
  const Diagnostics d0 = measure(w);
  const Real e0 = d0.kinetic + d0.elastic;  // kinetic includes the blocks
  const Real end = gap / v + 0.06;
  const auto t0 = std::chrono::steady_clock::now();
  while (w.time() < end) w.step(stepTowards(w.chooseTimeStep().dt, end, w.time()));
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Diagnostics d = measure(w);
  const Real e = d.kinetic + d.elastic;
  return {std::abs(e - e0) / e0, std::abs(d.kinetic - d0.kinetic) / d0.kinetic,
          w.blocks()->state(0).velocity.norm(), 1e6 * sec / w.stepCount(), w.stepCount()};
}

}  // namespace

int main(int argc, char** argv) {
  const char* csv = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--csv") == 0) {
      csv = argv[i + 1];
    } else {
      std::fprintf(stderr, "usage: %s [--csv FILE]\n", argv[0]);
      return 2;
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s [--csv FILE]\n", argv[0]);
    return 2;
  }
  FILE* out = csv ? std::fopen(csv, "w") : nullptr;
  if (csv && !out) {
    std::fprintf(stderr, "cannot write %s\n", csv);
    return 1;
  }
  if (out)
    std::fprintf(out,
                 "scheme,cell_size_m,energy_error,v2_error,block_speed_m_s,us_per_step,steps\n");
  std::printf("%-17s %7s %13s %10s %12s %12s %8s\n", "scheme", "d_g cm", "energy error", "v2 error",
              "block cm/s", "us per step", "steps");
  for (CouplingScheme scheme :
       {CouplingScheme::kImp, CouplingScheme::kImpGrid, CouplingScheme::kMultiVelocity,
        CouplingScheme::kParticleSurface, CouplingScheme::kPartitioned}) {
    for (int k = 1; k <= 10; ++k) {
      const Real h = 0.001 * k;
      const Result r = run(scheme, h);
      std::printf("%-17s %7.1f %13.3e %10.3e %12.4f %12.2f %8ld\n", couplingSchemeName(scheme),
                  100 * h, r.energy_error, r.v2_error, 100 * r.block_speed, r.us_per_step, r.steps);
      std::fflush(stdout);
      if (out)
        std::fprintf(out, "%s,%g,%.6g,%.6g,%.6g,%.4g,%ld\n", couplingSchemeName(scheme), h,
                     r.energy_error, r.v2_error, r.block_speed, r.us_per_step, r.steps);
    }
  }
  if (out) std::fclose(out);
  return 0;
}
