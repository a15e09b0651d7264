// Granular flows: the silo (Beverloo), the granular matrix under a plate (seed 000 sec. 7), steady
// chute flow (Bagnold) and the column collapse (Lube et al.).
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

namespace mpm_sdem::report::granular {

// Seed 000 sec. 5.3: silo discharge rate against the 2D Beverloo law at five neck widths and
// three point densities (3,200 to 12,900 points; the seed's 8,000-10,000), the exponent fitted
// per density; the grains' separation volume ratio (a choice of ours, not the seed's) is varied
// at the coarsest density, and one neck is rerun at the seed's 3.5 mm cells, to show their
// weight. 7 mm cells: the seed's 3.5 mm took 80 s to 10 min a run here.
void siloDischarge(const Options& o, Results& r) {
  struct Run {
    Real neck;
    int ppc;
    Real separation;
    Real h;
  };
  std::vector<Run> runs;
  const std::vector<Real> necks =
      o.fast ? std::vector<Real>{0.04} : std::vector<Real>{0.02, 0.03, 0.04, 0.05, 0.06};
  for (int ppc : o.fast ? std::vector<int>{2} : std::vector<int>{2, 3, 4})
    for (Real d : necks) runs.push_back({d, ppc, 1.27, 0.007});
  if (!o.fast) {
    for (Real d : necks) runs.push_back({d, 2, 2.0, 0.007});
    runs.push_back({0.04, 2, 1.27, 0.0035});
    runs.push_back({0.04, 2, 2.0, 0.0035});
  }
  FILE* table = std::fopen((o.out + "/silo.csv").c_str(), "w");
  std::fprintf(table,
               "neck_m,cell_size_m,points_per_cell,points,separation,rate_kg_s_m,beverloo_kg_s_m,"
               "wall_s\n");
  // log(rate) against log(D0 - k_c r_p) per (density, separation): the fitted exponent.
  std::vector<std::pair<std::pair<int, Real>, LineFit>> fits;
  for (const Run& run : runs) {
    const Real h = run.h;
    WorldDef def = cases::silo(run.neck, h, run.ppc);
    def.materials[0].separation_volume_ratio = run.separation;
    World w(def);
    const auto t0 = std::chrono::steady_clock::now();
    const cases::SiloFlow f = cases::siloFlow(w, o.fast ? 1.2 : 4.0);
    const double wall = seconds(t0);
    const Real ref = cases::beverloo(run.neck);
    std::fprintf(table, "%g,%g,%d,%zu,%g,%.6g,%.6g,%.4g\n", run.neck, h, run.ppc,
                 w.particles().size(), run.separation, f.rate, ref, wall);
    std::fflush(table);
    char q[128], settings[160];
    std::snprintf(q, sizeof q,
                  "mass flow rate, D0 %.0f cm, h %.1f mm, %d x %d points per cell, J_sep %.2f",
                  100 * run.neck, 1000 * h, run.ppc, run.ppc, run.separation);
    std::snprintf(settings, sizeof settings, "h %g m, %zu points, %ld steps, %s t = %.2f-%.2f s", h,
                  w.particles().size(), w.stepCount(),
                  f.window_reached ? "fitted over" : "under 10% discharged: mean over",
                  f.window_start, f.window_end);
    r.add("silo", q, f.rate, ref, "kg/(s m)", "seed 000 Fig. 16 (2D Beverloo, C 0.58, k_c 2.2)",
          wall, settings);
    // The fits are over the necks at 7 mm that discharged 10% (a neck of under three cells can
    // arch and hold the fill: its rate is then the mean of the last second, not a flow rate).
    if (h != 0.007 || !f.window_reached) continue;
    auto it = std::find_if(fits.begin(), fits.end(), [&](const auto& e) {
      return e.first.first == run.ppc && e.first.second == run.separation;
    });
    if (it == fits.end()) it = fits.insert(fits.end(), {{run.ppc, run.separation}, LineFit{}});
    it->second.add(std::log(cases::beverlooWidth(run.neck)), std::log(f.rate));
  }
  std::fclose(table);
  for (const auto& [key, fit] : fits) {
    if (fit.n < 3) continue;
    char q[96];
    std::snprintf(q, sizeof q, "fitted exponent, h 7 mm, %d x %d points per cell, J_sep %.2f",
                  key.first, key.first, key.second);
    char settings[96];
    std::snprintf(settings, sizeof settings,
                  "least squares over the %.0f necks that discharged 10%%", fit.n);
    r.add("silo", q, fit.slope(), 1.5, "-", "2D Beverloo law", 0, settings);
  }
}

// Issue 15: the silo's flow rate under refinement, per neck, at 7, 5, 3.5 and 2.5 mm cells
// (2 x 2 points per cell, J_sep 1.27 as in siloDischarge): one run per cell and neck (each its
// own run of a split report, Options::part), its rate in silo_convergence.csv; then, from that
// table (siloConvergenceFits), the Beverloo exponent fitted at each cell size over the necks
// that are at least six cells wide, and per neck the observed order p of the rate's convergence
// from the three finest sizes (h ratio 1.4 each) and the Richardson-extrapolated rate
// q_h + (q_h - q_2h) / (1.4^p - 1) when the differences shrink.
struct SiloRun {
  Real h, neck;
};
std::vector<SiloRun> siloConvergenceRunList(bool fast) {
  const std::vector<Real> necks =
      fast ? std::vector<Real>{0.05} : std::vector<Real>{0.02, 0.03, 0.04, 0.05, 0.06};
  const std::vector<Real> sizes =
      fast ? std::vector<Real>{0.01, 0.007} : std::vector<Real>{0.007, 0.005, 0.0035, 0.0025};
  std::vector<SiloRun> runs;
  for (Real h : sizes)
    for (Real neck : necks) runs.push_back({h, neck});
  return runs;
}
int siloConvergenceRuns(bool fast) {
  return static_cast<int>(siloConvergenceRunList(fast).size());
}

void siloConvergence(const Options& o, Results& r) {
  const std::vector<SiloRun> runs = siloConvergenceRunList(o.fast);
  FILE* table = std::fopen((o.out + "/silo_convergence.csv").c_str(), "w");
  std::fprintf(table,
               "neck_m,cell_size_m,points,steps,rate_kg_s_m,beverloo_kg_s_m,window,wall_s\n");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const Real h = runs[i].h, neck = runs[i].neck;
    WorldDef def = cases::silo(neck, h, 2);
    def.materials[0].separation_volume_ratio = 1.27;
    World w(def);
    const auto t0 = std::chrono::steady_clock::now();
    const cases::SiloFlow f = cases::siloFlow(w, o.fast ? 1.2 : 4.0);
    const double wall = seconds(t0);
    // The rate to every digit: the fits read it back (siloConvergenceFits).
    std::fprintf(table, "%.17g,%.17g,%zu,%ld,%.17g,%.6g,%d,%.4g\n", neck, h, w.particles().size(),
                 w.stepCount(), f.rate, cases::beverloo(neck), f.window_reached ? 1 : 0, wall);
    std::fflush(table);
    char q[96], settings[160];
    std::snprintf(q, sizeof q, "mass flow rate, D0 %.0f cm, h %.1f mm (%.1f cells)", 100 * neck,
                  1000 * h, neck / h);
    std::snprintf(settings, sizeof settings, "%s t = %.2f-%.2f s",
                  f.window_reached ? "fitted over" : "under 10% discharged: mean over",
                  f.window_start, f.window_end);
    r.add("silo_convergence", q, f.rate, cases::beverloo(neck), "kg/(s m)",
          "seed 000 Fig. 16 (2D Beverloo, C 0.58, k_c 2.2)", wall, settings,
          static_cast<long>(w.particles().size()), w.stepCount());
  }
  std::fclose(table);
}

