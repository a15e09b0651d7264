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
#include "mpm_sdem/core/mpm/materials/drucker_prager.hpp"
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
// --fast: d 6 cm at 5 mm, the rough blade only (both stiffnesses, and the Drucker-Prager blade).
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
  // Blade friction: smooth (Rankine's exact passive state) and rough.
  const std::vector<Real> frictions = o.fast ? std::vector<Real>{0.3} : std::vector<Real>{0, 0.3};
  std::vector<Real> miss(stiffnesses.size(), 0);  // mean |onset / Reece - 1| per stiffness
  for (std::size_t k = 0; k < stiffnesses.size(); ++k) {
    for (const Real mu : frictions) {
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
  for (const Real mu : frictions) {
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

}  // namespace mpm_sdem::report::robots
