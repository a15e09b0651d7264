// Robot interfaces against terramechanics: the driven wheel and the blade (Reece's equation).
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

namespace mpm_sdem::report::robots {

// Issue 20's wheel (config/scenes/wheel.yaml): a rigid wheel driven at omega R = 0.1 m/s and
// towed at (1 - slip) omega R over dry sand (phi = 30 deg), at two loads. Terramechanics has no
// closed form for a rigid wheel in a Drucker-Prager continuum; its measured trends (Bekker 1969,
// Wong and Reece 1967) are: drawbar pull rises with slip, sinkage with load and with slip
// (slip sinkage), motion resistance with sinkage, and neither the gross thrust T / R nor the
// pull exceeds Coulomb's W tan(phi) for a cohesionless soil (Bekker's maximum thrust; a smooth
// wheel of friction 0.6 > tan 30 deg does not slip on its rim first). The rows give DP/W and
// T/(W R) against that bound and the sinkage; the 5 mm runs show the resolution's effect.
// The wheel rig's sweep (slip x load x cell) with the scene's Drucker-Prager sand or, for issue
// 41, the granular sand that flows where it does (cases::matchedGranular).
// One run per slip, load and cell (each its own run of a split report, Options::part).
struct WheelRun {
  Real slip, load, h;
};
std::vector<WheelRun> wheelRunList(bool fast) {
  if (fast) return {{0.1, 200, 0.01}, {0.7, 200, 0.01}};
  std::vector<WheelRun> runs;
  for (Real load : {200.0, 400.0})
    for (Real slip : {0.0, 0.1, 0.2, 0.4, 0.7}) runs.push_back({slip, load, 0.01});
  for (Real load : {200.0, 400.0})
    for (Real slip : {0.0, 0.4, 0.7}) runs.push_back({slip, load, 0.005});
  return runs;
}
int wheelRuns(bool fast) {
  return static_cast<int>(wheelRunList(fast).size());
}

void wheelSweep(const Options& o, Results& r, bool granular) {
  const char* name = granular ? "wheel_granular" : "wheel";
  const std::vector<WheelRun> runs = wheelRunList(o.fast);
  const Real t_end = o.fast ? 0.5 : 1.5;
  const std::string path = std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/wheel.yaml";
  FILE* sweep = std::fopen((o.out + "/" + name + "_sweep.csv").c_str(), "w");
  std::fprintf(sweep, "cell_m,load_n_m,slip,pull_n_m,pull_sd_n_m,torque_nm_m,sinkage_m\n");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const WheelRun& run = runs[i];
    Scene scene = loadScene(path, {"grid.cell_size=" + std::to_string(run.h)});
    cases::setWheelRig(scene.world, run.slip, run.load);
    const Real bound = std::tan(scene.world.materials[0].friction_angle);  // radians here
    // Grains of 1 mm: a sand's, well below the wheel's contact length.
    if (granular) scene.world.materials[0] = cases::matchedGranular(scene.world.materials[0], 1e-3);
    World w(scene.world);
    const auto start = std::chrono::steady_clock::now();
    const cases::WheelRun m = cases::runWheel(w, t_end);
    const double wall = seconds(start);
    std::fprintf(sweep, "%g,%g,%g,%.5g,%.4g,%.5g,%.5g\n", run.h, run.load, run.slip, m.pull,
                 m.pull_spread, m.torque, m.sinkage);
    char at[96], settings[160];
    std::snprintf(at, sizeof at, ", W = %g N/m, slip %g, h %g mm", run.load, run.slip, 1e3 * run.h);
    std::snprintf(settings, sizeof settings,
                  "%.1f s, mean over the second half; pull sd %.3g N/m; %zu points", t_end,
                  m.pull_spread, w.particles().size());
    const std::string src = "Coulomb bound tan(phi) (Bekker 1969): never reached";
    const long points = static_cast<long>(w.particles().size());
    r.add(name, std::string("drawbar pull / load") + at, m.pull / run.load, bound, "-", src, wall,
          settings, points, w.stepCount());
    r.add(name, std::string("gross thrust T / (W R)") + at, m.torque / (run.load * m.radius), bound,
          "-", src, wall, settings, points, w.stepCount());
    r.add(name, std::string("sinkage") + at, m.sinkage, 0, "m",
          "rises with load and slip (Bekker; Wong and Reece)", wall, settings, points,
          w.stepCount());
  }
  std::fclose(sweep);
}

void wheel(const Options& o, Results& r) {
  wheelSweep(o, r, false);
}
void wheelGranular(const Options& o, Results& r) {
  wheelSweep(o, r, true);
}

// Issue 20: the excavator blade (cases::excavatorBlade) against Reece's fundamental earth-moving
// equation with McKyes' N_gamma for a wide blade (cases::reece): a vertical blade, smooth
// (delta = 0, where the planar wedge is Rankine's passive state, an exact solution) and rough
// (friction 0.3, delta = 16.7 deg, where a planar failure surface is known to overestimate the
// passive force), at three depths and three cell sizes each. The force is read over the blade's
// advance x from 0.05 d to 0.3 d (the heap ahead of it then still small): its line's value at
// x = 0 (onset: a level surface, q = 0) and its mean (against Reece with the surcharge
// q = gamma r x of the wedge's rise at the window's middle). Per cell size and per friction: the
// exponent of the onset force against d; per depth: the onset force extrapolated to h = 0 from
// the two finest cells (first order: the blade's edge smeared over a cell or two makes the
// failing wedge deeper by a length proportional to h). Then the blade's speed and time step (the
// grid transfers dissipate in the shear bands, per step), and a deeper layer (the floor).
// "2.5 mm" for 0.0025 m.
std::string millimetres(Real metres) {
  char t[32];
  std::snprintf(t, sizeof t, "%g mm", 1000 * metres);
  return t;
}