void siloConvergenceFits(const Options& o, Results& r) {
  const Table table(o.out + "/silo_convergence.csv");
  std::vector<Real> necks, sizes;  // in the runs' order
  for (const SiloRun& run : siloConvergenceRunList(o.fast)) {
    if (std::find(sizes.begin(), sizes.end(), run.h) == sizes.end()) sizes.push_back(run.h);
    if (std::find(necks.begin(), necks.end(), run.neck) == necks.end()) necks.push_back(run.neck);
  }
  auto index = [](const std::vector<Real>& v, Real x) {
    for (std::size_t k = 0; k < v.size(); ++k)
      if (std::abs(v[k] - x) < 1e-5 * x) return k;  // as printed
    throw std::runtime_error("silo_convergence.csv: " + std::to_string(x) + " is not a run's");
  };
  std::vector<std::vector<Real>> rate(necks.size(), std::vector<Real>(sizes.size(), std::nan("")));
  std::vector<LineFit> fits(sizes.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    const Real h = table.at(i, "cell_size_m"), neck = table.at(i, "neck_m");
    const bool window = table.at(i, "window") > 0;
    const Real q = table.at(i, "rate_kg_s_m");
    const std::size_t k = index(sizes, h), n = index(necks, neck);
    rate[n][k] = window ? q : std::numeric_limits<Real>::quiet_NaN();
    if (window && neck >= 6 * h - 1e-9)
      fits[k].add(std::log(cases::beverlooWidth(neck)), std::log(q));
  }
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    if (fits[k].n < 3) continue;
    char q[96], settings[96];
    std::snprintf(q, sizeof q, "fitted exponent, h %.1f mm, necks of at least 6 cells",
                  1000 * sizes[k]);
    std::snprintf(settings, sizeof settings, "least squares over %.0f necks", fits[k].n);
    r.add("silo_convergence", q, fits[k].slope(), 1.5, "-", "2D Beverloo law", 0, settings);
  }
  if (sizes.size() < 3) return;
  const std::size_t f = sizes.size() - 1;  // the finest
  for (std::size_t n = 0; n < necks.size(); ++n) {
    const cases::Richardson e =
        cases::richardson(rate[n][f - 2], rate[n][f - 1], rate[n][f], sizes[f - 1] / sizes[f]);
    char q[96];
    std::snprintf(q, sizeof q, "rate change, finest two / coarser two, D0 %.0f cm", 100 * necks[n]);
    r.add("silo_convergence", q, e.change_ratio, 0, "-", "below 1: converging", 0,
          "differences of the three finest cell sizes");
    if (std::isnan(e.order)) continue;  // not in the asymptotic range
    std::snprintf(q, sizeof q, "extrapolated rate (order %.2f), D0 %.0f cm", e.order,
                  100 * necks[n]);
    r.add("silo_convergence", q, e.limit, cases::beverloo(necks[n]), "kg/(s m)",
          "Richardson from the three finest cell sizes", 0, "");
  }
}

