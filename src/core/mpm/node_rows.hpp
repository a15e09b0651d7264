// Four consecutive nodes of a grid row as one SIMD value, for the particle-grid sweeps
// (sweeps.cpp). A point in cell c (c = floor(x / h)) touches nodes c-1 .. c+2 along an axis
// with every kernel (3 of them with the quadratic B-spline and GIMP, 4 with the cubic), so one
// window of four nodes starting at c-1 holds its stencil along x: a row of the stencil is one
// vector load, multiply-add and store instead of three or four scalar ones. The window never
// reaches past c+2, so the tiles' colouring (tiles.hpp) keeps two threads off each other's
// nodes, also in the lanes that only add zero. Internal header of the core library.
//
// GCC's and Clang's vector extension: plain arithmetic on a fixed-size vector, lowered to the
// instructions of the target it is compiled for (AVX-512's 256-bit form, AVX2, pairs of SSE2
// operations), with no library and no intrinsics. Like a Highway "-inl.h" header it is compiled
// once per SIMD target (sweeps.cpp includes it under hwy/foreach_target.h): the sweeps call
// these functions with vector arguments, which Clang allows only within one target. Elsewhere
// it holds the build's own target, in detail::HWY_NAMESPACE.
#if defined(MPM_SDEM_NODE_ROWS_HPP_) == defined(HWY_TARGET_TOGGLE)  // per target, as Highway's
#ifdef MPM_SDEM_NODE_ROWS_HPP_
#undef MPM_SDEM_NODE_ROWS_HPP_
#else
#define MPM_SDEM_NODE_ROWS_HPP_
#endif

#include <cmath>
#include <cstring>
#include <type_traits>

#include "hwy/highway.h"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/types.hpp"

HWY_BEFORE_NAMESPACE();
namespace mpm_sdem::detail::HWY_NAMESPACE {

using Row4 = Real __attribute__((vector_size(4 * sizeof(Real))));
// The same vector at a node's alignment, for loads and stores at any node (declared as a typedef
// of Row4: Clang keeps a vector's own alignment when vector_size and aligned share one
// attribute). A vector of Real may alias Real (both compilers give it its element's alias set);
// memcpy would tell the compiler that any pointer may have changed and reload every array's
// address after each store.
typedef Row4 UnalignedRow4 __attribute__((aligned(alignof(Real))));
static_assert(alignof(UnalignedRow4) == alignof(Real), "loads and stores at any node");

inline Row4 loadRow(const Real* p) {
  return *reinterpret_cast<const UnalignedRow4*>(p);
}
inline void storeRow(Real* p, const Row4& v) {
  *reinterpret_cast<UnalignedRow4*>(p) = v;
}
// The sums of four rows' lanes at once, (sum a, sum b, sum c, sum d), each as
// (v0 + v1) + (v2 + v3): three shuffles and adds instead of four scalar reductions.
inline Row4 sums(const Row4& a, const Row4& b, const Row4& c, const Row4& d) {
  const Row4 ab =
      __builtin_shufflevector(a, b, 0, 4, 2, 6) + __builtin_shufflevector(a, b, 1, 5, 3, 7);
  const Row4 cd =
      __builtin_shufflevector(c, d, 0, 4, 2, 6) + __builtin_shufflevector(c, d, 1, 5, 3, 7);
  return __builtin_shufflevector(ab, cd, 0, 1, 4, 5) + __builtin_shufflevector(ab, cd, 2, 3, 6, 7);
}

// One axis of a point's stencil over the window of nodes first .. first+3 (first = c-1): the
// weights, their derivatives (per grid unit) and the offsets x_I - x_p (grid units); the lanes
// the kernel does not reach have zero weight and derivative.
struct Window {
  int first = 0;
  Row4 w, dw, r;
  Real second_moment = 0;  // sum_I w_I (x_I - x_p)^2: the APIC inertia's diagonal (grid units^2)
};

// The window from the kernel's own stencil (kernels.hpp), shifted to start at c-1: one
// definition of every kernel's weights for the scalar and the vector sweeps. The quadratic
// B-spline, the one of the default scenes, is evaluated in the lanes directly (the same
// polynomials as QuadraticBSpline::stencil, equal to round-off): assembling a vector from
// scalars in memory would stall the load behind four stores.
template <class K>
[[gnu::always_inline]] inline Window window(Real xg, Real half_size) {
  Window out;
  out.first = static_cast<int>(std::floor(xg)) - 1;
  const Row4 lanes = {0, 1, 2, 3};
  out.r = (lanes + Real(out.first)) - xg;  // node index exact, then one rounding, as the scalar
  if constexpr (std::is_same_v<K, QuadraticBSpline>) {
    // Seed 000 eq. A3 in r = x_I - x_p: 3/4 - r^2 inside half a cell, (3/2 - |r|)^2 / 2 out to
    // one and a half; the derivative is with respect to x_p.
    const Row4 q = out.r < 0 ? -out.r : out.r;
    const Row4 t = Real(1.5) - q, zero = {};
    const Row4 outer_w = Real(0.5) * t * t, outer_dw = out.r < 0 ? -t : t;
    out.w = q < Real(0.5) ? Real(0.75) - out.r * out.r : (q < Real(1.5) ? outer_w : zero);
    out.dw = q < Real(0.5) ? Real(2) * out.r : (q < Real(1.5) ? outer_dw : zero);
    out.second_moment = Real(0.25);
  } else {
    Stencil1D s;
    K::stencil(xg, half_size, s);
    const int shift = s.base - out.first;  // 0 or 1: where the kernel's first node falls
    Real w[4] = {0, 0, 0, 0}, dw[4] = {0, 0, 0, 0};
    for (int k = 0; k < K::kSupport; ++k) {
      w[k + shift] = s.w[k];
      dw[k + shift] = s.dw[k];
    }
    std::memcpy(&out.w, w, sizeof w);
    std::memcpy(&out.dw, dw, sizeof dw);
    out.second_moment = s.second_moment;
  }
  return out;
}

}  // namespace mpm_sdem::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // MPM_SDEM_NODE_ROWS_HPP_
