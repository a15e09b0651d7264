// What every case of mpm_sdem_validate shares: the options, the results file (one row per
// measured quantity), and the cases by topic (one file each in validation/report/).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mpm_sdem/core/coupling/coupling.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::report {

struct Options {
  std::string out = "validation_out";
  bool fast = false;
};

class Results {
 public:
  explicit Results(const std::string& path) : f_(std::fopen(path.c_str(), "w")) {
    if (f_)
      std::fprintf(
          f_, "case,quantity,value,reference,unit,source,error,wall_s,settings,points,steps\n");
  }
  ~Results() {
    if (f_) std::fclose(f_);
  }
  bool ok() const { return f_ != nullptr; }
  int nonFinite() const { return non_finite_; }
  void add(const std::string& c, const std::string& quantity, double value, double reference,
           const std::string& unit, const std::string& source, double wall,
           const std::string& settings, long points = 0, long steps = 0) {
    const double error =
        reference != 0 ? std::abs(value - reference) / std::abs(reference) : std::abs(value);
    if (!std::isfinite(value)) ++non_finite_;
    std::fprintf(f_, "%s,\"%s\",%.8g,%.8g,%s,\"%s\",%.6g,%.4g,\"%s\",%ld,%ld\n", c.c_str(),
                 quantity.c_str(), value, reference, unit.c_str(), source.c_str(), error, wall,
                 settings.c_str(), points, steps);
    std::fflush(f_);
    std::printf("  %-36s %12.6g  (reference %.6g %s, error %.3g)\n", quantity.c_str(), value,
                reference, unit.c_str(), error);
    std::fflush(stdout);
  }

 private:
  FILE* f_;
  int non_finite_ = 0;
};

// Every coupling scheme, in the order of coupling.hpp's table.
inline std::vector<CouplingScheme> allSchemes() {
  std::vector<CouplingScheme> out;
  for (const SchemeTraits& t : couplingSchemes()) out.push_back(t.scheme);
  return out;
}

inline double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Least-squares line y = a + b x through the points added.
struct LineFit {
  Real n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  void add(Real x, Real y) {
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  Real slope() const { return (n * sxy - sx * sy) / (n * sxx - sx * sx); }
  Real intercept() const { return (sy - slope() * sx) / n; }
};

namespace contact {
void collision(const Options& o, Results& r);
void forces(const Options& o, Results& r);
void drop(const Options& o, Results& r);
void incline(const Options& o, Results& r);
void contactSchemes(const Options& o, Results& r);
void rolling(const Options& o, Results& r);
void clusters(const Options& o, Results& r);
}  // namespace contact
namespace hard_cases {
void stability(const Options& o, Results& r);
}  // namespace hard_cases
namespace granular {
void siloDischarge(const Options& o, Results& r);
void siloConvergence(const Options& o, Results& r);
void siloGranular(const Options& o, Results& r);
void siloGranularAsflip(const Options& o, Results& r);
void compression(const Options& o, Results& r);
void chuteFlow(const Options& o, Results& r);
void columnCollapse(const Options& o, Results& r);
}  // namespace granular
namespace sph {
void bar(const Options& o, Results& r);
void sph(const Options& o, Results& r);
}  // namespace sph
namespace debris {
void debris(const Options& o, Results& r);
void debrisSweep(const Options& o, Results& r);
void debrisEnsemble(const Options& o, Results& r);
void debrisGranular(const Options& o, Results& r);
void debrisSeed003(const Options& o, Results& r);
void debrisTimeStep(const Options& o, Results& r);
void debrisFlow(const Options& o, Results& r);
}  // namespace debris
namespace fem {
void femCantilever(const Options& o, Results& r);
void femIncline(const Options& o, Results& r);
void flexibleBarrier(const Options& o, Results& r);
void waterGate(const Options& o, Results& r);
}  // namespace fem
namespace robots {
void wheel(const Options& o, Results& r);
void wheelGranular(const Options& o, Results& r);
void blade(const Options& o, Results& r);
void bladeGranular(const Options& o, Results& r);
}  // namespace robots

}  // namespace mpm_sdem::report