// Issue 41: the silo with the mu(I) granular sand (cases::siloGranularSand; same geometry,
// contact, GIMP and APIC as silo_convergence, 2 x 2 points per cell) over the necks that are at
// least six cells wide, at 7, 5, 3.5 and 2.5 mm cells (fast: 5 and 6 cm at 7 mm, 1.2 s at most).
// Per cell size, Beverloo's exponent fitted against log W with W = D0 (k = 0) and W = D0 -
// k_c r_p (the seed's k_c = 2.2), and C and k fitted with the exponent held at 1.5 (rate^(2/3)
// is then linear in D0: slope (C rho g^0.5)^(2/3), root k d) against seed 000's C 0.58 and
// k_c r_p = 1.1 d (its Fig. 16, citing Mankoc et al. 2007, Granular Matter 9, for the 2D law;
// no quasi-2D measurement of C and k was at hand); the same from the rates' Richardson limits
// (three finest sizes, as in silo_convergence). One material for every neck and cell size.
// silo_granular_asflip: the same with ASFLIP (relaxation time 0.03 s, as in the granular
// wooden-block scene) at 7, 5 and 3.5 mm, to show the transfer's weight; silo_granular_fit: that
// with volume-consistent points (issue 79).
void siloGranularWith(const Options& o, Results& r, TransferScheme transfer,
                      bool volume_fit = false) {
  const bool asflip = transfer == TransferScheme::kAsflip;
  const std::string name = volume_fit ? "silo_granular_fit"
                           : asflip   ? "silo_granular_asflip"
                                      : "silo_granular";
  const std::vector<Real> necks =
      o.fast ? std::vector<Real>{0.05, 0.06} : std::vector<Real>{0.02, 0.03, 0.04, 0.05, 0.06};
  const std::vector<Real> sizes = o.fast   ? std::vector<Real>{0.007}
                                  : asflip ? std::vector<Real>{0.007, 0.005, 0.0035}
                                           : std::vector<Real>{0.007, 0.005, 0.0035, 0.0025};
  const Real t_max = o.fast ? 1.2 : 4.0;
  const Real d = cases::siloGranularSand("sand").grain_diameter;
  FILE* table = std::fopen((o.out + "/" + name + ".csv").c_str(), "w");
  std::fprintf(table,
               "neck_m,cell_size_m,points,steps,rate_kg_s_m,beverloo_kg_s_m,window,window_start_s,"
               "window_end_s,wall_s\n");
  // The 2D continuum's C for this sand: Basilisk's silo at the same mu(I) (issue 91).
  const Table basilisk(std::string(MPM_SDEM_SOURCE_DIR) +
                       "/validation/basilisk/silo_sand_discharge.csv");
  const Real continuumC = basilisk.at(0, "c_flux_3_to_4");
  // Beverloo's law fitted to (neck, rate) pairs: the exponent with k = 0 and with k = k_c, and
  // C and k with the exponent 1.5.
  auto beverlooFits = [&](const std::vector<std::pair<Real, Real>>& points, const char* what,
                          const std::string& settings) {
    LineFit bare, shifted, linear;  // log-log with k = 0 and k = k_c; rate^(2/3) against D0
    char q[128];
    for (const auto& [neck, rate] : points) {
      bare.add(std::log(neck), std::log(rate));
      shifted.add(std::log(cases::beverlooWidth(neck)), std::log(rate));
      linear.add(neck, std::pow(rate, Real(2) / 3));
      // C per neck with the seed's k_c held: rate / (rho g^0.5 (D0 - 2.2 r_p)^1.5), against the
      // continuum's C for this sand (Basilisk's silo2DCo.c, validation/basilisk/).
      std::snprintf(q, sizeof q, "C with k fixed at the seed's 2.2 r_p, D0 %.0f cm, %s", 100 * neck,
                    what);
      r.add(name, q,
            rate / (cases::siloDensityRootGravity() * std::pow(cases::beverlooWidth(neck), 1.5)),
            continuumC, "-", "Basilisk, silo2DCo.c with this sand's mu(I) (2D continuum)", 0,
            settings);
    }
    if (bare.n < 2) return;
    std::snprintf(q, sizeof q, "fitted exponent, W = D0, %s", what);
    r.add(name, q, bare.slope(), 1.5, "-", "2D Beverloo law", 0, settings);
    std::snprintf(q, sizeof q, "fitted exponent, W = D0 - 2.2 r_p, %s", what);
    r.add(name, q, shifted.slope(), 1.5, "-", "2D Beverloo law", 0, settings);
    const Real s = linear.slope();
    std::snprintf(q, sizeof q, "C with the exponent 1.5, %s", what);
    r.add(name, q, std::pow(s, Real(1.5)) / cases::siloDensityRootGravity(), continuumC, "-",
          "Basilisk, silo2DCo.c with this sand's mu(I) (seed 000's 0.58 is Beverloo's 3D C)", 0,
          settings);
    std::snprintf(q, sizeof q, "k (grain diameters) with the exponent 1.5, %s", what);
    r.add(name, q, -linear.intercept() / s / d, 1.1, "d", "seed 000 Fig. 16 (k_c r_p = 1.1 d)", 0,
          settings);
  };
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  std::vector<std::vector<Real>> rate(necks.size(), std::vector<Real>(sizes.size(), nan));
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    const Real h = sizes[k];
    std::vector<std::pair<Real, Real>> points;
    for (std::size_t n = 0; n < necks.size(); ++n) {
      const Real neck = necks[n];
      if (neck < 6 * h - 1e-9) continue;
      WorldDef def = cases::silo(neck, h, 2, cases::SiloSand::kGranular);
      def.solver.transfer = transfer;
      if (asflip) def.solver.asflip_relaxation_time = 0.03;
      def.solver.volume_fit = volume_fit;
      World w(def);
      const auto t0 = std::chrono::steady_clock::now();
      const cases::SiloFlow f = cases::siloFlow(w, t_max);
      const double wall = seconds(t0);
      std::fprintf(table, "%g,%g,%zu,%ld,%.6g,%.6g,%d,%.3f,%.3f,%.4g\n", neck, h,
                   w.particles().size(), w.stepCount(), f.rate, cases::beverloo(neck),
                   f.window_reached ? 1 : 0, f.window_start, f.window_end, wall);
      std::fflush(table);
      char q[96], settings[160];
      std::snprintf(q, sizeof q, "mass flow rate, D0 %.0f cm, h %.1f mm (%.1f cells)", 100 * neck,
                    1000 * h, neck / h);
      std::snprintf(settings, sizeof settings, "granular mu(I), %s%s; %s t = %.2f-%.2f s",
                    asflip ? "ASFLIP 0.03 s" : "APIC", volume_fit ? ", volume fit" : "",
                    f.window_reached ? "fitted over" : "under 10% discharged: mean over",
                    f.window_start, f.window_end);
      r.add(name, q, f.rate, cases::beverloo(neck), "kg/(s m)",
            "seed 000 Fig. 16 (2D Beverloo, C 0.58, k_c 2.2)", wall, settings,
            static_cast<long>(w.particles().size()), w.stepCount());
      if (!f.window_reached) continue;
      rate[n][k] = f.rate;
      points.emplace_back(neck, f.rate);
    }
    char what[32], settings[96];
    std::snprintf(what, sizeof what, "h %.1f mm", 1000 * h);
    std::snprintf(settings, sizeof settings, "least squares over %zu necks of at least 6 cells",
                  points.size());
    beverlooFits(points, what, settings);
  }
  std::fclose(table);
  // Per neck run at the three finest sizes, the rate's observed order of convergence and its
  // Richardson limit (as in silo_convergence), and Beverloo's law fitted to the limits.
  if (sizes.size() < 3) return;
  const std::size_t f = sizes.size() - 1;  // the finest
  const Real ratio = sizes[f - 1] / sizes[f];
  std::vector<std::pair<Real, Real>> limits;
  for (std::size_t n = 0; n < necks.size(); ++n) {
    const cases::Richardson e =
        cases::richardson(rate[n][f - 2], rate[n][f - 1], rate[n][f], ratio);
    if (!std::isfinite(rate[n][f - 1] - rate[n][f - 2]) ||
        !std::isfinite(rate[n][f] - rate[n][f - 1]))
      continue;  // a run missing
    char q[96];
    std::snprintf(q, sizeof q, "rate change, finest two / coarser two, D0 %.0f cm", 100 * necks[n]);
    r.add(name, q, e.change_ratio, 0, "-", "below 1: converging", 0,
          "differences of the three finest cell sizes");
    if (std::isnan(e.order)) continue;  // not in the asymptotic range
    std::snprintf(q, sizeof q, "extrapolated rate (order %.2f), D0 %.0f cm", e.order,
                  100 * necks[n]);
    r.add(name, q, e.limit, cases::beverloo(necks[n]), "kg/(s m)",
          "Richardson from the three finest cell sizes", 0, "");
    limits.emplace_back(necks[n], e.limit);
  }
  char settings[96];
  std::snprintf(settings, sizeof settings, "least squares over the %zu necks' Richardson limits",
                limits.size());
  beverlooFits(limits, "Richardson limits", settings);
}