void blade(const Options& o, Results& r) {
  FILE* series = std::fopen((o.out + "/blade.csv").c_str(), "w");
  std::fprintf(series,
               "friction,depth_m,cell_m,speed_m_s,start,displacement_m,horizontal_n_m,"
               "vertical_n_m,reece_n_m\n");
  const std::vector<Real> depths = {0.04, 0.06, 0.08};
  const std::vector<Real> cells =
      o.fast ? std::vector<Real>{0.01} : std::vector<Real>{0.01, 0.005, 0.0025};
  const Real from = 0.05, to = 0.3;
  const std::string source = "Reece / McKyes (1985) N_gamma, planar wedge";
  struct Run {
    cases::BladeForce force;
    Real reece = 0;
  };
  auto push = [&](const cases::Blade& c, const std::string& tag) {
    World w(cases::excavatorBlade(c));
    const cases::BladePush p = cases::pushBlade(w, c, to * c.depth);
    const cases::BladeForce f = cases::bladeForce(p, c.depth, from, to);
    const Real reece = cases::reeceHorizontal(c);
    for (std::size_t i = 0; i < p.displacement.size(); ++i)
      std::fprintf(series, "%g,%g,%g,%g,%s,%.6g,%.6g,%.6g,%.6g\n", c.friction, c.depth, c.cell_size,
                   c.speed, c.geostatic ? "eased" : "scene", p.displacement[i], p.horizontal[i],
                   p.vertical[i], reece);
    std::fflush(series);
    const Real phi = flowingFrictionAngle(c.friction_angle * M_PI / 180);
    const cases::Reece k = cases::reece(c.rake * M_PI / 180, phi, std::atan(c.friction));
    const Real rise = cases::wedgeRise(c), mid = 0.5 * (from + to) * c.depth;
    char settings[320];
    std::snprintf(settings, sizeof settings,
                  "d/h %.0f, v %g m/s (v^2/(g d) %.4f), %zu points, %ld steps; onset %.1f +- %.1f "
                  "N/m, mean %.1f +- %.1f, peak %.1f, vertical %.1f (Reece %.1f); phi %.1f deg, "
                  "delta %.1f deg, beta %.1f deg, N_gamma %.3f",
                  c.depth / c.cell_size, c.speed, c.speed * c.speed / (9.81 * c.depth), p.points,
                  p.steps, f.onset, f.onset_error, f.mean, f.mean_error, f.peak, f.vertical,
                  std::fabs(k.vertical) < 1e-9 ? 0.0 : 1500 * 9.81 * c.depth * c.depth * k.vertical,
                  phi * 180 / M_PI, std::atan(c.friction) * 180 / M_PI, k.beta * 180 / M_PI,
                  k.n_gamma);
    r.add("blade", "onset force" + tag, f.onset, reece, "N/m", source + " (q = 0)", p.seconds,
          settings, static_cast<long>(p.points), p.steps);
    // Reece's q term for the heap: q = gamma r x over the wedge, N_q = 2 N_gamma.
    r.add("blade", "mean force" + tag, f.mean, reece * (1 + 2 * rise * mid / c.depth), "N/m",
          source + " with q = gamma r x at x = 0.175 d", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
    return Run{f, reece};
  };
  auto name = [](Real mu, Real d, Real h) {
    char t[96];
    std::snprintf(t, sizeof t, ", friction %.1f, d %.0f cm, h %.1f mm", mu, 100 * d, 1000 * h);
    return std::string(t);
  };
  auto power = [&](const std::string& q, const cases::PowerLaw& k, const std::string& over) {
    r.add("blade", q, k.exponent, 2, "-", "Reece (gamma d^2 N_gamma)", 0,
          "+- " + std::to_string(k.error).substr(0, 5) + " (standard error), " + over);
  };
  for (const Real mu : {0.0, 0.3}) {
    std::vector<std::vector<Run>> runs;  // [cell][depth]
    const std::string tag = mu == 0 ? ", friction 0.0" : ", friction 0.3";
    for (const Real h : cells) {
      runs.emplace_back();
      std::vector<Real> onset, error;
      for (const Real d : depths) {
        cases::Blade c;
        c.depth = d;
        c.cell_size = h;
        c.friction = mu;
        runs.back().push_back(push(c, name(mu, d, h)));
        onset.push_back(runs.back().back().force.onset);
        error.push_back(runs.back().back().force.onset_error);
      }
      power("exponent of the onset force in d" + tag + ", h " + millimetres(h),
            cases::powerLaw(depths, onset, error), "d 4, 6, 8 cm");
    }
    if (cells.size() < 3) continue;
    // The onset force over Reece's against h / d over the nine runs: R0 + A h / d, least
    // squares; R0 is the converged ratio if the error is of first order in h / d.
    LineFit fit;
    for (std::size_t k = 0; k < cells.size(); ++k)
      for (std::size_t i = 0; i < depths.size(); ++i)
        fit.add(cells[k] / depths[i], runs[k][i].force.onset / runs[k][i].reece);
    const Real slope = fit.slope(), r0 = (fit.sy - slope * fit.sx) / fit.n;
    Real see = 0;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      for (std::size_t i = 0; i < depths.size(); ++i) {
        const Real e =
            runs[k][i].force.onset / runs[k][i].reece - r0 - slope * cells[k] / depths[i];
        see += e * e;
      }
    }
    const Real sxx = fit.sxx - fit.sx * fit.sx / fit.n;
    const Real r0_error =
        std::sqrt(see / (fit.n - 2) * (1 / fit.n + fit.sx * fit.sx / fit.n / fit.n / sxx));
    {
      char settings[160];
      const std::string q = "onset force / Reece at h / d -> 0" + tag;
      std::snprintf(settings, sizeof settings,
                    "R0 + A h / d over the nine runs: R0 +- %.3f (standard error), A %.2f, "
                    "residuals %.3f rms",
                    r0_error, slope, std::sqrt(see / fit.n));
      r.add("blade", q, r0, 1, "-", source + " (q = 0)", 0, settings);
    }
    // Per depth, Richardson from the two finest cells (first order).
    std::vector<Real> extrapolated, error;
    for (std::size_t i = 0; i < depths.size(); ++i) {
      const cases::BladeForce& fine = runs[cells.size() - 1][i].force;
      const cases::BladeForce& coarse = runs[cells.size() - 2][i].force;
      extrapolated.push_back(2 * fine.onset - coarse.onset);
      error.push_back(std::hypot(2 * fine.onset_error, coarse.onset_error));
      char settings[160];
      const std::string q = "onset force at h -> 0" + tag + ", d " +
                            std::to_string(std::lround(100 * depths[i])) + " cm";
      std::snprintf(settings, sizeof settings, "2 F(%.1f mm) - F(%.1f mm) +- %.1f N/m",
                    1000 * cells.back(), 1000 * cells[cells.size() - 2], error.back());
      r.add("blade", q, extrapolated.back(), runs.back()[i].reece, "N/m", source + " (q = 0)", 0,
            settings);
    }
    power(std::string("exponent of the onset force in d") + tag + ", h -> 0",
          cases::powerLaw(depths, extrapolated, error), "Richardson per depth, d 4, 6, 8 cm");
    // At the same h / d: d = 4 cm against 8 cm with the cell halved and kept.
    for (std::size_t k = 0; k + 1 < cells.size(); ++k) {
      const Run &a = runs[k + 1][0], &b = runs[k][2];  // d 4 cm at h / 2, d 8 cm at h
      const std::string q = "exponent of the onset force in d" + tag + ", h / d 1/" +
                            std::to_string(std::lround(depths[2] / cells[k]));
      power(q,
            cases::powerLaw({depths[0], depths[2]}, {a.force.onset, b.force.onset},
                            {a.force.onset_error, b.force.onset_error}),
            "d 4 cm at h " + millimetres(cells[k + 1]) + " and 8 cm at " + millimetres(cells[k]));
    }
  }
  if (!o.fast) {
    // The speed and the step at one depth and cell: the force grows with v and with the steps
    // per second (kappa_1 halved), not as the sand's inertia (rho v^2 d, 0.2% here) would.
    for (const Real mu : {0.0, 0.3}) {
      for (const Real v : {0.025, 0.1}) {
        cases::Blade c;
        c.friction = mu;
        c.speed = v;
        c.ramp = 0.05 * 0.05 / v;  // over the same advance
        char t[64];
        std::snprintf(t, sizeof t, ", v %g m/s", v);
        push(c, name(mu, c.depth, c.cell_size) + t);
      }
    }
    cases::Blade c;
    c.friction = 0;
    WorldDef def = cases::excavatorBlade(c);
    def.time_step.cfl = 0.15;
    World w(def);
    const cases::BladePush p = cases::pushBlade(w, c, to * c.depth);
    const cases::BladeForce f = cases::bladeForce(p, c.depth, from, to);
    r.add("blade", "onset force" + name(0, c.depth, c.cell_size) + ", cfl 0.15", f.onset,
          cases::reeceHorizontal(c), "N/m", source + " (q = 0)", p.seconds,
          "kappa_1 0.15 instead of 0.3: twice the steps", static_cast<long>(p.points), p.steps);
    // The shipped scene file's start: the layer unstressed under gravity and the blade at full
    // speed at once (a scene has no initial stress and no speed schedule).
    {
      cases::Blade scene;
      scene.geostatic = false;
      scene.ramp = 0;
      push(scene, name(scene.friction, scene.depth, scene.cell_size) +
                      ", as config/scenes/excavator_blade.yaml starts");
    }
    // The floor 1.5 d below the edge instead of d.
    for (const Real mu : {0.0, 0.3}) {
      cases::Blade deep;
      deep.depth = 0.08;
      deep.friction = mu;
      deep.bed = 0.2;
      push(deep, name(mu, deep.depth, deep.cell_size) + ", layer 20 cm");
    }
  }
  std::fclose(series);
}

