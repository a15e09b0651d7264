// Issue 44's intrusion cases: a plate pushed and dragged through the sand against resistive
// force theory (intrusion), what its forces owe to the transfer (intrusion_transfer), and their
// refinement (intrusion_refinement, intrusion_angles).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/world.hpp"
#include "report.hpp"

namespace mpm_sdem::report::robots {
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
  Real sleep = 0;           // solver.sleep_speed (m/s)
  StressUpdate update = StressUpdate::kUsf;
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

// RFT's one scale factor for a medium: zeta by least squares over both components of every
// measured alpha (N/m^3) against the generic ones, and the rms of the residual in N/m^3 and as a
// fraction of the rms of zeta alpha_gen (0 where the generic shapes hold exactly).
struct ZetaFit {
  Real zeta = 0, rms = 0, fraction = 0;
};
ZetaFit fitZeta(const std::vector<cases::RftStress>& measured,
                const std::vector<cases::RftStress>& generic) {
  Real num = 0, den = 0;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    num += measured[k].x * generic[k].x + measured[k].z * generic[k].z;
    den += generic[k].x * generic[k].x + generic[k].z * generic[k].z;
  }
  ZetaFit f;
  f.zeta = num / den;
  Real residual = 0, scale = 0;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    residual += std::pow(measured[k].x - f.zeta * generic[k].x, 2) +
                std::pow(measured[k].z - f.zeta * generic[k].z, 2);
    scale += std::pow(f.zeta * generic[k].x, 2) + std::pow(f.zeta * generic[k].z, 2);
  }
  f.rms = std::sqrt(residual / (2 * measured.size()));
  f.fraction = std::sqrt(residual / scale);
  return f;
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
  c.sleep_speed = run.sleep;
  c.stress_update = run.update;
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
// `checkpoint`: the run's checkpoint file (cases::PlateCheckpoints: a run of hours that is
// stopped continues from it when run again).
void intrusionRun(const IntrusionRun& run, const std::string& name, bool medium, FILE* table,
                  FILE* series, Results& r, const std::string& checkpoint) {
  const cases::Plate c = plateOf(run);
  World w(cases::plateIntrusion(c));
  const cases::PlateRun p = cases::movePlate(w, c, {checkpoint});
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
  const std::string levers_name =
      (run.sleep > 0 ? ", asleep below " + std::to_string(std::lround(1e3 * run.sleep)) + " mm/s"
                     : "") +
      (run.update == StressUpdate::kUsl ? ", USL" : "");
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
    std::snprintf(q, sizeof q, "drag force per depth, beta %g, z %.0f cm, h %s%s%s", run.beta,
                  100 * run.depth, millimetres(run.h).c_str(), medium_name.c_str(),
                  levers_name.c_str());
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
    if (o.runs(static_cast<int>(i)))
      intrusionRun(list[i], name, medium, table, series, r,
                   o.out + "/" + name + "." + std::to_string(i) + ".checkpoint");
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
  std::vector<cases::RftStress> measured, generic;
  for (const Alpha& a : alphas) {
    measured.push_back({a.x, a.z});
    generic.push_back(a.generic);
  }
  const ZetaFit fit = fitZeta(measured, generic);
  const Real zeta = fit.zeta;
  {
    char settings[200];
    std::snprintf(settings, sizeof settings,
                  "least squares over %zu alphas (x and z) at h %s: rms residual %.0f N/m^3, "
                  "%.3f of the rms of zeta alpha_gen",
                  alphas.size(), millimetres(h0).c_str(), fit.rms, fit.fraction);
    r.add("intrusion", "zeta (RFT's scale factor for this sand)", zeta, 0, "-",
          "fitted: one factor for every angle", 0, settings);
    r.add("intrusion", "rms residual / rms zeta alpha_gen", fit.fraction, 0, "-",
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
// `absolute`: each change as a difference (for ratios that pass near 0) instead of a percentage.
void addRefinement(Results& r, const std::string& name, const std::string& quantity,
                   const std::vector<std::pair<Real, Real>>& values, Real reference,
                   const std::string& unit, const std::string& source, bool absolute = false) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    char settings[96] = "";
    if (k > 0 && absolute)
      std::snprintf(settings, sizeof settings, "%+.3f from h %s",
                    values[k].second - values[k - 1].second,
                    millimetres(values[k - 1].first).c_str());
    else if (k > 0)
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

// Issue 44: the upright plate's drag under refinement, through 1.25 mm (`intrusion` drags it at
// 1 cm, 5 mm and 2.5 mm, where it still falls; its limit bounds the converged zeta,
// docs/robots.md): beta 90 dragged along x at 6 cm and 0.1 m/s, APIC, at 1 cm, 5 mm, 2.5 mm and
// 1.25 mm; alpha_x = -F_x / (z L) per cell with addRefinement's order and limit. The 1.25 mm drag
// took 79 minutes on two threads outside the report (256,000 points, 279,842 steps); its run
// writes a checkpoint every 10 minutes (cases::PlateCheckpoints). --fast: 2 and 1 cm.
namespace {

std::vector<IntrusionRun> intrusionDragRunList(bool fast) {
  std::vector<IntrusionRun> runs;
  for (Real h : refinementCells(fast)) runs.push_back({90, 0, 0.1, kIntrusionReference, h});
  return runs;
}

}  // namespace

int intrusionDragRuns(bool fast) {
  return static_cast<int>(intrusionDragRunList(fast).size());
}

void intrusionDrag(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionDragRunList(o.fast), "intrusion_drag", true);
}

void intrusionDragFits(const Options& o, Results& r) {
  const std::string name = "intrusion_drag";
  const Table t(o.out + "/" + name + ".csv");
  const Real L = cases::Plate().length;
  std::vector<IntrusionRun> runs = intrusionDragRunList(o.fast);
  std::sort(runs.begin(), runs.end(), [](auto& a, auto& b) { return a.h > b.h; });
  std::vector<std::pair<Real, Real>> alpha;
  for (const IntrusionRun& run : runs)
    alpha.emplace_back(run.h, -t.at(mediumRow(t, run, name), "fx_n_m") / (run.depth * L));
  addRefinement(r, name, "alpha_x, beta 90 dragged along x at 6 cm, 0.1 m/s (-F_x / (z L))", alpha,
                0, "N/m^3", "RFT: zeta x 370 kPa/m (the generic alpha_x of this drag)");
}

// Issue 78: speed against error for the upright plate's drag (intrusion_drag's run): at each
// cell with every point awake and with sand slower than 2 and 10 mm/s asleep (2% and 10% of the
// plate's speed), then in USL (every point awake); the wall time per simulated second
// and alpha_x's error from the drag's converged limit, 102.3 kPa/m (intrusion_drag: Richardson
// over 2.5 and 1.25 mm). --fast: 2 and 1 cm.
namespace {

std::vector<IntrusionRun> intrusionFrontierRunList(bool fast) {
  std::vector<IntrusionRun> runs;
  const std::vector<Real> cells =
      fast ? std::vector<Real>{0.02, 0.01} : std::vector<Real>{0.01, 0.005, 0.0025};
  for (Real h : cells) {
    for (Real sleep : {0.0, 0.002, 0.01}) {  // m/s: awake, 2% and 10% of the plate's speed
      IntrusionRun run{90, 0, 0.1, kIntrusionReference, h};
      run.sleep = sleep;
      runs.push_back(run);
    }
    IntrusionRun usl{90, 0, 0.1, kIntrusionReference, h};  // awake: sleep needs USF
    usl.update = StressUpdate::kUsl;
    runs.push_back(usl);
  }
  return runs;
}

}  // namespace

int intrusionFrontierRuns(bool fast) {
  return static_cast<int>(intrusionFrontierRunList(fast).size());
}

void intrusionFrontier(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionFrontierRunList(o.fast), "intrusion_frontier", false);
}

void intrusionFrontierFits(const Options& o, Results& r) {
  const std::string name = "intrusion_frontier";
  const Table t(o.out + "/" + name + ".csv");
  const std::vector<IntrusionRun> runs = intrusionFrontierRunList(o.fast);
  if (t.size() != runs.size())
    throw std::runtime_error(name + ".csv lacks a run (were all the case's runs gathered?)");
  const Real L = cases::Plate().length;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const IntrusionRun& run = runs[i];
    const Real alpha = -t.at(i, "fx_n_m") / (run.depth * L);
    // The plate descends the depth, then drags 3 L at its speed.
    const Real simulated = (run.depth + 3 * L) / run.speed;
    char q[160], settings[200];
    char sleep[64] = "all awake";
    if (run.sleep > 0) std::snprintf(sleep, sizeof sleep, "asleep below %g mm/s", 1e3 * run.sleep);
    std::snprintf(q, sizeof q, "alpha_x's error from the limit, h %s, %s%s",
                  millimetres(run.h).c_str(), sleep,
                  run.update == StressUpdate::kUsl ? ", USL" : "");
    std::snprintf(settings, sizeof settings,
                  "alpha_x %.4g N/m^3; %.4g s of wall time, about %.3g s per simulated s", alpha,
                  t.at(i, "wall_s"), t.at(i, "wall_s") / simulated);
    r.add(name, q, alpha / kDragLimit - 1, 0, "-",
          "intrusion_drag's limit 102.3 kPa/m (docs/robots.md)", t.at(i, "wall_s"), settings,
          static_cast<long>(t.at(i, "points")), static_cast<long>(t.at(i, "steps")));
  }
}

