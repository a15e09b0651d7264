#include "mpm_sdem/core/mpm/tiles.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "parallel.hpp"

namespace mpm_sdem {

void Tiles::init(const Grid& g) {
  nx = (g.nx + kSize - 1) / kSize;
  ny = (g.ny + kSize - 1) / kSize;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  start.assign(n + 1, 0);
  mpm_end.assign(n, 0);
  grid_end.assign(n, 0);
  reach_.assign(n, 0);
  order.clear();
  for (auto& c : colour) c.clear();
  active.clear();
  previous.clear();
  retired.clear();
}

void Tiles::bin(const Particles& P, const Grid& g, bool asleep,
                const std::vector<PointRun>* awake) {
  sort(P, g, false, asleep, awake);
  activate();
}

void Tiles::rebin(const Particles& P, const Grid& g, const std::vector<PointRun>* awake) {
  sort(P, g, false, false, awake);
  active.swap(previous);  // activate() swaps them back: previous is the last step's again
  activate();
}

void Tiles::binByKind(const Particles& P, const Grid& g) {
  sort(P, g, true, false, nullptr);
}

void Tiles::sort(const Particles& P, const Grid& g, bool by_kind, bool asleep,
                 const std::vector<PointRun>* awake) {
  const long n = static_cast<long>(P.size());
  key_.resize(n);
  // Without runs, one run of every point.
  const PointRun all{0, n};
  const PointRun* runs = awake ? awake->data() : &all;
  const long run_count = awake ? static_cast<long>(awake->size()) : 1;
  long binned = 0;
  for (long r = 0; r < run_count; ++r) binned += runs[r].end - runs[r].begin;
  order.resize(binned);
  // Keys are tile * kinds + kind; one kind when kinds are not told apart.
  const int kinds = by_kind ? 2 : 1;
  // One bucket past the tiles holds the points not binned (awake or asleep, as not asked).
  const int tiles = nx * ny * kinds, buckets = tiles + 1;
  counts_.resize(static_cast<std::size_t>(omp_get_max_threads()) * buckets);
  const Real inv_h = g.inv_h, ox = g.origin.x(), oy = g.origin.y();
  const int last_x = nx - 1, last_y = ny - 1;
  // Counting sort in parallel: each thread counts its own contiguous range of points per tile,
  // then writes them after the lower threads' points of the same tile. The order is the serial
  // stable one whatever the thread count.
  auto countingSort = [&] {
    const int threads = omp_get_num_threads(), me = omp_get_thread_num();
    // This thread's share of the points: a contiguous range of them in storage order, across
    // the runs, as without runs.
    auto forMyPoints = [&](auto&& f) {
      const long lo = binned * me / threads, hi = binned * (me + 1) / threads;
      long offset = 0;  // points of the runs before run r
      for (long r = 0; r < run_count && offset < hi; ++r) {
        const long len = runs[r].end - runs[r].begin;
        const long first = std::max(lo - offset, 0L), last = std::min(hi - offset, len);
        for (long p = runs[r].begin + first; p < runs[r].begin + last; ++p) f(p);
        offset += len;
      }
    };
    int* count = counts_.data() + static_cast<std::size_t>(me) * buckets;
    std::fill(count, count + buckets, 0);
    const std::uint8_t want = asleep ? 1 : 0;
    forMyPoints([&](long p) {
      // Points are kept inside the domain, so their cell lies inside the grid; the clamps only
      // guard against a non-finite position, which the step reports separately.
      const int a = static_cast<int>((P.x[p] - ox) * inv_h) / kSize;
      const int b = static_cast<int>((P.y[p] - oy) * inv_h) / kSize;
      const int t = std::clamp(a, 0, last_x) + std::clamp(b, 0, last_y) * nx;
      key_[p] = P.asleep[p] != want ? tiles : by_kind ? 2 * t + P.kind[p] : t;
      ++count[key_[p]];
    });
#pragma omp barrier
#pragma omp single
    {
      int next = 0;
      for (int t = 0; t < buckets; ++t) {
        if (t == tiles) start[tiles / kinds] = next;
        if (t < tiles && t % kinds == 0) start[t / kinds] = next;
        if (t % kinds == 1) mpm_end[t / kinds] = next;
        for (int k = 0; k < threads; ++k) {
          int& c = counts_[static_cast<std::size_t>(k) * buckets + t];
          const int m = c;
          c = next;  // becomes this thread's write position in the tile
          next += m;
        }
      }
    }
    forMyPoints([&](long p) { order[count[key_[p]]++] = static_cast<int>(p); });
  };
  // Outside a parallel region (one thread) the barrier is nothing and the single block runs.
  if (detail::singleThread()) {
    countingSort();
  } else {
#pragma omp parallel
    countingSort();
  }
  if (!by_kind) std::copy(start.begin() + 1, start.end(), mpm_end.begin());
  grid_end = mpm_end;
}

void Tiles::activate() {
  const int tiles = nx * ny;
  const int last_x = nx - 1, last_y = ny - 1;
  for (auto& c : colour) c.clear();
  previous.swap(active);
  active.clear();
  std::fill(reach_.begin(), reach_.end(), 0);
  for (int t = 0; t < tiles; ++t) {
    if (grid_end[t] == start[t]) continue;
    const int a = t % nx, b = t / nx;
    colour[(a & 1) | ((b & 1) << 1)].push_back(t);
    // A particle writes nodes from one before its tile to two past it: the neighbouring tiles.
    for (int j = std::max(b - 1, 0); j <= std::min(b + 1, last_y); ++j) {
      for (int i = std::max(a - 1, 0); i <= std::min(a + 1, last_x); ++i) reach_[i + j * nx] = 1;
    }
  }
  if (periodic_x) {
    for (int b = 0; b < ny; ++b) {
      auto* row = reach_.data() + b * nx;
      if (std::find(row, row + nx, 1) != row + nx) std::fill(row, row + nx, 1);
    }
  }
  for (int t = 0; t < tiles; ++t)
    if (reach_[t]) active.push_back(t);
  retired.clear();
  for (int t : previous)
    if (!reach_[t]) retired.push_back(t);
}

void Tiles::nodeRuns(const Grid& g, const std::vector<int>& tiles,
                     std::vector<NodeRun>& runs) const {
  runs.clear();
  for (std::size_t k = 0; k < tiles.size();) {
    const int t0 = tiles[k], b = t0 / nx;
    std::size_t last = k;  // the run of tiles t0, t0 + 1, ... in tile row b
    while (last + 1 < tiles.size() && tiles[last + 1] == tiles[last] + 1 &&
           tiles[last + 1] / nx == b)
      ++last;
    const int i0 = (t0 % nx) * kSize, i1 = std::min((tiles[last] % nx + 1) * kSize, g.nx);
    for (int j = b * kSize; j < std::min((b + 1) * kSize, g.ny); ++j)
      runs.push_back({j * g.nx + i0, j * g.nx + i1});
    k = last + 1;
  }
}

}  // namespace mpm_sdem
