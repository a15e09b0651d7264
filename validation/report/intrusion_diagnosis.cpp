// Issue 90: what the cell does to a tool's force (docs/robots.md). One numerical choice at a
// time against the report's (quadratic B-splines, 2 points per cell side, IMP, the plate 5 mm
// thick with sand behind it, no divergence average, the full step):
// - the upright plate dragged at 6 cm (intrusion_drag's run), against the drag's converged
//   limit, alpha_x = 102.3 kPa/m (kDragLimit);
// - the flat plate pushed down (intrusion_refinement's), its slope k_z against the 1.25 mm
//   value, 18,623 N/m^2 (kPushSlope), for the choices that moved the drag most;
// each at 1 cm and 5 mm, and the drag at 2.5 mm for the report's choices, the average, GIMP
// with it, and ASFLIP. The drag through 4, 6 and 8 cm gives its line F(z) = a + k z for the
// report's choices (1 cm, 5 mm, 2.5 mm), the average and ASFLIP (1 cm, 5 mm), against the
// converged line through the origin (k = alpha_x L). The plate's speed is a choice too: the
// sand's drag does not depend on it, the transfer's loss does (it grows as v / dt).
// --fast: 2 cm, five choices dragged at 6 cm (a smoke test of the case's machinery).
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/world.hpp"
#include "report.hpp"

namespace mpm_sdem::report::robots {

namespace {

constexpr Real kPushSlope = 18623.4;  // N/m^2: intrusion_refinement's k_z at 1.25 mm

// A numerical choice of the plate's world, named as the report prints it.
struct Choice {
  const char* name;
  std::function<void(cases::Plate&)> set;
};

const std::vector<Choice>& choices() {
  static const std::vector<Choice> all{
      {"report's", [](cases::Plate&) {}},
      {"GIMP", [](cases::Plate& c) { c.kernel = KernelType::kGimp; }},
      {"cubic B-spline", [](cases::Plate& c) { c.kernel = KernelType::kCubicBSpline; }},
      {"1 point per cell side", [](cases::Plate& c) { c.points_per_cell = 1; }},
      {"3 points per cell side", [](cases::Plate& c) { c.points_per_cell = 3; }},
      {"grid contact", [](cases::Plate& c) { c.scheme = CouplingScheme::kMultiVelocity; }},
      {"particle-surface", [](cases::Plate& c) { c.scheme = CouplingScheme::kParticleSurface; }},
      {"plate 10 mm thick", [](cases::Plate& c) { c.thickness = 0.01; }},
      {"no sand behind", [](cases::Plate& c) { c.wake = false; }},
      {"divergence average", [](cases::Plate& c) { c.volumetric_average = true; }},
      {"GIMP and average",
       [](cases::Plate& c) {
         c.kernel = KernelType::kGimp;
         c.volumetric_average = true;
       }},
      {"step halved", [](cases::Plate& c) { c.step_scale = 0.5; }},
      // A rate-independent sand's drag does not depend on the plate's speed at these speeds
      // (rho v^2 L is 0.75 N/m), so what moves with it is numerical.
      {"speed halved", [](cases::Plate& c) { c.speed = 0.05; }},
      {"ASFLIP", [](cases::Plate& c) { c.transfer = TransferScheme::kAsflip; }},
      {"ASFLIP, step halved",
       [](cases::Plate& c) {
         c.transfer = TransferScheme::kAsflip;
         c.step_scale = 0.5;
       }},
      // Points dilated past sand's loosest packing (1.27 times its densest volume, as the
      // granular cases') carry no stress and no wave, so they no longer shorten the step.
      {"ASFLIP, separation 1.27",
       [](cases::Plate& c) {
         c.transfer = TransferScheme::kAsflip;
         c.separation = 1.27;
       }},
  };
  return all;
}

int choiceNamed(const std::string& name) {
  for (std::size_t i = 0; i < choices().size(); ++i)
    if (name == choices()[i].name) return static_cast<int>(i);
  throw std::logic_error("no choice " + name);
}

struct DiagnosisRun {
  int choice;
  bool push;   // the flat plate pushed down; else the upright plate dragged at `depth`
  Real depth;  // m
  Real h;      // m
};

std::vector<DiagnosisRun> diagnosisRunList(bool fast) {
  std::vector<DiagnosisRun> runs;
  if (fast) {
    for (const char* c : {"report's", "GIMP", "divergence average", "no sand behind", "ASFLIP"})
      runs.push_back({choiceNamed(c), false, 0.06, 0.02});
    return runs;
  }
  for (Real h : {0.01, 0.005}) {
    for (std::size_t c = 0; c < choices().size(); ++c)
      runs.push_back({static_cast<int>(c), false, 0.06, h});
    for (const char* c : {"report's", "GIMP", "divergence average", "GIMP and average", "ASFLIP",
                          "ASFLIP, separation 1.27"})
      runs.push_back({choiceNamed(c), true, 0, h});
    for (const char* c : {"report's", "divergence average", "ASFLIP"})
      for (Real z : {0.04, 0.08}) runs.push_back({choiceNamed(c), false, z, h});
  }
  for (const char* c : {"report's", "divergence average", "GIMP and average", "ASFLIP"})
    runs.push_back({choiceNamed(c), false, 0.06, 0.0025});
  for (Real z : {0.04, 0.08}) runs.push_back({choiceNamed("report's"), false, z, 0.0025});
  return runs;
}

cases::Plate plateOf(const DiagnosisRun& run) {
  cases::Plate c;
  c.cell_size = run.h;
  if (!run.push) c.angle = 90, c.direction = 0, c.depth = run.depth;
  choices()[run.choice].set(c);
  return c;
}

const char* kName = "intrusion_diagnosis";

}  // namespace

int intrusionDiagnosisRuns(bool fast) {
  return static_cast<int>(diagnosisRunList(fast).size());
}

void intrusionDiagnosis(const Options& o, Results& r) {
  const std::vector<DiagnosisRun> list = diagnosisRunList(o.fast);
  FILE* table = std::fopen((o.out + "/" + kName + ".csv").c_str(), "w");
  // choice: its index in choices(), named in results.csv's quantities.
  std::fprintf(table, "choice,push,depth_m,cell_m,points,steps,wall_s,fx_n_m,fz_n_m,kz_n_m2\n");
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!o.runs(static_cast<int>(i))) continue;
    const DiagnosisRun& run = list[i];
    const cases::Plate c = plateOf(run);
    World w(cases::plateIntrusion(c));
    const std::string checkpoint = o.out + "/" + kName + "." + std::to_string(i) + ".checkpoint";
    const cases::PlateRun p = cases::movePlate(w, c, {checkpoint});
    const char* choice = choices()[run.choice].name;
    const std::string cell = millimetres(run.h);
    Real kz = NAN;
    Vec2 f(NAN, NAN);
    char q[200];
    if (run.push) {
      kz = cases::pushLines(c, p).kz;
      std::snprintf(q, sizeof q, "k_z of the flat plate pushed down, %s, h %s", choice,
                    cell.c_str());
      r.add(kName, q, kz, kPushSlope, "N/m^2", "intrusion_refinement's k_z at 1.25 mm", p.seconds,
            "", static_cast<long>(p.points), p.steps);
    } else {
      f = cases::dragMean(c, p);
      std::snprintf(q, sizeof q, "alpha_x of the upright plate dragged at %.0f cm, %s, h %s",
                    100 * run.depth, choice, cell.c_str());
      r.add(kName, q, -f.x() / (run.depth * c.length), kDragLimit, "N/m^3",
            "intrusion_drag's converged limit", p.seconds, "", static_cast<long>(p.points),
            p.steps);
    }
    std::fprintf(table, "%d,%d,%.17g,%.17g,%zu,%ld,%.4g,%.17g,%.17g,%.17g\n", run.choice, run.push,
                 run.depth, run.h, p.points, p.steps, p.seconds, f.x(), f.y(), kz);
    std::fflush(table);
  }
  std::fclose(table);
}