void siloGranular(const Options& o, Results& r) {
  siloGranularWith(o, r, TransferScheme::kApic);
}

void siloGranularAsflip(const Options& o, Results& r) {
  siloGranularWith(o, r, TransferScheme::kAsflip);
}

void siloGranularFit(const Options& o, Results& r) {
  siloGranularWith(o, r, TransferScheme::kAsflip, true);
}

// Seed 000 sec. 7: uniaxial compression of the granular matrix at three fines contents; the
// force-settlement curves (seed Fig. 23 has no numbers to compare: its finding is that more
// fines make the matrix stiffer), and the force at 1 and 2 cm of settlement.
void compression(const Options& o, Results& r) {
  const Real speed = 0.05, max_settlement = o.fast ? 0.01 : 0.02;
  for (Real fines : o.fast ? std::vector<Real>{0.3} : std::vector<Real>{0.1, 0.2, 0.3}) {
    int plate = -1;
    World w(cases::granularMatrix(fines, false, 7, plate));
    const auto t0 = std::chrono::steady_clock::now();
    const cases::Compression c = cases::compressMatrix(w, plate, speed, max_settlement);
    const double wall = seconds(t0);
    char name[64];
    std::snprintf(name, sizeof name, "%s/compression_%02.0f.csv", o.out.c_str(), 100 * fines);
    FILE* f = std::fopen(name, "w");
    std::fprintf(f, "settlement_m,force_n_m\n");
    for (std::size_t i = 0; i < c.settlement.size(); ++i)
      std::fprintf(f, "%.6g,%.6g\n", c.settlement[i], c.force[i]);
    std::fclose(f);
    char settings[160];
    std::snprintf(settings, sizeof settings,
                  "30 x 30 cm, 25 pentagons, %zu fines points, h 1 cm, plate at %g cm/s, %ld steps",
                  w.particles().size(), 100 * speed, w.stepCount());
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    char q[96];
    std::snprintf(q, sizeof q, "fines content (mass), %.0f%% asked", 100 * fines);
    r.add("compression", q, c.fines_mass / c.solids_mass, fines, "-", "sample preparation", wall,
          settings);
    for (Real s : {0.01, 0.02}) {
      if (s > max_settlement) continue;
      // The mean over the samples within 1 mm of s: the skeleton's force jumps as it slips.
      Real sum = 0;
      int n = 0;
      for (std::size_t i = 0; i < c.settlement.size(); ++i)
        if (std::abs(c.settlement[i] - s) <= 0.001) sum += c.force[i], ++n;
      std::snprintf(q, sizeof q, "plate force at %.0f cm settlement, fines %.0f%%", 100 * s,
                    100 * fines);
      r.add("compression", q, n ? sum / n : nan, nan, "N/m",
            "seed 000 Fig. 23 (curves only: more fines, stiffer)", wall, settings);
    }
  }
}

