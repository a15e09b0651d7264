// The stress update of many points at once (issue 42): the arithmetic of updatePointStress
// (transfer.hpp) for one material, across points in the lanes of the widest vectors the running
// CPU has (Google Highway, chosen at run time: AVX-512, AVX2 or SSE4 from one binary). The
// scalar functions of constitutive.hpp stay the definition; test_stress_batch checks that
// every lane agrees with them to round-off.
#pragma once

#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::detail {

// Up to kSize points of one material, one array per field (structure of arrays). kSize is a
// multiple of every vector's lane count (8 doubles or 16 floats in 512 bits); lanes from count
// up are padding and their results are not read.
struct StressBatch {
  static constexpr int kSize = 16;
  alignas(64) Real lxx[kSize], lxy[kSize], lyx[kSize], lyy[kSize];  // L_p (1/s)
  alignas(64) Real sxx[kSize], syy[kSize], sxy[kSize], szz[kSize];  // sigma_p (Pa)
  alignas(64) Real J[kSize];                                        // V / V0
  int count = 0;
};

// Whether a material's update runs in batches: its row's batches_stress (material.hpp), true for
// Drucker-Prager's return, whose square root, division and branches the lanes share. Measured and
// left point by point (bench/README.md, issue 42): the linear elastic update, which costs about as
// much as gathering a batch; the granular return (a settled column: 261 M points/s alone, 150 M
// batched, Highway's logarithm against libm's and both branches in every lane; a collapsing one:
// the same time per step); a fluid's Tait pressure.
inline bool batchesStress(const MaterialParams& m) {
  return m.batches_stress;
}

// The stress and volume of the batch's points over dt, as updatePointStress does one point:
// Jaumann-rate elasticity (seed 000 eq. 21-25), J *= det(I + dt L), then the Drucker-Prager
// return (eq. 31-35) for that material, and no stress beyond the separation volume ratio. Linear
// elastic or Drucker-Prager only.
void updateStressBatch(const MaterialParams& m, StressBatch& b, Real dt);

}  // namespace mpm_sdem::detail
