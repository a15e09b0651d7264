// Seed 002's deformable bodies: the cantilever, the incline, the flexible barrier and the water
// gate. Each function is one case of mpm_sdem_validate: its world (cases.hpp), what it measures and
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

namespace mpm_sdem::report::fem {

// Issue 18, validation 1: the plane-strain cantilever of FEM triangles under its own weight
// (cases::cantilever) at h = H/2, H/4 and H/8: static tip deflection and first frequency against
// Euler-Bernoulli, with the element-steps per second of each run.
void femCantilever(const Options& o, Results& r) {
  const std::vector<Real> sizes =
      o.fast ? std::vector<Real>{0.025} : std::vector<Real>{0.025, 0.0125, 0.00625};
  for (const Real size : sizes) {
    const cases::Cantilever c = cases::cantilever(size);
    char q[96], settings[160];
    std::snprintf(settings, sizeof settings,
                  "1 x 0.05 m, E 1 GPa, nu 0.3, corotational, %d triangles of at most %g mm, "
                  "%.3g M element-steps/s",
                  c.elements, 1e3 * size, c.element_steps / c.seconds / 1e6);
    std::snprintf(q, sizeof q, "static tip deflection, h = H/%.0f", 0.05 / size);
    r.add("fem_cantilever", q, c.static_tip, c.euler_bernoulli, "m", "Euler-Bernoulli", c.seconds,
          settings);
    std::snprintf(q, sizeof q, "first frequency, h = H/%.0f", 0.05 / size);
    r.add("fem_cantilever", q, c.frequency, c.frequency_eb, "Hz", "Euler-Bernoulli", c.seconds,
          settings);
  }
}

// Issue 18, validation 2: seed 002 sec. 4.1 in 2D, the elastic disk sliding (mu 0.2) and
// rolling (mu 0.4) on an FEM plate at R = element / cell = 1, 2, 4, 8 with the particle-to-
// surface contact (the seed: under 6% for ICFEMP at every R), and the grid-based multi_velocity
// on the rigid incline cut into blocks R cells long (an FEM body has no area for it to sample;
// the seed: 26-28% for its grid-based scheme at R = 8).
void femIncline(const Options& o, Results& r) {
  const Real h = o.fast ? 0.02 : 0.005;  // fast: test_fem runs R = 1 and 8 at 1 cm
  for (const int R : o.fast ? std::vector<int>{1} : std::vector<int>{1, 2, 4, 8}) {
    for (const Real mu : o.fast ? std::vector<Real>{0.2} : std::vector<Real>{0.2, 0.4}) {
      char q[112], settings[112];
      const char* motion = mu < 0.3 ? "slides" : "rolls";
      auto t0 = std::chrono::steady_clock::now();
      const Real a = cases::femInclineAcceleration(mu, h, R * h);
      std::snprintf(q, sizeof q, "acceleration mu %.1f (%s), FEM plate, particle_surface, R = %d",
                    mu, motion, R);
      std::snprintf(settings, sizeof settings, "h %g mm, disk R = 5 cm: %.0f cells per radius",
                    1e3 * h, 0.05 / h);
      r.add("fem_incline", q, a, cases::inclineAnalytic(mu), "m/s^2", "seed 002 eq. 55 (2D)",
            seconds(t0), settings);
      if (o.fast) continue;
      t0 = std::chrono::steady_clock::now();
      const Real g = cases::inclineAcceleration(mu, h, CouplingScheme::kMultiVelocity, R * h);
      std::snprintf(q, sizeof q,
                    "acceleration mu %.1f (%s), rigid segments, multi_velocity, R = %d", mu, motion,
                    R);
      r.add("fem_incline", q, g, cases::inclineAnalytic(mu), "m/s^2", "seed 002 eq. 55 (2D)",
            seconds(t0), settings);
    }
  }
}

// Issue 18, validation 5: the shipped flexible_barrier scene (seed 003 sand into a clamped FEM
// barrier) at 1 cm, 5 mm and 2.5 mm cells with elements of the cell's size: the barrier top's
// largest and final deflection, and the cost by stage.
void flexibleBarrier(const Options& o, Results& r) {
  const std::string path =
      std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/flexible_barrier.yaml";
  const Real t_end = o.fast ? 0.3 : 1.0;
  FILE* stages = std::fopen((o.out + "/flexible_barrier_stages.csv").c_str(), "w");
  std::fprintf(stages, "cell_m,element_m,stage,ms_per_step,share\n");
  for (const Real h : o.fast ? std::vector<Real>{0.01} : std::vector<Real>{0.01, 0.005, 0.0025}) {
    const Real element =
        std::min(h, Real(0.004));  // the shipped 4 mm at most: 3 across the barrier
    const Scene scene =
        loadScene(path, {"grid.cell_size=" + std::to_string(h),
                         "fem_bodies.barrier.element_size=" + std::to_string(element)});
    World w(scene.world);
    const FemBodies& F = *w.femBodies();
    int top = 0;  // the node nearest the barrier's upper left corner
    for (int k = 1; k < F.totalNodes(); ++k)
      if ((F.reference(k) - Vec2(0.294, 0.08)).norm() <
          (F.reference(top) - Vec2(0.294, 0.08)).norm())
        top = k;
    Real largest = 0;
    const auto t0 = std::chrono::steady_clock::now();
    while (w.time() < t_end) {
      stepStable(w, t_end);
      largest = std::max(largest, F.position(top).x() - F.reference(top).x());
    }
    const double wall = seconds(t0);
    const Profile& prof = w.profile();
    for (const Stage s : prof.usedStages()) {
      const double t = prof.seconds[static_cast<int>(s)];
      std::fprintf(stages, "%g,%g,%s,%.5f,%.4f\n", h, element, stageName(s),
                   1e3 * t / w.stepCount(), t / prof.total());
    }
    char settings[160], q[96];
    std::snprintf(settings, sizeof settings,
                  "cells %g mm, elements %g mm, %zu points, %d triangles", 1e3 * h, 1e3 * element,
                  w.particles().size(), F.totalElements());
    std::snprintf(q, sizeof q, "barrier top, largest deflection, h %g mm", 1e3 * h);
    r.add("flexible_barrier", q, largest, 0, "m", "convergence (no measurement)", wall, settings,
          w.particles().size(), w.stepCount());
    std::snprintf(q, sizeof q, "barrier top, deflection at %.1f s, h %g mm", t_end, 1e3 * h);
    r.add("flexible_barrier", q, F.position(top).x() - F.reference(top).x(), 0, "m",
          "convergence (no measurement)", wall, settings, w.particles().size(), w.stepCount());
  }
  std::fclose(stages);
}

// Seed 002 sec. 4.3: the water column through the elastic gate (config/scenes/water_gate.yaml)
// at cells and elements of 8, 4 (the seed's, R = 1) and 2 mm, 4 mm cells with 2 mm elements, and
// the seed's cells at twice the scene's sound speed (the artificial c0's effect); the gate's
// upper-left corner against the five published histories (their mean, with their range in the
// settings), free-surface snapshots of the seed's run, and the cost by stage.
// One run per cell, element and sound speed (each its own run of a split report, Options::part).
struct GateRun {
  Real cell, element, sound_speed_factor = 1;
};
std::vector<GateRun> gateRunList(bool fast) {
  if (fast) return {{0.008, 0.008}};
  return {{0.008, 0.008}, {0.004, 0.004}, {0.004, 0.004, 2}, {0.004, 0.002}, {0.002, 0.002}};
}
int waterGateRuns(bool fast) {
  return static_cast<int>(gateRunList(fast).size());
}

void waterGate(const Options& o, Results& r) {
  const std::vector<GateRun> runs = gateRunList(o.fast);
  const Real t_end = o.fast ? 0.3 : 0.5;
  const cases::GateReference ref = cases::gateReference();
  FILE* series = std::fopen((o.out + "/water_gate_tip.csv").c_str(), "w");
  std::fprintf(series, "cell_m,element_m,sound_speed,time,tip_m\n");
  FILE* snaps = std::fopen((o.out + "/water_gate_snapshots.csv").c_str(), "w");
  std::fprintf(snaps, "time,what,x,y\n");
  FILE* stages = std::fopen((o.out + "/water_gate_stages.csv").c_str(), "w");
  std::fprintf(stages, "cell_m,element_m,stage,ms_per_step,share\n");
  // The published range the plot draws (cases::gateReferenceAt: one source for it), written
  // once by the first run.
  if (o.runs(0)) {
    FILE* reference = std::fopen((o.out + "/water_gate_reference.csv").c_str(), "w");
    std::fprintf(reference, "time,mean_m,low_m,high_m\n");
    for (int i = 0; i < 5; ++i) {
      Real mean, lo, hi;
      cases::gateReferenceAt(i, mean, lo, hi);
      std::fprintf(reference, "%g,%.5f,%.5f,%.5f\n", cases::kGateTimes[i], mean, lo, hi);
    }
    std::fclose(reference);
  }
  const std::string path = std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/water_gate.yaml";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const GateRun& run = runs[i];
    Scene scene = loadScene(path, {"grid.cell_size=" + std::to_string(run.cell),
                                   "fem_bodies.gate.element_size=" + std::to_string(run.element)});
    MaterialDef& water = scene.world.materials[0];
    water.bulk_modulus *= run.sound_speed_factor * run.sound_speed_factor;
    const Real c0 = std::sqrt(water.bulk_modulus / water.density);
    World w(scene.world);
    const bool seed = run.cell == 0.004 && run.element == 0.004 && run.sound_speed_factor == 1;
    auto snapshot = [&](const World& world, Real t) {
      const Particles& P = world.particles();
      for (std::size_t p = 0; p < P.size(); p += 2)  // every other point: the picture is the same
        std::fprintf(snaps, "%.3f,water,%.4f,%.4f\n", t, P.x[p], P.y[p]);
      const FemBodies& F = *world.femBodies();
      for (int k = 0; k < F.totalNodes(); ++k)
        std::fprintf(snaps, "%.3f,gate,%.5f,%.5f\n", t, F.position(k).x(), F.position(k).y());
    };
    const cases::GateRun g = cases::runWaterGate(
        w, t_end, 0.002, seed ? std::vector<Real>{0.1, 0.2, 0.3, 0.4} : std::vector<Real>{},
        seed ? std::function<void(const World&, Real)>(snapshot) : nullptr);
    for (std::size_t k = 0; k < g.time.size(); ++k)
      std::fprintf(series, "%g,%g,%g,%.5f,%.6g\n", run.cell, run.element, c0, g.time[k], g.tip[k]);
    const Profile& prof = w.profile();
    for (const Stage s : prof.usedStages()) {
      if (run.sound_speed_factor != 1) break;
      const double t = prof.seconds[static_cast<int>(s)];
      std::fprintf(stages, "%g,%g,%s,%.5f,%.4f\n", run.cell, run.element, stageName(s),
                   1e3 * t / g.steps, t / prof.total());
    }
    char settings[256], q[96];
    std::snprintf(settings, sizeof settings,
                  "cells %g mm, elements %g mm (R = %g), c0 %g m/s, %zu points, %d triangles, max "
                  "Mach %.3f; published peaks %.4f-%.4f m at %.3f-%.3f s",
                  1e3 * run.cell, 1e3 * run.element, run.element / run.cell, c0, g.points,
                  g.elements, g.max_mach, ref.peak_min, ref.peak_max, ref.time_min, ref.time_max);
    const std::string at =
        ", h " + std::to_string(static_cast<int>(std::lround(1e3 * run.cell))) + " mm, element " +
        std::to_string(static_cast<int>(std::lround(1e3 * run.element))) + " mm" +
        (run.sound_speed_factor != 1
             ? ", c0 " + std::to_string(static_cast<int>(std::lround(c0))) + " m/s"
             : "");
    const std::string src = "Walhorn 2005, Idelsohn 2008, Rafiee 2009, Ryzhakov 2010, Li (figures)";
    r.add("water_gate", "peak tip displacement" + at, g.peak, ref.peak_mean, "m", src, g.seconds,
          settings, g.points, g.steps);
    r.add("water_gate", "time of the peak" + at, g.peak_time, ref.time_mean, "s", src, g.seconds,
          settings, g.points, g.steps);
    for (int k = 0; k < 5; ++k) {
      if (cases::kGateTimes[k] > t_end) break;
      Real mean, lo, hi;
      cases::gateReferenceAt(k, mean, lo, hi);
      std::snprintf(q, sizeof q, "tip at %.2f s", cases::kGateTimes[k]);
      std::snprintf(settings, sizeof settings, "published %.4f-%.4f m", lo, hi);
      r.add("water_gate", q + at, g.at(cases::kGateTimes[k]), mean, "m", src, g.seconds, settings,
            g.points, g.steps);
    }
  }
  std::fclose(series);
  std::fclose(snaps);
  std::fclose(stages);
}

}  // namespace mpm_sdem::report::fem