// Issues 41 and 79: steady uniform chute flow of the mu(I) material (cases::chute) at three
// angles between the mu_s and mu_2 angles and three cells, from rest perturbed by 10 um (as
// mpm_sdem_chute), 6 s, for each variant: ASFLIP as the scenes run it, with volume-consistent
// points (SolverDef::volume_fit), and APIC with them. Rows: the worst layer's speed against
// Bagnold's profile (fraction of the surface speed), the top layer's ratio, the grid's L2 error
// (cases::ChuteProfile::l2), the nodes' largest over-fill (VolumeFit) and the surface speed's
// change over the last second; the same every 0.5 s in chute_series.<run>.csv. One run per
// variant, angle and cell. Fast: ASFLIP with the fit, 24 deg, 5 mm, 2 s.
struct ChuteRun {
  Real degrees, h;
  TransferScheme transfer;
  bool fit;
  std::string variant;
};
std::vector<ChuteRun> chuteRunList(bool fast) {
  if (fast) return {{24, 0.005, TransferScheme::kAsflip, true, "ASFLIP, volume fit"}};
  std::vector<ChuteRun> runs;
  const std::pair<TransferScheme, bool> variants[] = {{TransferScheme::kAsflip, false},
                                                      {TransferScheme::kAsflip, true},
                                                      {TransferScheme::kApic, true}};
  for (const auto& [transfer, fit] : variants)
    for (const Real degrees : {22.0, 24.0, 27.0})
      for (const Real h : {0.005, 0.0025, 0.00125}) {
        std::string variant = transfer == TransferScheme::kApic ? "APIC" : "ASFLIP";
        if (fit) variant += ", volume fit";
        runs.push_back({degrees, h, transfer, fit, variant});
      }
  return runs;
}