// Issue 41: the blade of `blade` in the granular sand (cases::Blade::Sand::kGranular: mu(I) with
// mu_s = sin 33.0 deg, the Drucker-Prager sand's flowing in-plane angle, so that Reece's force is
// the same) at the Drucker-Prager sand's stiffness (E = 1 MPa) and at a soft dense state (E = 50
// kPa, nu 0.3: a 4.5 times longer CFL step), smooth (friction 0: Rankine's exact passive state)
// and rough (friction 0.3), d = 4, 6, 8 cm at 5 mm cells: the onset and mean forces against
// Reece's as in `blade`, the exponent of the onset force in d, and the steps and wall time per
// simulated second (one thread: OMP_NUM_THREADS=1). Then the Drucker-Prager blade at d 6 cm for
// the same wall time on the same machine; at d 6 cm, 5 mm: the step halved, the soft state with
// its coupling springs subcycled (its step is otherwise the springs', not its CFL step); d 6 cm
// at 2.5 mm cells (first the stiffness whose onsets are nearer Reece's); and a push to x = d.
// --fast: d 6 cm at 5 mm only (both stiffnesses, both frictions, and the Drucker-Prager blade).
void bladeGranular(const Options& o, Results& r) {
  FILE* series = std::fopen((o.out + "/blade_granular.csv").c_str(), "w");
  std::fprintf(series,
               "sand,young_pa,friction,depth_m,cell_m,cfl,displacement_m,horizontal_n_m,"
               "vertical_n_m,reece_n_m\n");
  const std::vector<Real> depths =
      o.fast ? std::vector<Real>{0.06} : std::vector<Real>{0.04, 0.06, 0.08};
  const Real from = 0.05, to = 0.3;
  const std::string source = "Reece / McKyes (1985) N_gamma, planar wedge";
  const char* kCase = "blade_granular";
  struct Run {
    cases::BladeForce force;
    Real reece = 0;
  };
  auto label = [](const cases::Blade& c) {
    char t[96];
    if (c.sand == cases::Blade::Sand::kDruckerPrager)
      std::snprintf(t, sizeof t, "Drucker-Prager E %g kPa", c.young_modulus / 1e3);
    else
      std::snprintf(t, sizeof t, "granular E %g kPa", c.young_modulus / 1e3);
    return std::string(t);
  };
  // step: the factor on both bounds of the step (kappa_1 and kappa_2 of eq. 51); subcycled: the
  // coupling springs in substeps, so that they no longer bound the material's step.
  auto push = [&](const cases::Blade& c, Real step, bool subcycled = false) {
    WorldDef def = cases::excavatorBlade(c);
    def.time_step.cfl *= step;
    def.time_step.contact_factor *= step;
    const Real kappa1 = def.time_step.cfl;
    if (subcycled) def.coupling.normal_integration = ContactIntegration::kSubcycled;
    World w(def);
    const cases::BladePush p = cases::pushBlade(w, c, to * c.depth);
    const cases::BladeForce f = cases::bladeForce(p, c.depth, from, to);
    const Real reece = cases::reeceHorizontal(c);
    const bool granular = c.sand == cases::Blade::Sand::kGranular;
    for (std::size_t i = 0; i < p.displacement.size(); ++i)
      std::fprintf(series, "%s,%g,%g,%g,%g,%g,%.6g,%.6g,%.6g,%.6g\n",
                   granular ? "granular" : "drucker_prager", c.young_modulus, c.friction, c.depth,
                   c.cell_size, kappa1, p.displacement[i], p.horizontal[i], p.vertical[i], reece);
    std::fflush(series);
    const Real simulated = w.time();
    const Real steps_per_s = p.steps / simulated, wall_per_s = p.seconds / simulated;
    const Real phi = cases::bladeFrictionAngle(c);
    const Real rise = cases::wedgeRise(c), mid = 0.5 * (from + to) * c.depth;
    char tag[160];
    std::snprintf(tag, sizeof tag, ", %s, friction %.1f, d %.0f cm, h %.1f mm%s%s",
                  label(c).c_str(), c.friction, 100 * c.depth, 1000 * c.cell_size,
                  step != 1 ? ", step halved (kappa_1 0.15, kappa_2 0.05)" : "",
                  subcycled ? ", subcycled springs" : "");
    char settings[440];
    std::snprintf(settings, sizeof settings,
                  "d/h %.0f, %zu points, %ld steps (%ld bounded by the springs) over %.3f s "
                  "simulated (%.0f per s), %.1f s wall (%.1f per simulated s); onset %.1f +- %.1f "
                  "N/m, mean %.1f +- %.1f, peak %.1f, vertical %.1f; in-plane phi %.2f deg, delta "
                  "%.1f deg, cfl %g",
                  c.depth / c.cell_size, p.points, p.steps, p.contact_steps, simulated, steps_per_s,
                  p.seconds, wall_per_s, f.onset, f.onset_error, f.mean, f.mean_error, f.peak,
                  f.vertical, phi * 180 / M_PI, std::atan(c.friction) * 180 / M_PI, kappa1);
    std::printf(
        "  %s: onset %.1f +- %.1f N/m (Reece %.1f, ratio %.3f), mean %.1f +- %.1f, peak "
        "%.1f, %ld steps (%ld spring-bound), %.0f steps/s, %.1f s wall per simulated s\n",
        tag + 2, f.onset, f.onset_error, reece, f.onset / reece, f.mean, f.mean_error, f.peak,
        p.steps, p.contact_steps, steps_per_s, wall_per_s);
    r.add(kCase, std::string("onset force") + tag, f.onset, reece, "N/m", source + " (q = 0)",
          p.seconds, settings, static_cast<long>(p.points), p.steps);
    r.add(kCase, std::string("mean force") + tag, f.mean, reece * (1 + 2 * rise * mid / c.depth),
          "N/m", source + " with q = gamma r x at x = 0.175 d", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
    r.add(kCase, std::string("steps per simulated second") + tag, steps_per_s, 0, "1/s",
          "(measured; issue 40 expected about 4,000 for the scene)", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
    r.add(kCase, std::string("wall time per simulated second") + tag, wall_per_s, 0, "s",
          "(measured, one thread; 2 for 0.5 x real time)", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
    return Run{f, reece};
  };
  auto granular = [](Real young, Real friction, Real depth, Real cell) {
    cases::Blade c;
    c.sand = cases::Blade::Sand::kGranular;
    c.young_modulus = young;
    c.friction = friction;
    c.depth = depth;
    c.cell_size = cell;
    return c;
  };
  const std::vector<Real> stiffnesses = {1e6, 5e4};
  std::vector<Real> miss(stiffnesses.size(), 0);  // mean |onset / Reece - 1| per stiffness
  for (std::size_t k = 0; k < stiffnesses.size(); ++k) {
    for (const Real mu : {0.0, 0.3}) {
      std::vector<Real> onset, error;
      for (const Real d : depths) {
        const Run run = push(granular(stiffnesses[k], mu, d, 0.005), 1);
        onset.push_back(run.force.onset);
        error.push_back(run.force.onset_error);
        miss[k] += std::fabs(run.force.onset / run.reece - 1);
      }
      if (depths.size() < 3) continue;
      const cases::PowerLaw law = cases::powerLaw(depths, onset, error);
      char q[160];
      std::snprintf(q, sizeof q,
                    "exponent of the onset force in d, granular E %g kPa, friction %.1f, h 5.0 mm",
                    stiffnesses[k] / 1e3, mu);
      r.add(kCase, q, law.exponent, 2, "-", "Reece (gamma d^2 N_gamma)", 0,
            "+- " + std::to_string(law.error).substr(0, 5) + " (standard error), d 4, 6, 8 cm");
    }
  }
  // The Drucker-Prager blade at d 6 cm: its wall time on the same machine.
  for (const Real mu : {0.0, 0.3}) {
    cases::Blade c;
    c.friction = mu;
    push(c, 1);
  }
  if (!o.fast) {
    // The step halved (both its bounds: the soft state's is the springs'): the force should not
    // move with it beyond its noise.
    for (const Real young : stiffnesses)
      for (const Real mu : {0.0, 0.3}) push(granular(young, mu, 0.06, 0.005), 0.5);
    // The soft dense state's step is bounded by the coupling springs (kappa_2 of eq. 51), not
    // by its CFL term: with the springs subcycled the material's step is its own; and halved.
    for (const Real step : {1.0, 0.5})
      for (const Real mu : {0.0, 0.3}) push(granular(stiffnesses[1], mu, 0.06, 0.005), step, true);
    // d 6 cm at 2.5 mm cells: first the stiffness nearer Reece at 5 mm, then the other.
    const std::size_t better = miss[0] <= miss[1] ? 0 : 1;
    for (const std::size_t k : {better, 1 - better})
      for (const Real mu : {0.0, 0.3}) push(granular(stiffnesses[k], mu, 0.06, 0.0025), 1);
    // A longer push (to x = d) at d 6 cm: the soft dense state mobilises its resistance over more
    // of the advance (its passive strain, K_p gamma d / E, is 20 times the stiff state's), so
    // its onset, read from 0.05 d to 0.3 d, is that of a force still rising. The mean over 0.5 d
    // to d, against Reece with the surcharge of the wedge's rise at 0.75 d.
    for (const Real young : stiffnesses) {
      for (const Real mu : {0.0, 0.3}) {
        const cases::Blade c = granular(young, mu, 0.06, 0.005);
        World w(cases::excavatorBlade(c));
        const cases::BladePush p = cases::pushBlade(w, c, c.depth);
        const cases::BladeForce f = cases::bladeForce(p, c.depth, 0.5, 1.0);
        const Real reece = cases::reeceHorizontal(c);
        for (std::size_t i = 0; i < p.displacement.size(); ++i)
          std::fprintf(series, "granular_long,%g,%g,%g,%g,%g,%.6g,%.6g,%.6g,%.6g\n", young, mu,
                       c.depth, c.cell_size, w.def().time_step.cfl, p.displacement[i],
                       p.horizontal[i], p.vertical[i], reece);
        char q[160], settings[200];
        std::snprintf(q, sizeof q,
                      "mean force over x 0.5 d to d, granular E %g kPa, friction %.1f, d 6 cm, h "
                      "5.0 mm",
                      young / 1e3, mu);
        std::snprintf(settings, sizeof settings,
                      "mean %.1f +- %.1f N/m, peak %.1f, line %.1f + %.0f x; %ld steps, %.1f s "
                      "wall over %.3f s simulated",
                      f.mean, f.mean_error, f.peak, f.onset, f.slope, p.steps, p.seconds, w.time());
        std::printf("  %s: %s\n", q, settings);
        r.add(kCase, q, f.mean, reece * (1 + 2 * cases::wedgeRise(c) * 0.75), "N/m",
              source + " with q = gamma r x at x = 0.75 d", p.seconds, settings,
              static_cast<long>(p.points), p.steps);
      }
    }
  }
  std::fclose(series);
}

// Issue 44: intrusion forces against resistive force theory (cases::Plate; Li, Zhang & Goldman
// 2013). A 5 cm plate (5 mm thick, friction 0.3) in the blade's sand: pushed from above the
// surface along gamma = 90 deg (down) and 45 deg at six angles beta, its force fitted as a line
// in the centre's depth z over z from just covered + 1 cm to 9 cm (RFT: F = alpha z L, the line
// through 0: the intercept and the exponent of |F| in z say how linear); dragged along +x
// (gamma = 0) at 4, 6 and 8 cm at four angles, each the mean over the last 1.5 L of a 3 L drag
// (alpha from the line through the three depths). One scale factor zeta for the medium, fitted
// by least squares to every alpha_x and alpha_z of the report's cell against RFT's generic
// shapes, then each alpha against zeta times the generic one. The plate pushed down at 0.5 to
// 2 m/s: sqrt(v^2 / (g z)) to 2.9 at z = 5 cm; the force at z = 6 cm against the quasi-static
// one plus lambda rho L v^2 (dynamic RFT, Agarwal et al. 2021, Sci. Adv. 7: lambda of about 1).
// Refinement: the push (beta 0, gamma 90) and the drag (beta 90, 6 cm) at 1 cm, 5 mm, 2.5 mm.
// One run per plate motion (intrusionRunList); the fits across them: intrusionFits.
// --fast: 1 cm cells, beta 0, 45, 90 pushed down, 0 along 45 deg, the vertical plate dragged
// at 4 and 8 cm, and one push at 1 m/s.
namespace {

struct IntrusionRun {
  Real beta, gamma, speed, depth, h;  // deg, deg, m/s, m (drags), m
  TransferScheme transfer = TransferScheme::kApic;
  Real g = 9.81, phi = 35;  // m/s^2; the sand's friction angle (deg)
};

constexpr Real kIntrusionReference = 0.06;  // m: the depth at which speeds are compared

std::vector<IntrusionRun> intrusionRunList(bool fast) {
  std::vector<IntrusionRun> runs;
  const Real h = fast ? 0.01 : 0.005;
  if (fast) {
    for (Real beta : {0.0, 45.0, 90.0}) runs.push_back({beta, 90, 0.1, 0, h});
    runs.push_back({0, 45, 0.1, 0, h});
    for (Real d : {0.04, 0.08}) runs.push_back({90, 0, 0.1, d, h});
    runs.push_back({0, 90, 1.0, 0, h});
    return runs;
  }
  for (Real gamma : {90.0, 45.0})
    for (Real beta : {-60.0, -30.0, 0.0, 30.0, 60.0, 90.0})
      runs.push_back({beta, gamma, 0.1, 0, h});
  for (Real beta : {-45.0, 0.0, 45.0, 90.0})
    for (Real d : {0.04, 0.06, 0.08}) runs.push_back({beta, 0, 0.1, d, h});
  for (Real v : {0.5, 1.0, 1.5, 2.0}) runs.push_back({0, 90, v, 0, h});
  for (Real cell : {0.01, 0.0025}) {
    runs.push_back({0, 90, 0.1, 0, cell});
    runs.push_back({90, 0, 0.1, 0.06, cell});
  }
  return runs;
}

cases::Plate plateOf(const IntrusionRun& run) {
  cases::Plate c;
  c.angle = run.beta;
  c.direction = run.gamma;
  c.speed = run.speed;
  c.depth = run.depth;
  c.cell_size = run.h;
  c.transfer = run.transfer;
  c.gravity = run.g;
  c.friction_angle = run.phi;
  return c;
}

}  // namespace

int intrusionRuns(bool fast) {
  return static_cast<int>(intrusionRunList(fast).size());
}

namespace {

// One run of a list: the plate moved, its series written, its result added to `r` under
// `name`, and its row (every digit: the fits read it back) written to `table`. `medium`: five
// more columns (intrusion_transfer's): the run's transfer, gravity and friction angle, and the
// mean forces (a push's over its window, cases::pushMean; a drag's as above).
void intrusionRun(const IntrusionRun& run, const std::string& name, bool medium, FILE* table,
                  FILE* series, Results& r) {
  const cases::Plate c = plateOf(run);
  World w(cases::plateIntrusion(c));
  const cases::PlateRun p = cases::movePlate(w, c);
  const bool asflip = run.transfer == TransferScheme::kAsflip;
  for (std::size_t k = 0; k < p.depth.size(); ++k) {
    std::fprintf(series, "%g,%g,%g,%g,%g,%.6g,%.6g,%.6g,%.6g", run.beta, run.gamma, run.speed,
                 run.depth, run.h, p.travel[k], p.depth[k], p.fx[k], p.fz[k]);
    if (medium) std::fprintf(series, ",%d,%g,%g", asflip, run.g, run.phi);
    std::fprintf(series, "\n");
  }
  std::fflush(series);
  // A push: lines F = a + k z over the window, and the exponent of |F| in z there. A drag:
  // the means over the last half of its 3 L.
  Real fx = 0, fz = 0, kx = NAN, kz = NAN, ax = NAN, az = NAN, exponent = NAN;
  char q[160], settings[240];
  const std::string medium_name =
      medium ? std::string(asflip ? ", ASFLIP" : ", APIC") + (run.g > 0 ? "" : ", no gravity") +
                   (run.phi == 35 ? "" : ", phi " + std::to_string(std::lround(run.phi)))
             : "";
  const Real from = cases::pushWindowStart(c);
  if (run.gamma > 0 && run.g == 0) {  // inertia alone: the window's mean (the fits' lambda_0)
    const Vec2 mean = cases::pushMean(c, p);
    fz = mean.y();
    std::snprintf(q, sizeof q, "mean F_z over z %.3f-%.3f m, v %g m/s, h %s%s", from, c.reach,
                  run.speed, millimetres(run.h).c_str(), medium_name.c_str());
    r.add(name, q, fz, 0, "N/m", "(lambda_0 in the case's fits)", p.seconds, "",
          static_cast<long>(p.points), p.steps);
  } else if (run.gamma > 0) {
    const cases::PlateLines l = cases::pushLines(c, p);
    kx = l.kx, kz = l.kz, ax = l.ax, az = l.az, exponent = l.exponent;
    fx = ax + kx * kIntrusionReference;
    fz = az + kz * kIntrusionReference;
    std::snprintf(q, sizeof q, "exponent of |F| in z, beta %g, gamma %g, v %g m/s, h %s%s",
                  run.beta, run.gamma, run.speed, millimetres(run.h).c_str(), medium_name.c_str());
    std::snprintf(settings, sizeof settings,
                  "z %.3f-%.3f m: F_x = %.1f + %.0f z, F_z = %.1f + %.0f z (N/m); at z = 6 cm "
                  "F_x %.1f, F_z %.1f N/m",
                  from, c.reach, ax, kx, az, kz, fx, fz);
    r.add(name, q, exponent, 1, "-", "RFT: F = alpha |z| L (Li et al. 2013)", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
  } else {
    const Vec2 mean = cases::dragMean(c, p);
    fx = mean.x(), fz = mean.y();
    std::snprintf(q, sizeof q, "drag force per depth, beta %g, z %.0f cm, h %s%s", run.beta,
                  100 * run.depth, millimetres(run.h).c_str(), medium_name.c_str());
    std::snprintf(settings, sizeof settings,
                  "mean over travel 1.5-3 L: F_x %.2f, F_z %.2f N/m; |F| / (z L) against "
                  "zeta |alpha_gen| in the fits",
                  fx, fz);
    r.add(name, q, std::hypot(fx, fz) / (run.depth * c.length), 0, "N/m^3",
          "(fitted across runs: " + name + "'s fits)", p.seconds, settings,
          static_cast<long>(p.points), p.steps);
  }
  std::fprintf(table,
               "%.17g,%.17g,%.17g,%.17g,%.17g,%zu,%ld,%.4g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
               "%.17g",
               run.beta, run.gamma, run.speed, run.depth, run.h, p.points, p.steps, p.seconds, fx,
               fz, kx, kz, ax, az, exponent);
  if (medium) {
    const Vec2 mean = run.gamma > 0 ? cases::pushMean(c, p) : Vec2(fx, fz);
    std::fprintf(table, ",%d,%.17g,%.17g,%.17g,%.17g", asflip, run.g, run.phi, mean.x(), mean.y());
  }
  std::fprintf(table, "\n");
  std::fflush(table);
}

// The row of `run` in a table written with the medium's columns (runIntrusionList's `medium`).
std::size_t mediumRow(const Table& t, const IntrusionRun& run, const std::string& name) {
  const bool asflip = run.transfer == TransferScheme::kAsflip;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t.at(i, "beta_deg") == run.beta && t.at(i, "gamma_deg") == run.gamma &&
        t.at(i, "speed_m_s") == run.speed && t.at(i, "depth_m") == run.depth &&
        t.at(i, "cell_m") == run.h && t.at(i, "asflip") == asflip &&
        t.at(i, "gravity_m_s2") == run.g && t.at(i, "phi_deg") == run.phi)
      return i;
  throw std::runtime_error(name + ".csv lacks a run (were all the case's runs gathered?)");
}

// The runs of `list` that `o` selects, into <out>/<name>.csv and <name>_series.csv.
void runIntrusionList(const Options& o, Results& r, const std::vector<IntrusionRun>& list,
                      const std::string& name, bool medium) {
  FILE* table = std::fopen((o.out + "/" + name + ".csv").c_str(), "w");
  FILE* series = std::fopen((o.out + "/" + name + "_series.csv").c_str(), "w");
  const char* columns = medium ? ",asflip,gravity_m_s2,phi_deg,mean_fx_n_m,mean_fz_n_m\n" : "\n";
  std::fprintf(table,
               "beta_deg,gamma_deg,speed_m_s,depth_m,cell_m,points,steps,wall_s,fx_n_m,fz_n_m,"
               "kx_n_m2,kz_n_m2,ax_n_m,az_n_m,exponent%s",
               columns);
  std::fprintf(series,
               "beta_deg,gamma_deg,speed_m_s,depth_set_m,cell_m,travel_m,depth_m,fx_n_m,"
               "fz_n_m%s",
               medium ? ",asflip,gravity_m_s2,phi_deg\n" : "\n");
  for (std::size_t i = 0; i < list.size(); ++i)
    if (o.runs(static_cast<int>(i))) intrusionRun(list[i], name, medium, table, series, r);
  std::fclose(table);
  std::fclose(series);
}

}  // namespace

void intrusion(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionRunList(o.fast), "intrusion", false);
}

void intrusionFits(const Options& o, Results& r) {
  const Table t(o.out + "/intrusion.csv");
  const std::vector<IntrusionRun> runs = intrusionRunList(o.fast);
  const Real h0 = runs.front().h, L = cases::Plate().length, rho = 1500;
  const std::string rft = "RFT, Li et al. 2013: zeta x generic alpha";
  auto find = [&](const IntrusionRun& run) -> std::size_t {
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t.at(i, "beta_deg") == run.beta && t.at(i, "gamma_deg") == run.gamma &&
          t.at(i, "speed_m_s") == run.speed && t.at(i, "depth_m") == run.depth &&
          t.at(i, "cell_m") == run.h)
        return i;
    throw std::runtime_error("intrusion.csv lacks a run (were all the case's runs gathered?)");
  };
  // The measured alphas (N/m^3) at the report's cell and 0.1 m/s, each with RFT's generic one:
  // pushes from their lines' slopes, drags from the line through their depths per beta.
  struct Alpha {
    std::string what;
    Real beta, gamma, x, z;
    Real exponent;
    cases::RftStress generic;
  };
  std::vector<Alpha> alphas;
  std::vector<Real> drag_betas;
  for (const IntrusionRun& run : runs) {
    if (run.h != h0 || run.speed != 0.1) continue;
    const std::size_t i = find(run);
    if (run.gamma > 0) {
      alphas.push_back({"pushed", run.beta, run.gamma, -t.at(i, "kx_n_m2") / L,
                        t.at(i, "kz_n_m2") / L, t.at(i, "exponent"),
                        cases::rftGeneric(run.beta * M_PI / 180, run.gamma * M_PI / 180)});
    } else if (std::find(drag_betas.begin(), drag_betas.end(), run.beta) == drag_betas.end()) {
      drag_betas.push_back(run.beta);
    }
  }
  for (const Real beta : drag_betas) {
    LineFit lx, lz, log_f;
    int n = 0;
    for (const IntrusionRun& run : runs) {
      if (run.h != h0 || run.gamma != 0 || run.beta != beta) continue;
      const std::size_t i = find(run);
      lx.add(run.depth, t.at(i, "fx_n_m"));
      lz.add(run.depth, t.at(i, "fz_n_m"));
      log_f.add(std::log(run.depth), std::log(std::hypot(t.at(i, "fx_n_m"), t.at(i, "fz_n_m"))));
      ++n;
    }
    alphas.push_back({"dragged", beta, 0, -lx.slope() / L, lz.slope() / L,
                      n > 1 ? log_f.slope() : NAN, cases::rftGeneric(beta * M_PI / 180, 0)});
  }
  // zeta: least squares over both components of every alpha.
  Real num = 0, den = 0;
  for (const Alpha& a : alphas) {
    num += a.x * a.generic.x + a.z * a.generic.z;
    den += a.generic.x * a.generic.x + a.generic.z * a.generic.z;
  }
  const Real zeta = num / den;
  Real residual = 0, scale = 0;
  for (const Alpha& a : alphas) {
    residual += std::pow(a.x - zeta * a.generic.x, 2) + std::pow(a.z - zeta * a.generic.z, 2);
    scale += std::pow(zeta * a.generic.x, 2) + std::pow(zeta * a.generic.z, 2);
  }
  const Real rms = std::sqrt(residual / (2 * alphas.size()));
  const Real rms_scale = std::sqrt(scale / (2 * alphas.size()));
  {
    char settings[200];
    std::snprintf(settings, sizeof settings,
                  "least squares over %zu alphas (x and z) at h %s: rms residual %.0f N/m^3, "
                  "%.3f of the rms of zeta alpha_gen",
                  alphas.size(), millimetres(h0).c_str(), rms, rms / rms_scale);
    r.add("intrusion", "zeta (RFT's scale factor for this sand)", zeta, 0, "-",
          "fitted: one factor for every angle", 0, settings);
    r.add("intrusion", "rms residual / rms zeta alpha_gen", rms / rms_scale, 0, "-",
          "RFT's generic shapes (0 where they hold exactly)", 0, settings);
  }
  for (const Alpha& a : alphas) {
    char q[128], settings[160];
    std::snprintf(settings, sizeof settings, "%s; generic alpha_x %.3f, alpha_z %.3f N/cm^3",
                  a.what.c_str(), a.generic.x / 1e6, a.generic.z / 1e6);
    std::snprintf(q, sizeof q, "alpha_z, beta %g, gamma %g", a.beta, a.gamma);
    r.add("intrusion", q, a.z, zeta * a.generic.z, "N/m^3", rft, 0, settings);
    std::snprintf(q, sizeof q, "alpha_x, beta %g, gamma %g", a.beta, a.gamma);
    r.add("intrusion", q, a.x, zeta * a.generic.x, "N/m^3", rft, 0, settings);
    if (a.gamma == 0 && std::isfinite(a.exponent)) {
      std::snprintf(q, sizeof q, "exponent of |F| in z, beta %g dragged", a.beta);
      r.add("intrusion", q, a.exponent, 1, "-", "RFT: F = alpha |z| L", 0,
            "the drags' mean forces at their depths");
    }
  }
  // The scale-free ratio: the vertical plate dragged against the horizontal plate pushed down.
  const Alpha *drag = nullptr, *push = nullptr;
  for (const Alpha& a : alphas) {
    if (a.gamma == 0 && a.beta == 90) drag = &a;
    if (a.gamma == 90 && a.beta == 0) push = &a;
  }
  if (drag && push)
    r.add("intrusion", "alpha_x(beta 90, dragged) / alpha_z(beta 0, pushed down)",
          drag->x / push->z, drag->generic.x / push->generic.z, "-",
          "RFT's generic shapes (no zeta)", 0, "");
  // The horizontal plate pushed down is a strip footing (width B = L) sinking into the layer:
  // bearing capacity theory gives its force as q B = gamma z N_q B + gamma B^2 N_gamma / 2, a
  // line in z whose intercept RFT leaves out (significant while z is not large against B).
  // cases::bearingFactors at the sand's flowing in-plane angle (bladeFrictionAngle, 33.0 deg).
  for (const IntrusionRun& run : runs) {
    if (run.h != h0 || run.speed != 0.1 || run.gamma != 90 || run.beta != 0) continue;
    const std::size_t i = find(run);
    const Real phi = cases::bladeFrictionAngle(cases::Blade());
    const cases::BearingFactors f = cases::bearingFactors(phi);
    const Real nq = f.n_q, ng = f.n_gamma, gamma = rho * 9.81;
    char settings[160];
    std::snprintf(settings, sizeof settings,
                  "phi %.1f deg: N_q %.1f, N_gamma %.1f; the push's line F_z = a + k z over its "
                  "window",
                  phi * 180 / M_PI, nq, ng);
    const std::string source = "bearing capacity: Prandtl-Reissner N_q, Meyerhof N_gamma";
    r.add("intrusion", "slope k of F_z in z, beta 0 pushed down", t.at(i, "kz_n_m2"),
          gamma * nq * L, "N/m^2", source + " (gamma N_q B)", 0, settings);
    r.add("intrusion", "intercept a of F_z, beta 0 pushed down", t.at(i, "az_n_m"),
          0.5 * gamma * L * L * ng, "N/m", source + " (gamma B^2 N_gamma / 2)", 0, settings);
  }
  // Speed: the force at 6 cm of the horizontal plate pushed down, F_0 + c v^2 over the speeds.
  {
    LineFit fit;
    std::vector<std::pair<Real, Real>> forces;
    for (const IntrusionRun& run : runs) {
      if (run.h != h0 || run.gamma != 90 || run.beta != 0) continue;
      const Real f = t.at(find(run), "fz_n_m");
      fit.add(run.speed * run.speed, f);
      forces.emplace_back(run.speed, f);
    }
    if (forces.size() > 1) {
      const Real lambda = fit.slope() / (rho * L), f0 = fit.intercept();
      for (const auto& [v, f] : forces) {
        char q[96], settings[160];
        std::snprintf(q, sizeof q, "F_z at z 6 cm, beta 0 pushed down, v %g m/s", v);
        std::snprintf(settings, sizeof settings,
                      "reference F_0 + rho L v^2 (lambda 1), F_0 = %.1f N/m from the line in v^2; "
                      "sqrt(v^2 / (g z)) %.2f",
                      f0, v / std::sqrt(9.81 * kIntrusionReference));
        r.add("intrusion", q, f, f0 + rho * L * v * v, "N/m", "dynamic RFT (Agarwal et al. 2021)",
              0, settings);
      }
      char settings[160];
      std::snprintf(settings, sizeof settings,
                    "F = F_0 + lambda rho L v^2 over %zu speeds (0.1 to %g m/s), rho 1500 kg/m^3, "
                    "L 5 cm",
                    forces.size(), forces.back().first);
      r.add("intrusion", "lambda (the v^2 term's coefficient)", lambda, 1, "-",
            "dynamic RFT (Agarwal et al. 2021): about 1", 0, settings);
      // Whether the excess over the slowest push grows as v^2 at all: its exponent in v.
      LineFit excess;
      for (const auto& [v, f] : forces)
        if (v > forces.front().first && f > forces.front().second)
          excess.add(std::log(v), std::log(f - forces.front().second));
      if (excess.n >= 2)
        r.add("intrusion", "exponent of F(v) - F(0.1 m/s) in v", excess.slope(), 2, "-",
              "dynamic RFT: the excess as v^2", 0, "over the faster speeds");
    }
  }
  // Refinement: the push (beta 0) and the drag (beta 90, 6 cm) at every cell size run.
  for (const bool dragged : {false, true}) {
    std::vector<std::pair<Real, Real>> values;  // (h, alpha)
    for (const IntrusionRun& run : runs) {
      if (run.speed != 0.1 || (dragged ? run.gamma != 0 || run.beta != 90 || run.depth != 0.06
                                       : run.gamma != 90 || run.beta != 0))
        continue;
      const std::size_t i = find(run);
      values.emplace_back(run.h,
                          dragged ? -t.at(i, "fx_n_m") / (run.depth * L) : t.at(i, "kz_n_m2") / L);
    }
    if (values.size() < 2) continue;
    std::sort(values.begin(), values.end(), [](auto a, auto b) { return a.first > b.first; });
    const cases::RftStress g = cases::rftGeneric(dragged ? M_PI / 2 : 0, dragged ? 0 : M_PI / 2);
    for (std::size_t k = 0; k < values.size(); ++k) {
      char q[128], settings[96] = "";
      std::snprintf(q, sizeof q, "%s, h %s",
                    dragged ? "alpha_x, beta 90 dragged at 6 cm (F_x / (z L))"
                            : "alpha_z, beta 0 pushed down (slope / L)",
                    millimetres(values[k].first).c_str());
      if (k > 0)
        std::snprintf(settings, sizeof settings, "%+.1f%% from h %s",
                      100 * (values[k].second / values[k - 1].second - 1),
                      millimetres(values[k - 1].first).c_str());
      r.add("intrusion", q, values[k].second, zeta * (dragged ? g.x : g.z), "N/m^3", rft, 0,
            settings);
    }
  }
}

// Issue 44: what the intrusion case's forces owe to the transfer, and the v^2 term alone. The
// horizontal plate pushed down (as intrusion's), its force the mean over the push's window z =
// 1.25-9 cm (cases::pushMean: a fast push rings with the layer's waves), at 1 cm and 5 mm with
// APIC and with ASFLIP:
// - at 0.1, 1 and 2 m/s in the sand under gravity: lambda from the excess over 0.1 m/s;
// - without gravity, so that nothing but inertia loads the plate (in a rigid medium F = lambda_0
//   rho L v^2, lambda_0 fixed by the medium's friction and the shape: there is no other stress
//   scale), at 1 and 2 m/s, in the sand and in a medium without shear strength (phi 0: the
//   points carry pressure only). A plate that gives the material it sweeps its own speed feels
//   rho L v^2 (lambda_0 = 1, dynamic RFT's inertial term); a steady plate with an open cavity in
//   an ideal fluid C_d / 2 = pi / (pi + 4) = 0.44 (Kirchhoff);
// - the slow push and the vertical plate's drag at 6 cm: APIC loses at every transfer the part
//   of a point's velocity that departs from the affine field (docs/method.md, Transfers), a drag
//   on the shear bands per step, and the step is the sand's wave's, so it does not vanish at
//   0.1 m/s: ASFLIP against APIC at the same cell and at half of it.
// --fast: 1 cm cells, without gravity: phi 0 at 1 and 2 m/s with both transfers, the sand at
// 1 m/s with ASFLIP.
namespace {

std::vector<IntrusionRun> intrusionTransferRunList(bool fast) {
  constexpr TransferScheme apic = TransferScheme::kApic, asflip = TransferScheme::kAsflip;
  std::vector<IntrusionRun> runs;
  if (fast) {
    for (TransferScheme transfer : {apic, asflip})
      for (Real v : {1.0, 2.0}) runs.push_back({0, 90, v, 0, 0.01, transfer, 0, 0});
    runs.push_back({0, 90, 1.0, 0, 0.01, asflip, 0, 35});
    return runs;
  }
  for (Real h : {0.01, 0.005})
    for (TransferScheme transfer : {apic, asflip}) {
      for (Real v : {0.1, 1.0, 2.0}) runs.push_back({0, 90, v, 0, h, transfer});
      for (Real phi : {0.0, 35.0})
        for (Real v : {1.0, 2.0}) runs.push_back({0, 90, v, 0, h, transfer, 0, phi});
      runs.push_back({90, 0, 0.1, 0.06, h, transfer});
    }
  // APIC's approach to ASFLIP's lambda_0 without strength (ASFLIP's points there expand
  // without bound at 2.5 mm: 97,515 steps for one push; docs/method.md, Transfers).
  for (Real v : {1.0, 2.0}) runs.push_back({0, 90, v, 0, 0.0025, apic, 0, 0});
  return runs;
}

}  // namespace

int intrusionTransferRuns(bool fast) {
  return static_cast<int>(intrusionTransferRunList(fast).size());
}

void intrusionTransfer(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionTransferRunList(o.fast), "intrusion_transfer", true);
}