// Issue 44: the angle shapes under refinement (the intrusion case fits zeta at its 5 mm cell
// only). The plate pushed at 0.1 m/s along gamma = 90 deg (beta 0, 30, 60, 90: a negative beta
// is its positive's mirror image, F_x reversed and F_z equal to 5 digits in `intrusion`) and
// along 45 deg (beta -60 to 90), APIC, at 5 mm and 2.5 mm; the four along gamma 90 also at
// 1.25 mm (3,807-4,215 s each on one thread, two at a time; the six along 45 deg took
// 5,427-9,000 s each, run outside the report: docs/robots.md). Per cell:
// zeta by least squares over the pushes' alpha_x and alpha_z (as intrusion's, without the drags)
// with its rms residual, for every push and for those along gamma 90; and each alpha over the
// cell's alpha_z(beta 0, gamma 90), the scale-free shape that RFT's generic alphas fix, against
// the generic ratio, with its change from the coarser cell and, over three cells,
// addRefinement's order and limit. --fast: 2 and 1 cm, beta 0 and 60 pushed down and 0 along
// 45 deg.
namespace {

constexpr Real kAnglesFinest = 0.00125;  // m: the report's finest cell, only along gamma 90

std::vector<Real> angleCells(bool fast) {
  if (fast) return {0.01, 0.02};
  return {kAnglesFinest, 0.0025, 0.005};  // the longest runs first
}

// The pushes a cell runs: all of them, or at the finest report cell those along gamma 90.
bool runsAngle(bool fast, Real h, Real gamma) {
  return fast || h != kAnglesFinest || gamma == 90;
}

std::vector<IntrusionRun> intrusionAnglesRunList(bool fast) {
  std::vector<IntrusionRun> runs;
  for (Real h : angleCells(fast)) {
    if (fast) {
      for (Real beta : {0.0, 60.0}) runs.push_back({beta, 90, 0.1, 0, h});
      runs.push_back({0, 45, 0.1, 0, h});
      continue;
    }
    for (Real beta : {0.0, 30.0, 60.0, 90.0}) runs.push_back({beta, 90, 0.1, 0, h});
    if (runsAngle(fast, h, 45))
      for (Real beta : {-60.0, -30.0, 0.0, 30.0, 60.0, 90.0}) runs.push_back({beta, 45, 0.1, 0, h});
  }
  return runs;
}

}  // namespace

