// updateStressBatch for every SIMD target Highway compiles here, and the run-time choice among
// them (hwy/foreach_target.h re-includes this file once per target). Each lane computes what
// constitutive.hpp computes for one point, in the same order of operations; both branches of
// every return are evaluated and the lane's own is selected.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mpm/stress_batch.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "mpm/stress_batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace mpm_sdem::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<Real>;
using V = hn::Vec<D>;

struct Lanes {
  V xx, yy, xy, zz;
};

// Seed 000 eq. 33-34: sigma_m and tau = sqrt(J2) (meanStress, equivalentShear).
HWY_INLINE V mean(D d, const Lanes& s) {
  return (s.xx + s.yy + s.zz) / hn::Set(d, 3);
}
HWY_INLINE V shear(D d, const Lanes& s, V sm) {
  const V ax = s.xx - sm, ay = s.yy - sm, az = s.zz - sm;
  return hn::Sqrt(hn::Set(d, 0.5) * (ax * ax + ay * ay + az * az) + s.xy * s.xy);
}

// The deviator scaled by scale about the new mean stress sm_new.
HWY_INLINE Lanes rescaled(const Lanes& s, V sm, V scale, V sm_new) {
  return {(s.xx - sm) * scale + sm_new, (s.yy - sm) * scale + sm_new, s.xy * scale,
          (s.zz - sm) * scale + sm_new};
}

// druckerPragerReturn, lane by lane.
HWY_INLINE void druckerPrager(D d, const MaterialParams& m, Lanes& s) {
  const V sm = mean(d, s), tau = shear(d, s, sm);
  const V tension = hn::Set(d, m.tension), tau_corner = hn::Set(d, m.tau_corner);
  const V fs = tau + hn::Set(d, m.q_phi) * sm - hn::Set(d, m.k_phi);
  const V ft = sm - tension;
  const auto elastic = hn::And(fs <= hn::Zero(d), ft <= hn::Zero(d));
  const auto shear_return = hn::Or(
      ft <= hn::Zero(d), tau - tau_corner - hn::Set(d, m.alpha_p) * (sm - tension) > hn::Zero(d));
  // Shear: back along the flow potential, onto the corner if that overshoots the cut-off.
  const V multiplier = fs * hn::Set(d, m.inv_return_modulus);
  V sm_shear = sm - hn::Set(d, m.bulk * m.q_psi) * multiplier;
  V tau_shear = hn::Set(d, m.k_phi) - hn::Set(d, m.q_phi) * sm_shear;
  const auto overshot = sm_shear > tension;
  sm_shear = hn::IfThenElse(overshot, tension, sm_shear);
  tau_shear = hn::IfThenElse(overshot, tau_corner, tau_shear);
  // Tension: onto the cut-off, tau capped at the corner (a NaN tau takes the corner).
  const V tau_tension = hn::IfThenElse(tau < tau_corner, tau, tau_corner);
  const V sm_new = hn::IfThenElse(shear_return, sm_shear, tension);
  const V tau_new = hn::IfThenElse(shear_return, tau_shear, tau_tension);
  const auto positive = tau > hn::Zero(d);
  const V scale = hn::IfThenElseZero(positive, hn::IfThenElseZero(tau_new > hn::Zero(d), tau_new) /
                                                   hn::IfThenElse(positive, tau, hn::Set(d, 1)));
  const Lanes r = rescaled(s, sm, scale, sm_new);
  s = {hn::IfThenElse(elastic, s.xx, r.xx), hn::IfThenElse(elastic, s.yy, r.yy),
       hn::IfThenElse(elastic, s.xy, r.xy), hn::IfThenElse(elastic, s.zz, r.zz)};
}

void UpdateStressBatch(const MaterialParams& m, StressBatch& b, Real dt) {
  const D d;
  const V half = hn::Set(d, 0.5), two = hn::Set(d, 2), one = hn::Set(d, 1), vdt = hn::Set(d, dt);
  const V lame = hn::Set(d, m.lame), two_g = hn::Set(d, 2 * m.shear);
  const V separation = hn::Set(d, m.separation);
  for (int i = 0; i < b.count; i += static_cast<int>(hn::Lanes(d))) {
    const V lxx = hn::Load(d, b.lxx + i), lxy = hn::Load(d, b.lxy + i);
    const V lyx = hn::Load(d, b.lyx + i), lyy = hn::Load(d, b.lyy + i);
    Lanes s{hn::Load(d, b.sxx + i), hn::Load(d, b.syy + i), hn::Load(d, b.sxy + i),
            hn::Load(d, b.szz + i)};
    // jaumannElasticUpdate (seed 000 eq. 21-25).
    const V dxx = lxx * vdt, dyy = lyy * vdt, dxy = half * (lxy + lyx) * vdt;
    const V w = half * (lxy - lyx) * vdt;
    const V tr = dxx + dyy;
    const Lanes r{s.xx + lame * tr + two_g * dxx + two * w * s.xy,
                  s.yy + lame * tr + two_g * dyy - two * w * s.xy,
                  s.xy + two_g * dxy + w * (s.yy - s.xx), s.zz + lame * tr};
    s = r;
    const V J =
        hn::Load(d, b.J + i) * ((one + vdt * lxx) * (one + vdt * lyy) - vdt * vdt * lxy * lyx);
    hn::Store(J, d, b.J + i);
    if (m.model == MaterialModel::kDruckerPrager) druckerPrager(d, m, s);
    const auto loose = J > separation;
    hn::Store(hn::IfThenZeroElse(loose, s.xx), d, b.sxx + i);
    hn::Store(hn::IfThenZeroElse(loose, s.yy), d, b.syy + i);
    hn::Store(hn::IfThenZeroElse(loose, s.xy), d, b.sxy + i);
    hn::Store(hn::IfThenZeroElse(loose, s.zz), d, b.szz + i);
  }
}

}  // namespace mpm_sdem::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace mpm_sdem::detail {

#if MPM_SDEM_STATIC_SIMD
// Only the target the compiler flags name (bench/instructions.sh: valgrind cannot run libhwy's
// start-up code, and counts the AVX2 build it asks for).
void updateStressBatch(const MaterialParams& m, StressBatch& b, Real dt) {
  HWY_STATIC_DISPATCH(UpdateStressBatch)(m, b, dt);
}
#else
HWY_EXPORT(UpdateStressBatch);

void updateStressBatch(const MaterialParams& m, StressBatch& b, Real dt) {
  HWY_DYNAMIC_DISPATCH(UpdateStressBatch)(m, b, dt);
}
#endif

}  // namespace mpm_sdem::detail
#endif