int chuteFlowRuns(bool fast) {
  return static_cast<int>(chuteRunList(fast).size());
}

void chuteFlow(const Options& o, Results& r) {
  const Real t_end = o.fast ? 2 : 6, every = 0.5;
  const std::vector<ChuteRun> runs = chuteRunList(o.fast);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!o.runs(static_cast<int>(k))) continue;
    const ChuteRun& run = runs[k];
    cases::Chute c;
    c.theta = run.degrees * M_PI / 180;
    c.cell_size = run.h;
    WorldDef def = cases::chute(c);
    def.solver.transfer = run.transfer;
    def.solver.volume_fit = run.fit;
    World w(def);
    perturbPositions(w.particles(), 1e-5, 1);
    char settings[160];
    std::snprintf(settings, sizeof settings,
                  "%g deg, h %g mm, d 4 mm, depth 5 cm, perturbed by 10 um, %s", run.degrees,
                  1000 * run.h, run.variant.c_str());
    FILE* series = std::fopen((o.out + "/chute_series." + std::to_string(k) + ".csv").c_str(), "w");
    std::fprintf(series, "variant,angle_deg,cell_m,t_s,worst,surface,l2,overfill\n");
    const auto t0 = std::chrono::steady_clock::now();
    Real before = 0;
    cases::ChuteProfile p;
    Real overfill = 0;
    for (Real next = every; next <= t_end + 1e-9; next += every) {
      runUntil(w, next);
      p = cases::chuteProfile(w, c);
      overfill = w.largestOverfill();
      std::fprintf(series, "\"%s\",%g,%g,%.3f,%.6g,%.6g,%.6g,%.6g\n", run.variant.c_str(),
                   run.degrees, run.h, w.time(), p.worst, p.surface, p.l2, overfill);
      std::fflush(series);
      if (std::abs(next - (t_end - 1)) < 1e-9) before = p.surface;
    }
    std::fclose(series);
    const double wall = seconds(t0);
    const long points = static_cast<long>(w.particles().size()), steps = w.stepCount();
    const char* source = "Bagnold profile (Jop et al. 2006)";
    auto add = [&](const char* what, double value, double reference, const char* from) {
      r.add("chute", std::string(what) + ", " + settings, value, reference, "-", from, wall,
            settings, points, steps);
    };
    add("worst layer |u - u_B| / u_B(h)", p.worst, 0, source);
    add("top layer u / u_B", p.surface, 1, source);
    add("L2 error of the grid's velocity", p.l2, 0, source);
    add("largest nodal over-fill", overfill, 0, "volume-consistent points");
    add("top layer's change over the last second", p.surface / before - 1, 0, "steady flow");
  }
}