int intrusionAnglesRuns(bool fast) {
  return static_cast<int>(intrusionAnglesRunList(fast).size());
}

void intrusionAngles(const Options& o, Results& r) {
  runIntrusionList(o, r, intrusionAnglesRunList(o.fast), "intrusion_angles", true);
}

void intrusionAnglesFits(const Options& o, Results& r) {
  const std::string name = "intrusion_angles";
  const Table t(o.out + "/" + name + ".csv");
  const std::vector<IntrusionRun> runs = intrusionAnglesRunList(o.fast);
  const Real L = cases::Plate().length;
  std::vector<Real> cells = angleCells(o.fast);
  std::sort(cells.begin(), cells.end(), std::greater<Real>());
  const auto generic = [](const IntrusionRun& run) {
    return cases::rftGeneric(run.beta * M_PI / 180, run.gamma * M_PI / 180);
  };
  // Per cell (coarse to fine), each push's alpha over the cell's alpha_z(0, 90); and zeta over
  // all the pushes and over those along gamma 90, each with its ZetaFit::fraction residual.
  struct Cell {
    Real h;
    bool all;  // every angle ran
    ZetaFit every, down;
    std::vector<std::pair<IntrusionRun, cases::RftStress>> shape;
  };
  std::vector<Cell> fits;
  for (const Real h : cells) {
    Cell c{h, runsAngle(o.fast, h, 45), {}, {}, {}};
    std::vector<cases::RftStress> measured, gen, measured_down, gen_down;
    Real pushed = NAN;
    for (const IntrusionRun& run : runs) {
      if (run.h != h) continue;
      const std::size_t i = mediumRow(t, run, name);
      const cases::RftStress a{-t.at(i, "kx_n_m2") / L, t.at(i, "kz_n_m2") / L};
      measured.push_back(a), gen.push_back(generic(run));
      if (run.gamma == 90) measured_down.push_back(a), gen_down.push_back(generic(run));
      if (run.beta == 0 && run.gamma == 90) pushed = a.z;
      c.shape.emplace_back(run, a);
    }
    c.every = fitZeta(measured, gen);
    c.down = fitZeta(measured_down, gen_down);
    for (auto& [run, a] : c.shape) a = {a.x / pushed, a.z / pushed};
    fits.push_back(c);
  }
  // zeta over every push, at the cells that ran every angle.
  std::vector<std::pair<Real, Real>> every, down;
  for (const Cell& c : fits) {
    down.emplace_back(c.h, c.down.zeta);
    if (!c.all) continue;
    every.emplace_back(c.h, c.every.zeta);
    r.add(name, "rms residual / rms zeta alpha_gen, h " + millimetres(c.h), c.every.fraction, 0,
          "-", "RFT's generic shapes (0 where they hold exactly)", 0, "");
  }
  addRefinement(r, name, "zeta over the pushes", every, 0, "-",
                "fitted: one factor for every angle");
  addRefinement(r, name, "zeta over the pushes along gamma 90", down, 0, "-",
                "fitted: one factor for the pushes straight down");
  // Each shape ratio through the cells that ran its angle, and the largest change per halving.
  const cases::RftStress g0 = cases::rftGeneric(0, M_PI / 2);
  std::vector<Real> largest(fits.size(), 0);
  for (const auto& [run, unused] : fits.front().shape) {
    if (run.beta == 0 && run.gamma == 90) continue;  // 1 by definition
    for (const bool x : {false, true}) {
      std::vector<std::pair<Real, Real>> values;
      for (std::size_t c = 0; c < fits.size(); ++c)
        for (const auto& [other, a] : fits[c].shape) {
          if (other.beta != run.beta || other.gamma != run.gamma) continue;
          const Real value = x ? a.x : a.z;
          if (!values.empty())
            largest[c] = std::max(largest[c], std::abs(value - values.back().second));
          values.emplace_back(fits[c].h, value);
        }
      const cases::RftStress g = generic(run);
      char q[96];
      std::snprintf(q, sizeof q, "%s / alpha_z(0, 90), beta %g, gamma %g",
                    x ? "alpha_x" : "alpha_z", run.beta, run.gamma);
      addRefinement(r, name, q, values, (x ? g.x : g.z) / g0.z, "-",
                    "RFT's generic shapes (no zeta)", true);
    }
  }
  for (std::size_t c = 1; c < fits.size(); ++c)
    r.add(name,
          "largest change of a shape ratio, h " + millimetres(fits[c].h) + " from " +
              millimetres(fits[c - 1].h) + (fits[c].all ? "" : " (the pushes along gamma 90)"),
          largest[c], 0, "-", "(0 for a converged shape)", 0, "");
}

}  // namespace mpm_sdem::report::robots