void intrusionDiagnosisFits(const Options& o, Results& r) {
  if (o.fast) return;  // one depth
  const Table t(o.out + "/" + kName + ".csv");
  const Real L = cases::Plate().length;
  // A line for each choice and cell the run list drags at 4 cm (and so at 4, 6 and 8 cm).
  for (const DiagnosisRun& lined : diagnosisRunList(false)) {
    if (lined.push || lined.depth != 0.04) continue;
    cases::LineFit line;  // F = a + k z through the three depths (N/m, N/m^2)
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t.at(i, "choice") == lined.choice && t.at(i, "push") == 0 && t.at(i, "cell_m") == lined.h)
        line.add(t.at(i, "depth_m"), -t.at(i, "fx_n_m"));
    if (line.n < 3) throw std::runtime_error(std::string(kName) + ".csv lacks a depth");
    const char* choice = choices()[lined.choice].name;
    const std::string cell = millimetres(lined.h);
    char q[200];
    std::snprintf(q, sizeof q, "drag's line F(z), slope, %s, h %s", choice, cell.c_str());
    r.add(kName, q, line.slope(), kDragLimit * L, "N/m^2", "the converged line, alpha_x L", 0,
          "least squares through 4, 6 and 8 cm");
    std::snprintf(q, sizeof q, "drag's line F(z), intercept, %s, h %s", choice, cell.c_str());
    r.add(kName, q, line.intercept(), 0, "N/m", "the converged line passes through 0", 0,
          "least squares through 4, 6 and 8 cm");
  }
}

}  // namespace mpm_sdem::report::robots