// Issue 41: granular column collapse on a rough floor (cases::granularColumn), aspect ratios 0.5
// to 8 at two cells, 3 s from release: the run-out (L_inf - L0) / L0 and the height H_inf / L0
// against the quasi-2D experiments' fits (Lube et al. 2005; the run-out also against Lajeunesse
// et al. 2005's glass beads), with the farthest point (the thin front) and the fastest point at
// the end; then a = 1 and 3 at 5 mm with rougher grains, and the beads with volume-consistent
// points (issue 79). Fast: a = 1 at 1 cm.
// One run per column (each its own run of a split report, Options::part): aspect ratio, cell
// and grains' friction, and the run's label.
struct ColumnRun {
  cases::GranularColumn column;
  std::string settings;
  bool details;             // the farthest and the fastest point too
  bool volume_fit = false;  // SolverDef::volume_fit (issue 79)
};
std::vector<ColumnRun> columnRunList(bool fast) {
  std::vector<ColumnRun> runs;
  char settings[120];
  for (const Real a : {0.5, 1.0, 3.0, 8.0}) {
    if (fast && a != 1.0) continue;
    for (const Real h : fast ? std::vector<Real>{0.01} : std::vector<Real>{0.005, 0.0025}) {
      cases::GranularColumn c;
      c.aspect = a;
      c.cell_size = h;
      std::snprintf(settings, sizeof settings, "a %g, L0 10 cm, h %g mm, 1 mm beads, ASFLIP", a,
                    1000 * h);
      runs.push_back({c, settings, true});
    }
  }
  if (fast) return runs;
  // The deposit against the grains' friction (5 mm): Lube et al.'s sands, sugar, rice and
  // couscous are rougher than glass beads, and Balmforth & Kerswell 2005 (J. Fluid Mech. 538)
  // find the run-out's prefactor material-dependent.
  for (const Real a : {1.0, 3.0}) {
    for (const Real degrees : {25.0, 30.0, 35.0}) {
      cases::GranularColumn c;
      c.aspect = a;
      c.friction_angle = degrees * M_PI / 180;
      std::snprintf(settings, sizeof settings, "a %g, mu_s tan %g deg, h 5 mm, ASFLIP", a, degrees);
      runs.push_back({c, settings, false});
    }
  }
  // With volume-consistent points (issue 79): every aspect at 5 mm, and up to a = 3 at 2.5 mm
  // (a = 8 would take about 23 min: the fit doubles the step's cost).
  for (const Real a : {0.5, 1.0, 3.0, 8.0}) {
    for (const Real h : {0.005, 0.0025}) {
      if (a == 8.0 && h == 0.0025) continue;
      cases::GranularColumn c;
      c.aspect = a;
      c.cell_size = h;
      std::snprintf(settings, sizeof settings,
                    "a %g, L0 10 cm, h %g mm, 1 mm beads, ASFLIP, volume fit", a, 1000 * h);
      runs.push_back({c, settings, true, true});
    }
  }
  return runs;
}
int columnCollapseRuns(bool fast) {
  return static_cast<int>(columnRunList(fast).size());
}

// One column released and measured 3 s on (or at rest): its deposit and what it cost.
struct ColumnResult {
  cases::ColumnDeposit d;
  double wall;
  long points, steps;
};
ColumnResult runColumn(const ColumnRun& run) {
  WorldDef def = cases::granularColumn(run.column);
  def.solver.volume_fit = run.volume_fit;
  World w(def);
  const auto t0 = std::chrono::steady_clock::now();
  const cases::ColumnDeposit d = cases::collapseColumn(w, run.column, 3);
  return {d, seconds(t0), static_cast<long>(w.particles().size()), w.stepCount()};
}

