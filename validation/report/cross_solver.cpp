// Issue 91: the granular cases against a second solver of the same rheology. Lagree's mu(I)
// Navier-Stokes solver in Basilisk solves the chute, the column and the silo of its sandbox
// (cases.hpp, CrossChute / CrossColumn / CrossSilo); its numbers are kept as data in
// validation/basilisk/ (rebuilt by scripts/basilisk_references), so that these cases run without
// Basilisk. Each case runs ours at three cells under ASFLIP (as the granular scenes run it) and
// under APIC, one run each (a split case, Options::part).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "report.hpp"

namespace mpm_sdem::report::cross_solver {

namespace {

constexpr Real kGravity = 9.81;

std::string basiliskData(const char* file) {
  return std::string(MPM_SDEM_SOURCE_DIR) + "/validation/basilisk/" + file;
}

const char* transferName(TransferScheme t) {
  return t == TransferScheme::kApic ? "APIC" : "ASFLIP";
}

// The runs of a case: each transfer at each of its cells (the coarsest ASFLIP one when fast).
struct Run {
  Real cell;
  TransferScheme transfer;
};
std::vector<Run> runList(const std::vector<Real>& cells, bool fast) {
  if (fast) return {{cells.front(), TransferScheme::kAsflip}};
  std::vector<Run> runs;
  for (const TransferScheme t : {TransferScheme::kAsflip, TransferScheme::kApic})
    for (const Real h : cells) runs.push_back({h, t});
  return runs;
}

// Linear interpolation of y(x) in a table sorted by x, extended linearly past its ends.
Real interpolate(const std::vector<Real>& x, const std::vector<Real>& y, Real at) {
  std::size_t k = 1;
  while (k + 1 < x.size() && x[k] < at) ++k;
  return y[k - 1] + (y[k] - y[k - 1]) * (at - x[k - 1]) / (x[k] - x[k - 1]);
}

// Basilisk's deposit of the column of aspect a at `level` (validation/basilisk/
// column_deposit.csv), in metres for the column height H0.
cases::Deposit basiliskDeposit(const Table& t, Real aspect, int level, Real height) {
  cases::Deposit d;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (std::abs(t.at(k, "aspect") - aspect) > 1e-6) continue;
    if (static_cast<int>(t.at(k, "level")) != level) continue;
    d.x.push_back(t.at(k, "x_over_h0") * height);
    d.thickness.push_back(t.at(k, "thickness_over_h0") * height);
  }
  return d;
}

const std::vector<Real> kChuteCells = {0.005, 0.0025, 0.00125};  // h / 10, 20, 40
const std::vector<Real> kColumnCells = {0.01, 0.005, 0.0025};    // H0 / 10, 20, 40
const std::vector<Real> kSiloCells = {0.008, 0.004, 0.002};      // W / 5, 10, 20
const std::vector<Real> kSiloFrictions = {0.3, 0.5};

}  // namespace

// bagnold_periodic.c: the layer's speed per cell-thick layer after 6 s (fast: 1 s) from
// Bagnold's profile, against Basilisk's steady profile on 16 cells at the layer's height: the
// worst layer's difference as a fraction of Basilisk's surface speed, and the top layer's ratio;
// the layer's depth; and the top layer's change over the last second (steady flow: 0).
int chuteRuns(bool fast) {
  return static_cast<int>(runList(kChuteCells, fast).size());
}