void intrusionTransferFits(const Options& o, Results& r) {
  const std::string name = "intrusion_transfer";
  const Table t(o.out + "/" + name + ".csv");
  const std::vector<IntrusionRun> runs = intrusionTransferRunList(o.fast);
  const Real L = cases::Plate().length, rho = 1500;
  auto find = [&](const IntrusionRun& run) { return mediumRow(t, run, name); };
  auto label = [](const IntrusionRun& run) {
    return std::string(run.transfer == TransferScheme::kAsflip ? "ASFLIP" : "APIC") + ", h " +
           millimetres(run.h);
  };
  auto same = [](IntrusionRun a, Real speed, TransferScheme transfer, Real h) {
    a.speed = speed, a.transfer = transfer, a.h = h;
    return a;
  };
  for (const IntrusionRun& run : runs) {
    const std::size_t i = find(run);
    const Real f = t.at(i, "mean_fz_n_m"), v = run.speed;
    char q[160], settings[200];
    if (run.g == 0) {  // inertia alone
      std::snprintf(q, sizeof q, "lambda_0 = F_z / (rho L v^2), no gravity, phi %g, v %g m/s, %s",
                    run.phi, v, label(run).c_str());
      std::snprintf(settings, sizeof settings,
                    "mean F_z %.1f N/m over z 1.25-9 cm; a steady plate with an open cavity in "
                    "an ideal fluid: 0.44 (Kirchhoff)",
                    f);
      r.add(name, q, f / (rho * L * v * v), 1, "-",
            "the swept material given the plate's speed: 1; dynamic RFT: about 1", 0, settings);
    } else if (run.gamma > 0 && v > 0.1) {  // the excess over the slow push
      const Real slow = t.at(find(same(run, 0.1, run.transfer, run.h)), "mean_fz_n_m");
      std::snprintf(q, sizeof q, "lambda = (F_z(v) - F_z(0.1 m/s)) / (rho L v^2), v %g m/s, %s", v,
                    label(run).c_str());
      std::snprintf(settings, sizeof settings,
                    "mean F_z over z 1.25-9 cm: %.1f N/m, %.1f at 0.1 m/s; sqrt(v^2 / (g z)) at "
                    "z 6 cm: %.2f",
                    f, slow, v / std::sqrt(9.81 * kIntrusionReference));
      r.add(name, q, (f - slow) / (rho * L * v * v), 1, "-",
            "dynamic RFT (Agarwal et al. 2021): about 1", 0, settings);
    } else if (run.transfer == TransferScheme::kAsflip) {  // slow: against APIC at h and h / 2
      const bool drag = run.gamma == 0;
      const std::string column = drag ? "mean_fx_n_m" : "mean_fz_n_m";
      const Real apic = t.at(find(same(run, v, TransferScheme::kApic, run.h)), column);
      std::snprintf(q, sizeof q, "%s, ASFLIP / APIC at the same cell, h %s",
                    drag ? "drag F_x, beta 90 at 6 cm" : "mean F_z pushed down at 0.1 m/s",
                    millimetres(run.h).c_str());
      std::snprintf(settings, sizeof settings, "ASFLIP %.1f, APIC %.1f N/m", t.at(i, column), apic);
      r.add(name, q, t.at(i, column) / apic, 1, "-", "a transfer that loses nothing: 1 as h -> 0",
            0, settings);
      if (run.h > 0.006) {
        const Real apic_half = t.at(find(same(run, v, TransferScheme::kApic, run.h / 2)), column);
        std::snprintf(q, sizeof q, "%s, ASFLIP at h %s / APIC at h %s",
                      drag ? "drag F_x, beta 90 at 6 cm" : "mean F_z pushed down at 0.1 m/s",
                      millimetres(run.h).c_str(), millimetres(run.h / 2).c_str());
        std::snprintf(settings, sizeof settings, "ASFLIP %.1f, APIC %.1f N/m", t.at(i, column),
                      apic_half);
        r.add(name, q, t.at(i, column) / apic_half, 1, "-", "APIC at half the cell", 0, settings);
      }
    }
  }
}

