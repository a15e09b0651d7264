// mpm_sdem_chute: the periodic chute of the report's case `chute` (cases::Chute) from a start
// perturbed by up to --perturb metres, printing at every --every seconds the profile against
// Bagnold's (cases::chuteProfile) and whether the points' volumes still fit their spacing
// (cases::chuteVolume), the grid's L2 error against Bagnold's profile and the nodes' largest
// over-fill (issue 79): the measurements behind docs/method.md's account of the runaway at
// 1.25 mm (issue 41) and of the volume fit (--fit, SolverDef::volume_fit). --film swaps the beads
// for the Newtonian film whose Nusselt surface speed is Bagnold's (as test_chute's disabled film
// test).
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cases.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/stepper.hpp"

using namespace mpm_sdem;

namespace {

int usage(const char* program, FILE* to = stderr) {
  std::fprintf(to,
               "usage: %s [--cell M] [--angle DEG] [--end S] [--every S] [--perturb M]\n"
               "          [--seed N] [--transfer apic|asflip] [--film] [--threads N]\n"
               "          [--ppc N] [--relax S] [--grain M] [--fit] [--usl] [--average]\n"
               "          [--basilisk] [--step-scale S]\n"
               "  defaults: 2.5 mm cells, 27 deg, 3 s, every 0.25 s, perturbed by 1e-5 m\n"
               "  (seed 1; 0: the symmetric start), 4 mm grains (--grain: the beads' own\n"
               "  are 0.53 mm), volume fit off (--fit: on), USF (--usl: USL),\n"
               "  (seed 1; 0: the symmetric start), ASFLIP (cases::chute's), 1 thread, 2 x 2\n"
               "  points per cell (--ppc 1-4), ASFLIP kept whole (--relax: its departure's\n"
               "  relaxation time in s); below\n"
               "  21 deg the beads do not flow (the profile's columns are then meaningless),\n"
               "  and --film needs a flowing angle; --average: the divergence average\n"
               "  (solver.volumetric_average); --basilisk: the report's cross_chute instead\n"
               "  (cases::CrossChute: Basilisk's mu(I), 24.64 deg unless --angle, from Bagnold's\n"
               "  profile); --step-scale: the CFL factor times S (0.5: the step halved)\n",
               program);
  return to == stderr ? 2 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  cases::Chute c;
  c.cell_size = 0.0025;
  c.theta = 27 * M_PI / 180;
  Real end = 3, every = 0.25, perturb = 1e-5, relax = 0, step_scale = 1;
  unsigned seed = 1;
  int threads = 1, ppc = 2;
  bool film = false, apic = false, fit = false, usl = false, average = false, basilisk = false;
  bool angle_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") return usage(argv[0], stdout);
    if (a == "--film" || a == "--fit" || a == "--usl" || a == "--average" || a == "--basilisk") {
      (a == "--film"      ? film
       : a == "--fit"     ? fit
       : a == "--usl"     ? usl
       : a == "--average" ? average
                          : basilisk) = true;
      continue;
    }
    if (i + 1 >= argc) return usage(argv[0]);
    const char* v = argv[++i];
    char* stop = nullptr;
    const double x = std::strtod(v, &stop);
    const bool number = stop != v && *stop == '\0';
    if (a == "--transfer" && (!std::strcmp(v, "apic") || !std::strcmp(v, "asflip")))
      apic = !std::strcmp(v, "apic");
    else if (!number)
      return usage(argv[0]);
    else if (a == "--cell" && x >= 2e-4 && x <= 0.01)
      c.cell_size = x;
    else if (a == "--angle" && x >= 0 && x < 32)  // below mu_2's angle (32.76 deg)
      c.theta = x * M_PI / 180, angle_given = true;
    else if (a == "--end" && x > 0)
      end = x;
    else if (a == "--every" && x > 0)
      every = x;
    else if (a == "--perturb" && x >= 0)
      perturb = x;
    else if (a == "--seed" && x >= 0 && x == std::floor(x))
      seed = static_cast<unsigned>(x);
    else if (a == "--grain" && x >= 1e-4 && x <= 0.01)
      c.grain = x;
    else if (a == "--step-scale" && x > 0 && x <= 1)
      step_scale = x;
    else if (a == "--relax" && x >= 0)
      relax = x;
    else if (a == "--ppc" && x >= 1 && x <= 4 && x == std::floor(x))
      ppc = static_cast<int>(x);
    else if (a == "--threads" && x >= 1 && x == std::floor(x))
      threads = static_cast<int>(x);
    else
      return usage(argv[0]);
  }
  if (perturb >= 0.1 * c.cell_size) return usage(argv[0]);  // a tenth of a cell at most
  // The film's viscosity is set from Bagnold's surface speed, which needs a flowing angle.
  if (film && c.theta <= 20.9 * M_PI / 180) return usage(argv[0]);  // mu_s = tan 20.9 deg
  omp_set_num_threads(threads);
  cases::CrossChute cross;
  cross.cell_size = c.cell_size;
  cross.transfer = apic ? TransferScheme::kApic : TransferScheme::kAsflip;
  if (basilisk) {
    if (angle_given) cross.theta = c.theta;
    c.theta = cross.theta;
    c.depth = cross.depth;
    c.grain = cases::crossChuteRheology(cross).grain;
    if (film) return usage(argv[0]);
  }
  WorldDef def = basilisk ? cases::crossSolverChute(cross) : cases::chute(c);
  def.solver.volumetric_average = average;
  def.time_step.cfl *= step_scale;
  if (apic) def.solver.transfer = TransferScheme::kApic;
  def.bodies[0].points_per_cell = ppc;
  if (relax > 0) def.solver.asflip_relaxation_time = relax;
  def.solver.volume_fit = fit;
  if (usl) def.solver.stress_update = StressUpdate::kUsl;
  const Real surface = cases::bagnoldProfile(def.materials[0], c.theta, c.depth, c.depth);
  if (film) {  // Nusselt's surface speed rho g sin(theta) h^2 / (2 eta) set to Bagnold's
    MaterialDef& m = def.materials[0];
    m.model = MaterialModel::kFluid;
    m.viscosity = m.density * 9.81 * std::sin(c.theta) * c.depth * c.depth / (2 * surface);
    m.tensile_strength = 100;
  }
  World w(def);
  if (basilisk) cases::startOnBagnold(w, cross);
  if (perturb > 0) perturbPositions(w.particles(), perturb, seed);
  std::printf(
      "h %g m, %g deg, d %g m, %s%s%s%s%s, perturbed by %g m: %zu points, Bagnold's surface "
      "speed %.4f m/s\n",
      c.cell_size, c.theta * 180 / M_PI, c.grain, basilisk ? "Basilisk's chute, " : "",
      film ? "Newtonian film, " : "", apic ? "APIC" : "ASFLIP", fit ? ", volume fit" : "",
      average ? ", divergence average" : "", perturb, w.particles().size(), surface);
  std::printf(
      "t (s), steps, worst layer / surface speed, top layer / Bagnold's, max |v_y| (m/s), "
      "points at J >= 1, phi min-max (mean) below the top two cells, their mean J, L2 error, "
      "largest over-fill, points the last step's fit moved\n");
  long steps = 0;
  for (Real next = every; w.time() < end - 1e-12; next = std::min(end, next + every)) {
    while (!reachedEnd(w.time(), next)) {
      if (!stepStable(w, next).finite) {
        std::printf("not finite at t = %.4f s\n", w.time());
        return 3;
      }
      ++steps;
    }
    const cases::ChuteProfile e = cases::chuteProfile(w, c);
    const cases::ChuteVolume v = cases::chuteVolume(w, c);
    std::printf("%.3f %ld %.4f %.3f %.3e %ld %.4f-%.4f (%.5f) %.5f %.4f %.4f %ld\n", w.time(),
                steps, e.worst, e.surface, v.vy_max, v.separated, v.phi_min, v.phi_max, v.phi_mean,
                v.j_mean, e.l2, w.largestOverfill(), w.lastVolumeFit().moved);
    std::fflush(stdout);
  }
  return 0;
}