void chute(const Options& o, Results& r) {
  const Table basilisk(basiliskData("chute_profile.csv"));
  const std::vector<Run> runs = runList(kChuteCells, o.fast);
  const Real t_end = o.fast ? 1 : 6;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    cases::CrossChute c;
    c.cell_size = runs[i].cell;
    c.transfer = runs[i].transfer;
    const Real speed_unit = std::sqrt(kGravity * c.depth);
    std::vector<Real> zb, ub;
    for (std::size_t k = 0; k < basilisk.size(); ++k) {
      zb.push_back(basilisk.at(k, "z_over_h") * c.depth);
      ub.push_back(basilisk.at(k, "u_over_sqrt_gh") * speed_unit);
    }
    World w(cases::crossSolverChute(c));
    cases::startOnBagnold(w, c);
    const auto t0 = std::chrono::steady_clock::now();
    runUntil(w, t_end - 1);
    const cases::LayerProfile before = cases::layerProfile(w, c.cell_size);
    runUntil(w, t_end);
    const double wall = seconds(t0);
    const cases::LayerProfile p = cases::layerProfile(w, c.cell_size);
    const Real surface = interpolate(zb, ub, c.depth);
    Real worst = 0;
    FILE* f = std::fopen((o.out + "/cross_chute." + std::to_string(i) + ".csv").c_str(), "w");
    std::fprintf(f, "transfer,cell_m,z_m,u_m_s,basilisk_m_s\n");
    for (std::size_t k = 0; k < p.z.size(); ++k) {
      const Real expected = interpolate(zb, ub, p.z[k]);
      worst = std::max(worst, std::abs(p.u[k] - expected) / surface);
      std::fprintf(f, "%s,%g,%.6g,%.6g,%.6g\n", transferName(c.transfer), c.cell_size, p.z[k],
                   p.u[k], expected);
    }
    std::fclose(f);
    const Real top_ratio = p.u.back() / interpolate(zb, ub, p.z.back());
    char settings[160];
    std::snprintf(settings, sizeof settings,
                  "24.64 deg, h 5 cm, d 2 mm, mu_s 0.38, delta mu 0.26, I0 0.3, cell %g mm, %s, "
                  "%g s from Bagnold's profile",
                  1000 * c.cell_size, transferName(c.transfer), t_end);
    const long points = static_cast<long>(w.particles().size()), steps = w.stepCount();
    const char* source = "Basilisk, bagnold_periodic.c (16 cells)";
    r.add("cross_chute", std::string("worst layer |u - u_Basilisk| / u_Basilisk(h), ") + settings,
          worst, 0, "-", source, wall, settings, points, steps);
    r.add("cross_chute", std::string("top layer u / u_Basilisk, ") + settings, top_ratio, 1, "-",
          source, wall, settings, points, steps);
    // The layer's depth from its top point (a quarter cell inside the outline): Basilisk's is h
    // by construction; ours thins where the points crowd while their J says they expanded.
    Real top = 0;
    for (std::size_t p = 0; p < w.particles().size(); ++p) top = std::max(top, w.particles().y[p]);
    r.add("cross_chute", std::string("layer depth / h, ") + settings,
          (top + c.cell_size / 4) / c.depth, 1, "-", "Basilisk (incompressible)", wall, settings,
          points, steps);
    r.add("cross_chute", std::string("top layer's change over the last second, ") + settings,
          p.u.back() / before.u.back() - 1, 0, "-", "steady flow", wall, settings, points, steps);
  }
}

// granular_column.c's columns a = 0.5 (d = H0 / 30) and a = 1.42 (d = H0 / 65): the deposit once
// at rest (or at 10 sqrt(H0 / g), where Basilisk's is read), against Basilisk's at its finest
// level: the run-out (L_inf - L0) / L0 with L_inf where the deposit first thins below a grain in
// both, and the deposit's greatest thickness over H0 (at a = 1.42, at the back wall); with each
// column's first run, Basilisk's run-out at its coarser level.
const std::vector<std::pair<Real, Real>> kColumns = {{0.5, 30}, {1.42, 65}};  // a, H0 / d

int columnRuns(bool fast) {
  return static_cast<int>(runList(kColumnCells, fast).size() * (fast ? 1 : kColumns.size()));
}

void column(const Options& o, Results& r) {
  const Table basilisk(basiliskData("column_deposit.csv"));
  const std::vector<Run> runs = runList(kColumnCells, o.fast);
  int index = -1;
  for (const auto& [aspect, ratio] :
       o.fast ? std::vector<std::pair<Real, Real>>{kColumns[0]} : kColumns) {
    cases::CrossColumn column;
    column.aspect = aspect;
    column.grain_ratio = ratio;
    const cases::GranularColumn unit = cases::crossColumnShape(column);
    std::vector<int> levels;  // Basilisk's for this column, in the file's order
    for (std::size_t k = 0; k < basilisk.size(); ++k) {
      if (std::abs(basilisk.at(k, "aspect") - aspect) > 1e-6) continue;
      const int level = static_cast<int>(basilisk.at(k, "level"));
      if (std::find(levels.begin(), levels.end(), level) == levels.end()) levels.push_back(level);
    }
    const int finest = *std::max_element(levels.begin(), levels.end());
    const cases::Deposit theirs = basiliskDeposit(basilisk, aspect, finest, column.height);
    auto runout = [&](const cases::Deposit& dep) {
      return (cases::depositFront(dep, unit.grain) - unit.length) / unit.length;
    };
    auto tallest = [&](const cases::Deposit& dep) {
      return *std::max_element(dep.thickness.begin(), dep.thickness.end()) / column.height;
    };
    char tag[64];
    std::snprintf(tag, sizeof tag, "a %g, H0 10 cm, d H0/%g", aspect, ratio);
    if (o.runs(index + 1))  // Basilisk's own convergence: its coarser level against its finest
      for (const int level : levels) {
        if (level == finest) continue;
        char q[128];
        std::snprintf(q, sizeof q,
                      "Basilisk's (L_inf - L0) / L0 at LEVEL %d (%d cells over 5 H0), %s", level,
                      1 << level, tag);
        r.add("cross_column", q, runout(basiliskDeposit(basilisk, aspect, level, column.height)),
              runout(theirs), "-", "Basilisk at its finest level", 0, "granular_column.c");
      }
    for (const Run& run : runs) {
      if (!o.runs(++index)) continue;
      cases::CrossColumn c = column;
      c.cell_size = run.cell;
      c.transfer = run.transfer;
      World w(cases::crossSolverColumn(c));
      const auto t0 = std::chrono::steady_clock::now();
      const cases::ColumnDeposit d =
          cases::collapseColumn(w, unit, 10 * std::sqrt(c.height / kGravity));
      const double wall = seconds(t0);
      const cases::Deposit ours = cases::depositThickness(w, c.cell_size);
      FILE* f =
          std::fopen((o.out + "/cross_column." + std::to_string(index) + ".csv").c_str(), "w");
      std::fprintf(f, "aspect,transfer,cell_m,x_m,thickness_m\n");
      for (std::size_t k = 0; k < ours.x.size(); ++k)
        std::fprintf(f, "%g,%s,%g,%.6g,%.6g\n", aspect, transferName(c.transfer), c.cell_size,
                     ours.x[k], ours.thickness[k]);
      std::fclose(f);
      char settings[192];
      std::snprintf(settings, sizeof settings,
                    "%s, mu_s 0.32, delta mu 0.28, I0 0.4, cell %g mm, %s, %s at %.2f s", tag,
                    1000 * c.cell_size, transferName(c.transfer), d.at_rest ? "at rest" : "stopped",
                    d.time);
      const long points = static_cast<long>(w.particles().size()), steps = w.stepCount();
      char source[96];
      std::snprintf(source, sizeof source, "Basilisk, granular_column.c (LEVEL %d, t = 10)",
                    finest);
      r.add("cross_column", std::string("(L_inf - L0) / L0, ") + settings, runout(ours),
            runout(theirs), "-", source, wall, settings, points, steps);
      r.add("cross_column", std::string("deposit's greatest thickness / H0, ") + settings,
            tallest(ours), tallest(theirs), "-", source, wall, settings, points, steps);
    }
  }
}