// Issue 44: the intrusion forces under refinement, through 1.25 mm (the `intrusion` case's
// zeta and lambda are its 5 mm cell's). The flat plate pushed down at 0.1 m/s (alpha_z, the
// slope over Prandtl-Reissner's gamma N_q B and the intercept over Meyerhof's gamma B^2
// N_gamma / 2) and without gravity at 1 and 2 m/s in the sand (lambda_0 = F / (rho L v^2),
// intrusion_transfer's), APIC, at 1 cm, 5 mm, 2.5 mm and 1.25 mm; from the three finest cells
// (each half the one before) the observed order p = log2(d1 / d2) of the successive changes d1,
// d2 and Richardson's limit a_3 - d2 / (2^p - 1), stated only where p >= 1 (each change at
// most half the one before). The 1.25 mm push is one 53-minute run on one thread (256,000
// points, 92,234 steps). --fast: 2 and 1 cm.
namespace {

std::vector<Real> refinementCells(bool fast) {
  if (fast) return {0.01, 0.02};
  return {0.00125, 0.0025, 0.005, 0.01};  // the longest runs first
}

std::vector<IntrusionRun> intrusionRefinementRunList(bool fast) {
  std::vector<IntrusionRun> runs;
  for (Real h : refinementCells(fast)) {
    runs.push_back({0, 90, 0.1, 0, h});
    for (Real v : {1.0, 2.0}) runs.push_back({0, 90, v, 0, h, TransferScheme::kApic, 0, 35});
  }
  return runs;
}

// Successive values of one quantity from the coarsest cell to the finest, each cell half the
// one before: every value with its change from the one before, then the observed order and the
// Richardson limit from the three finest where the last change is at most half the one before.
void addRefinement(Results& r, const std::string& name, const std::string& quantity,
                   const std::vector<std::pair<Real, Real>>& values, Real reference,
                   const std::string& unit, const std::string& source) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    char settings[96] = "";
    if (k > 0)
      std::snprintf(settings, sizeof settings, "%+.1f%% from h %s",
                    100 * (values[k].second / values[k - 1].second - 1),
                    millimetres(values[k - 1].first).c_str());
    r.add(name, quantity + ", h " + millimetres(values[k].first), values[k].second, reference, unit,
          source, 0, settings);
  }
  if (values.size() < 3) return;
  const std::size_t n = values.size();
  const Real a1 = values[n - 3].second, a2 = values[n - 2].second, a3 = values[n - 1].second;
  char settings[160];
  std::snprintf(settings, sizeof settings, "from h %s, %s, %s: changes %.4g, %.4g",
                millimetres(values[n - 3].first).c_str(), millimetres(values[n - 2].first).c_str(),
                millimetres(values[n - 1].first).c_str(), a2 - a1, a3 - a2);
  // Richardson's limit assumes the asymptotic range; take it only where the last change is at
  // most half the one before (observed order >= 1).
  const cases::Richardson e =
      cases::richardson(a1, a2, a3, values[n - 3].first / values[n - 2].first);
  if (!(e.change_ratio > 0 && e.change_ratio <= 0.5)) {
    r.add(name, quantity + ": last change over the one before (above 0.5: no limit stated)",
          e.change_ratio, 0, "-", "", 0, settings);
    return;
  }
  r.add(name, quantity + ": observed order", e.order, 0, "-", "", 0, settings);
  r.add(name, quantity + ": Richardson limit", e.limit, reference, unit, source, 0, settings);
}

}  // namespace

