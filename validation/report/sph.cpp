// Seed 001: the coupled SPH-MPM bar and the SPH region's cases.
// Each function is one case of mpm_sdem_validate: its world (cases.hpp), what it measures and
// the reference it is compared with, written to the report (report.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "report.hpp"

namespace mpm_sdem::report::sph {

// Seed 001 sec. 5.1 and 5.2, the MPM side: reversibility of the copper bar and its static strain
// under a 1 MPa stress boundary condition (seed: -7.8125e-6; the coupled MPM-SPH code there had
// -7.8938e-6).
void bar(const Options& o, Results& r) {
  struct Combo {
    TransferScheme transfer;
    StressUpdate update;
    const char* name;
  };
  for (const Combo& c : {Combo{TransferScheme::kFlip, StressUpdate::kUsf, "FLIP, USF"},
                         Combo{TransferScheme::kFlip, StressUpdate::kUsl, "FLIP, USL"},
                         Combo{TransferScheme::kApic, StressUpdate::kUsf, "APIC, USF"}}) {
    const auto t0 = std::chrono::steady_clock::now();
    const cases::Reversal rv = cases::reversal(c.transfer, c.update);
    const double wall = seconds(t0);
    const std::string settings = "1 cm cells, 2 x 2 points per cell, Courant 0.1, 2 x 500 steps";
    r.add("bar", std::string("reversed velocity error / amplitude, ") + c.name, rv.velocity_error,
          0, "-", "seed 001 sec. 5.1 (exact reversal)", wall, settings);
    r.add("bar", std::string("energy after reversal / initial, ") + c.name, rv.energy_ratio, 1, "-",
          "seed 001 sec. 5.1 (conservation)", wall, settings);
  }
  const std::vector<std::pair<Real, int>> grids =
      o.fast ? std::vector<std::pair<Real, int>>{{0.1, 2}}
             : std::vector<std::pair<Real, int>>{{0.1, 2}, {0.05, 2}, {0.02, 2}, {0.1, 4}};
  for (const auto& [h, ppc] : grids) {
    const auto t0 = std::chrono::steady_clock::now();
    const cases::BarStrain b = cases::stressBar(h, ppc, 1e6, 20, 40);
    const double wall = seconds(t0);
    char q[96], settings[128];
    std::snprintf(q, sizeof q, "static strain, h %g m, %d x %d points per cell", h, ppc, ppc);
    std::snprintf(settings, sizeof settings,
                  "%zu points, %ld steps, ramp 20 and hold 40 transits; ringing %.2g", b.points,
                  b.steps, b.swing);
    r.add("bar", q, b.mean_strain, -7.8125e-6, "-", "seed 001 sec. 5.2 (-sigma / E)", wall,
          settings);
  }
}

// Seed 001 (issue 19): the coupled MPM-SPH method on the seed's four cases, each with its cost,
// and the SPH particles' throughput beside the material points'.
void sph(const Options& o, Results& r) {
  const char* source51 = "seed 001 sec. 5.1 (exact reversal)";
  for (SphKernel k : {SphKernel::kCubicSpline, SphKernel::kWendlandC2}) {
    const auto t0 = std::chrono::steady_clock::now();
    const cases::Reversal rv = cases::reversal(TransferScheme::kFlip, StressUpdate::kUsf,
                                               cases::sphBox(Vec2(0.3, -1), Vec2(0.7, 1), k));
    const double wall = seconds(t0);
    const std::string settings = std::string("SPH in the middle 40%, ") + sphKernelName(k) +
                                 ", no artificial viscosity; 1 cm cells, FLIP, 2 x 500 steps";
    r.add("sph", std::string("reversed velocity error / amplitude, ") + sphKernelName(k),
          rv.velocity_error, 0, "-", source51, wall, settings);
    r.add("sph", std::string("energy after reversal / initial, ") + sphKernelName(k),
          rv.energy_ratio, 1, "-", "seed 001 sec. 5.1 (conservation)", wall, settings);
  }
  for (Real h : o.fast ? std::vector<Real>{0.1} : std::vector<Real>{0.1, 0.05}) {
    const Real x0 = 4 * h;
    const auto t0 = std::chrono::steady_clock::now();
    const cases::BarStrain b = cases::stressBar(
        h, 2, 1e6, 20, 40,
        cases::sphBox(Vec2(x0 + 0.25, -1), Vec2(x0 + 0.75, 1), SphKernel::kCubicSpline, 0.5));
    char q[96], settings[160];
    std::snprintf(q, sizeof q, "static strain, SPH interior, h %g m", h);
    std::snprintf(settings, sizeof settings,
                  "middle half SPH (cubic spline, alpha 0.5), load on the end points; %zu points",
                  b.points);
    r.add("sph", q, b.mean_strain, -7.8125e-6, "-", "seed 001 sec. 5.2 (-sigma / E)", seconds(t0),
          settings, static_cast<long>(b.points), b.steps);
  }
  for (Real h : o.fast ? std::vector<Real>{0.1} : std::vector<Real>{0.1, 0.05, 0.025}) {
    for (bool with : {true, false}) {
      const Real m = 4 * h;
      const auto t0 = std::chrono::steady_clock::now();
      const cases::Biaxial b =
          cases::biaxial(h, with ? cases::sphBox(Vec2(m + 0.25, m + 0.25), Vec2(m + 0.75, m + 0.75),
                                                 SphKernel::kCubicSpline, 0.5)
                                 : SphDef{});
      char q[128];
      std::snprintf(
          q, sizeof q,
          "biaxial: largest deviation of sigma / 1 MPa from 1 on the centre lines, h %g m, %s", h,
          with ? "middle half SPH" : "material points alone");
      r.add("sph", q, b.worst, 0, "-", "seed 001 sec. 6.1 (uniform 1 MPa)", seconds(t0),
            "1 m copper plate, 40 transits, local damping 0.1", 0, b.steps);
    }
  }
  for (int cells : o.fast ? std::vector<int>{4} : std::vector<int>{4, 6, 8}) {
    for (int variant = 0; variant < (o.fast ? 1 : 3); ++variant) {
      const Real h = 0.01;
      SphDef sph;
      const char* what = "material points alone";
      if (variant == 0) {
        sph = cases::holeFrame(h, cells, 4);
        what = "SPH frame 1.5a-3a";
      } else if (variant == 2) {
        sph = cases::holeFrame(h, cells, 4, 0, 3);
        what = "SPH up to the hole (r < 3a)";
      }
      // The fast form (CI's validate_fast: finite results) at a sixth of the transits.
      const int transits = o.fast ? 10 : 60;
      const auto t0 = std::chrono::steady_clock::now();
      const cases::PlateHole p = cases::plateWithHole(h, cells, 4, sph, transits);
      const double wall = seconds(t0);
      char q[128], settings[160];
      std::snprintf(settings, sizeof settings,
                    "a = %d cells, plate 8a under Kirsch's tractions, %d transits, %s; edge point "
                    "%.3f of %.3f",
                    cells, transits, what, p.edge, p.edge_expected);
      std::snprintf(q, sizeof q, "hole: fitted concentration factor, a = %d cells, %s", cells,
                    what);
      r.add("sph", q, p.fitted_concentration, 3, "-", "Kirsch (seed 001 sec. 6.2)", wall, settings,
            p.particles, p.steps);
      std::snprintf(q, sizeof q, "hole: largest sigma_yy error on the mid line, a = %d cells, %s",
                    cells, what);
      r.add("sph", q, p.worst_inside, 0, "-", "Kirsch, complete stencils (seed 001 sec. 6.2)", wall,
            settings, p.particles, p.steps);
    }
  }
  for (bool with : {false, true}) {
    const cases::Throughput t = cases::throughput(0.02, with, o.fast ? 20 : 200);
    char settings[160];
    std::snprintf(
        settings, sizeof settings,
        "1 m plate, 2 cm cells, %ld points, stable step %.3g s, SPH stage %.0f%% of the step",
        t.particles, t.dt, 100 * t.sph_share);
    r.add("sph",
          std::string("particle-steps per second, ") + (with ? "all SPH" : "all material points"),
          t.particle_steps_per_second, std::numeric_limits<double>::quiet_NaN(), "1/s",
          "cost (no reference)", 0, settings, t.particles);
  }
}

}  // namespace mpm_sdem::report::sph