void columnCollapse(const Options& o, Results& r) {
  const char* source = "Lube et al. 2005 (quasi-2D fits)";
  const std::vector<ColumnRun> runs = columnRunList(o.fast);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const cases::GranularColumn& c = runs[i].column;
    const std::string& settings = runs[i].settings;
    const auto [d, wall, points, steps] = runColumn(runs[i]);
    const std::string tag = ", " + settings;
    const Real a = c.aspect;
    r.add("column_collapse", "(L_inf - L0) / L0" + tag, (d.runout - c.length) / c.length,
          cases::lubeRunout(a), "-", source, wall, settings, points, steps);
    if (runs[i].details)
      r.add("column_collapse", "farthest point (L - L0) / L0" + tag,
            (d.farthest - c.length) / c.length, cases::lubeRunout(a), "-", source, wall, settings,
            points, steps);
    r.add("column_collapse", "(L_inf - L0) / L0 against glass beads" + tag,
          (d.runout - c.length) / c.length, cases::lajeunesseRunout(a), "-",
          "Lajeunesse et al. 2005 (glass beads, quasi-2D; as Lagree et al. 2011 eq. 3.1 quote it)",
          wall, settings, points, steps);
    r.add("column_collapse", "H_inf / L0" + tag, d.height / c.length, cases::lubeHeight(a), "-",
          source, wall, settings, points, steps);
    if (runs[i].details)
      r.add("column_collapse", "fastest point at the end" + tag, d.max_speed, 0, "m/s",
            "at rest (below 0.01 m/s)", wall, settings, points, steps);
  }
}

// Issue 91: the column between the channel's side walls (domain.sidewalls). Lajeunesse et al.'s
// and Lube et al.'s collapses ran between walls whose widths are not sourced here, so a = 1 and 3
// at 5 and 2.5 mm are bracketed over W = 5, 10 and 20 cm, with the wall friction angle of
// Lajeunesse et al. 2004's glass beads (24.8 deg, as K. Kumar's PhD thesis, Cambridge 2015,
// tabulates it). Without walls the same columns run out 2.15 (a = 1) and 7.15 (a = 3) L0 at 5 mm:
// column_collapse.
std::vector<ColumnRun> sidewallRunList(bool fast) {
  std::vector<ColumnRun> runs;
  char settings[120];
  for (const Real a : {1.0, 3.0}) {
    if (fast && a != 1.0) continue;
    for (const Real h : fast ? std::vector<Real>{0.01} : std::vector<Real>{0.005, 0.0025})
      for (const Real width : {0.05, 0.1, 0.2}) {
        if (fast && width != 0.1) continue;
        cases::GranularColumn c;
        c.aspect = a;
        c.cell_size = h;
        c.sidewall_width = width;
        c.sidewall_friction = std::tan(24.8 * M_PI / 180);
        std::snprintf(settings, sizeof settings,
                      "a %g, h %g mm, ASFLIP, side walls %g cm apart, mu_w tan 24.8 deg", a,
                      1000 * c.cell_size, 100 * width);
        runs.push_back({c, settings, false});
      }
  }
  return runs;
}
int columnSidewallsRuns(bool fast) {
  return static_cast<int>(sidewallRunList(fast).size());
}

void columnSidewalls(const Options& o, Results& r) {
  const std::vector<ColumnRun> runs = sidewallRunList(o.fast);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const cases::GranularColumn& c = runs[i].column;
    const auto [d, wall, points, steps] = runColumn(runs[i]);
    const std::string tag = ", " + runs[i].settings;
    r.add("column_sidewalls", "(L_inf - L0) / L0" + tag, (d.runout - c.length) / c.length,
          cases::lajeunesseRunout(c.aspect), "-",
          "Lajeunesse et al. 2005 (glass beads, quasi-2D; as Lagree et al. 2011 eq. 3.1 quote it)",
          wall, runs[i].settings, points, steps);
    r.add("column_sidewalls", "H_inf / L0" + tag, d.height / c.length, cases::lubeHeight(c.aspect),
          "-", "Lube et al. 2005 (quasi-2D fits)", wall, runs[i].settings, points, steps);
  }
}

}  // namespace mpm_sdem::report::granular