// silo2DCo.c without cohesion at mu_s 0.3 and 0.5: the discharge's C = Q / (sqrt(g) W^1.5)
// over t in [3, 4] sqrt(W / g) against Basilisk's mean flux over the same window at its finest
// level; with each friction's first run, Basilisk's C at its coarser level.
int siloRuns(bool fast) {
  return static_cast<int>(runList(kSiloCells, fast).size() * (fast ? 1 : kSiloFrictions.size()));
}

void silo(const Options& o, Results& r) {
  const Table basilisk(basiliskData("silo_discharge.csv"));
  const std::vector<Run> runs = runList(kSiloCells, o.fast);
  const std::vector<Real> frictions =
      o.fast ? std::vector<Real>{kSiloFrictions.front()} : kSiloFrictions;
  int index = -1;
  for (const Real mu_s : frictions) {
    // Basilisk's C at its finest level for this friction; with the first run, its coarser.
    Real reference = std::nan("");
    int finest = 0;
    std::vector<std::pair<int, Real>> levels;
    for (std::size_t k = 0; k < basilisk.size(); ++k) {
      if (std::abs(basilisk.at(k, "mu_s") - mu_s) > 1e-6) continue;
      const int level = static_cast<int>(basilisk.at(k, "level"));
      levels.emplace_back(level, basilisk.at(k, "c_flux_3_to_4"));
      if (level > finest) finest = level, reference = levels.back().second;
    }
    if (o.runs(index + 1))
      for (const auto& [level, c] : levels) {
        if (level == finest) continue;
        char q[96];
        std::snprintf(q, sizeof q, "Basilisk's C at LEVEL %d (%.1f cells over W), mu_s %g", level,
                      (1 << level) / 10.0, mu_s);
        r.add("cross_silo", q, c, reference, "-", "Basilisk at its finest level", 0,
              "silo2DCo.c, t in [3, 4]");
      }
    for (const Run& run : runs) {
      if (!o.runs(++index)) continue;
      cases::CrossSilo c;
      c.mu_s = mu_s;
      c.cell_size = run.cell;
      c.transfer = run.transfer;
      const Real unit = std::sqrt(c.opening / kGravity);
      char source[96];
      std::snprintf(source, sizeof source, "Basilisk, silo2DCo.c (LEVEL %d: %.1f cells over W)",
                    finest, (1 << finest) / 10.0);
      World w(cases::crossSolverSilo(c));
      const auto t0 = std::chrono::steady_clock::now();
      const Real q = cases::dischargeRate(w, c, 3 * unit, 4 * unit);
      const double wall = seconds(t0);
      char settings[160];
      std::snprintf(settings, sizeof settings,
                    "W 4 cm, 10 W wide, 4.5 W deep, d W/30, mu_s %g, delta mu 0.28, I0 0.4, "
                    "cell %g mm, %s",
                    mu_s, 1000 * c.cell_size, transferName(c.transfer));
      r.add("cross_silo", std::string("C = Q / (sqrt(g) W^1.5), ") + settings,
            q / (std::sqrt(kGravity) * std::pow(c.opening, 1.5)), reference, "-", source, wall,
            settings, static_cast<long>(w.particles().size()), w.stepCount());
    }
  }
}

}  // namespace mpm_sdem::report::cross_solver
