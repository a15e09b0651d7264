#pragma once

#include <omp.h>

namespace mpm_sdem::detail {

// Whether loops run on the calling thread alone. A parallel region costs libgomp a team and a
// futex system call at its end even for a team of one (1.8 us on a 2-core VM, measured), and a
// step enters about 24 of them (15% of the default scene's step on one thread), so with one
// thread allowed the loops below skip the region; the work and its order are the same. (The
// SPH stages, in SPH scenes only, still enter theirs.)
inline bool singleThread() {
  return omp_get_max_threads() == 1;
}

// While alive, the calling thread's parallel regions run on it alone when `serial` (a world too
// small to share: SolverDef::parallel_min_points); its thread count is restored after.
class SerialScope {
 public:
  explicit SerialScope(bool serial) : restore_(serial ? omp_get_max_threads() : 0) {
    if (restore_ > 1) omp_set_num_threads(1);
  }
  ~SerialScope() {
    if (restore_ > 1) omp_set_num_threads(restore_);
  }
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;

 private:
  int restore_;
};

// body(k) for k in [0, count), the iterations shared statically among the threads.
template <class Body>
void parallelFor(long count, Body&& body) {
  if (singleThread()) {
    for (long k = 0; k < count; ++k) body(k);
    return;
  }
#pragma omp parallel for schedule(static)
  for (long k = 0; k < count; ++k) body(k);
}

}  // namespace mpm_sdem::detail