int intrusionRefinementRuns(bool fast) {
  return static_cast<int>(intrusionRefinementRunList(fast).size());
}

void intrusionRefinement(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionRefinementRunList(o.fast), "intrusion_refinement", true);
}

void intrusionRefinementFits(const Options& o, Results& r) {
  const std::string name = "intrusion_refinement";
  const Table t(o.out + "/" + name + ".csv");
  const Real L = cases::Plate().length, rho = 1500, gamma = rho * 9.81;
  auto find = [&](const IntrusionRun& run) { return mediumRow(t, run, name); };
  std::vector<Real> cells = refinementCells(o.fast);
  std::sort(cells.begin(), cells.end(), std::greater<Real>());
  const Real phi = cases::bladeFrictionAngle(cases::Blade());
  const cases::BearingFactors f = cases::bearingFactors(phi);
  std::vector<std::pair<Real, Real>> alpha, slope, intercept, lambda1, lambda2;
  for (Real h : cells) {
    const std::size_t push = find({0, 90, 0.1, 0, h});
    alpha.emplace_back(h, t.at(push, "kz_n_m2") / L);
    slope.emplace_back(h, t.at(push, "kz_n_m2") / (gamma * f.n_q * L));
    intercept.emplace_back(h, t.at(push, "az_n_m") / (0.5 * gamma * L * L * f.n_gamma));
    for (Real v : {1.0, 2.0}) {
      const std::size_t i = find({0, 90, v, 0, h, TransferScheme::kApic, 0, 35});
      (v == 1 ? lambda1 : lambda2).emplace_back(h, t.at(i, "mean_fz_n_m") / (rho * L * v * v));
    }
  }
  const std::string bearing =
      "bearing capacity at phi " + std::to_string(std::lround(phi * 180 / M_PI)) + " deg: 1";
  addRefinement(r, name, "alpha_z, beta 0 pushed down at 0.1 m/s (slope / L)", alpha, 0, "N/m^3",
                "(the intrusion case's zeta alpha_gen is the 5 mm cell's)");
  addRefinement(r, name, "slope / (gamma N_q B), Prandtl-Reissner", slope, 1, "-", bearing);
  addRefinement(r, name, "intercept / (gamma B^2 N_gamma / 2), Meyerhof", intercept, 1, "-",
                bearing);
  const std::string rft = "the swept material given the plate's speed: 1; dynamic RFT: about 1";
  addRefinement(r, name, "lambda_0, no gravity, the sand, v 1 m/s", lambda1, 1, "-", rft);
  addRefinement(r, name, "lambda_0, no gravity, the sand, v 2 m/s", lambda2, 1, "-", rft);
}

}  // namespace mpm_sdem::report::robots
