#include "compare.hpp"

#include "mpm_sdem/ros/conversions.hpp"

#include <opencv2/flann.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace mpm_sdem::compare {

namespace {

constexpr double kSameTime = 1e-6;  // s: stamps this close are one time

// The recording period of a series: the median spacing of its times (0 with fewer than two).
template <class T, class Time>
double period(const std::vector<T>& v, Time t) {
  std::vector<double> gaps;
  for (std::size_t k = 1; k < v.size(); ++k) gaps.push_back(t(v[k]) - t(v[k - 1]));
  if (gaps.empty()) return 0;
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2];
}

// b read at time t between two of its samples: b[lo] with weight 1 - w and b[hi] with weight w.
struct Bracket {
  std::size_t lo = 0, hi = 0;
  double w = 0;
};

// b's samples on either side of t, or none when t lies outside b's span or in a gap longer than
// twice b's recording period (missing samples are not bridged).
template <class B, class Time>
bool bracket(const std::vector<B>& b, Time tb, double t, double b_period, Bracket& out) {
  const auto after = std::lower_bound(b.begin(), b.end(), t - kSameTime,
                                      [&](const B& s, double x) { return tb(s) < x; });
  if (after == b.end()) return false;
  const std::size_t hi = after - b.begin();
  if (std::abs(tb(b[hi]) - t) <= kSameTime) {
    out = {hi, hi, 1};
    return true;
  }
  if (hi == 0) return false;
  const double t0 = tb(b[hi - 1]), t1 = tb(b[hi]);
  if (t1 - t0 > 2 * b_period + kSameTime) return false;
  out = {hi - 1, hi, (t - t0) / (t1 - t0)};
  return true;
}

// Calls f(i, j) for each snapshot a[i] with b's nearest, b[j], within half a recording period
// (the shorter of the two runs'); counts the pairs that f compared (it returns whether it did).
template <class T, class Time, class F>
Paired forNearest(const std::vector<T>& a, const std::vector<T>& b, Time t, F f) {
  Paired p;
  p.of = a.size();
  const double pa = period(a, t), pb = period(b, t);
  const double tolerance = (pa > 0 && pb > 0 ? 0.5 * std::min(pa, pb) : 0) + kSameTime;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto after = std::lower_bound(b.begin(), b.end(), t(a[i]),
                                        [&](const T& s, double x) { return t(s) < x; });
    std::size_t j = after - b.begin();
    if (j > 0 && (j == b.size() || t(a[i]) - t(b[j - 1]) < t(b[j]) - t(a[i]))) --j;
    if (j >= b.size() || std::abs(t(b[j]) - t(a[i])) > tolerance || !f(i, j)) continue;
    p.largest_offset = std::max(p.largest_offset, std::abs(t(b[j]) - t(a[i])));
    ++p.paired;
  }
  return p;
}

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0 : std::sqrt(s / v.size());
}

const mpm_sdem::RigidBlockState* findBlock(const mpm_sdem::BlockStates& s, const std::string& n) {
  for (const auto& b : s.blocks)
    if (b.name == n) return &b;
  return nullptr;
}

// Every block name a run recorded, in the order they first appear.
std::vector<std::string> blockNames(const RunSeries& run) {
  std::vector<std::string> names;
  std::unordered_set<std::string> seen;
  for (const auto& s : run.blocks)
    for (const auto& b : s.blocks)
      if (seen.insert(b.name).second) names.push_back(b.name);
  return names;
}

double firstContact(const RunSeries& run, const std::string& name) {
  for (const auto& s : run.blocks) {
    const auto* b = findBlock(s, name);
    if (b && b->contact_count > 0) return s.header.stamp.toSec();
  }
  return -1;
}

// Mean distance from each point of `from` to its nearest neighbour in `to` (FLANN k-d tree).
double oneWayDistance(const std::vector<float>& from, const std::vector<float>& to) {
  const int nf = static_cast<int>(from.size() / 2), nt = static_cast<int>(to.size() / 2);
  if (nf == 0 || nt == 0) return std::numeric_limits<double>::quiet_NaN();
  const cv::Mat data(nt, 2, CV_32F, const_cast<float*>(to.data()));
  const cv::Mat query(nf, 2, CV_32F, const_cast<float*>(from.data()));
  cv::flann::Index index(data, cv::flann::KDTreeIndexParams(4));
  cv::Mat indices, dist2;
  index.knnSearch(query, indices, dist2, 1, cv::flann::SearchParams(128));
  double sum = 0;
  for (int i = 0; i < nf; ++i) sum += std::sqrt(std::max(0.f, dist2.at<float>(i, 0)));
  return sum / nf;
}

}  // namespace

double meanNearestDistance(const std::vector<float>& a, const std::vector<float>& b) {
  return 0.5 * (oneWayDistance(a, b) + oneWayDistance(b, a));
}

double occupancyIoU(const std::vector<float>& a, const std::vector<float>& b, double cell) {
  auto cells = [cell](const std::vector<float>& xy) {
    std::unordered_set<long long> out;
    for (std::size_t k = 0; k + 1 < xy.size(); k += 2) {
      const long long i = static_cast<long long>(std::floor(xy[k] / cell));
      const long long j = static_cast<long long>(std::floor(xy[k + 1] / cell));
      out.insert((i << 32) ^ (j & 0xffffffffLL));
    }
    return out;
  };
  const auto ca = cells(a), cb = cells(b);
  std::size_t both = 0;
  for (long long c : ca) both += cb.count(c);
  const std::size_t either = ca.size() + cb.size() - both;
  return either ? static_cast<double>(both) / either : 1.0;
}

Comparison compareRuns(const RunSeries& a, const RunSeries& b, double raster) {
  Comparison out;
  out.raster = raster;
  // Blocks by name, wherever both runs recorded them (a block spawned while running appears
  // from its spawn on).
  const std::vector<std::string> names_a = blockNames(a), names_b = blockNames(b);
  const std::unordered_set<std::string> in_a(names_a.begin(), names_a.end()),
      in_b(names_b.begin(), names_b.end());
  for (const std::string& n : names_a)
    if (!in_b.count(n)) out.only_a.push_back(n);
  for (const std::string& n : names_b)
    if (!in_a.count(n)) out.only_b.push_back(n);
  auto state_time = [](const mpm_sdem::BlockStates& s) { return s.header.stamp.toSec(); };
  const double b_state_period = period(b.blocks, state_time);
  for (const std::string& name : names_a) {
    if (!in_b.count(name)) continue;
    BlockError e;
    e.name = name;
    // Each of a's states holding the block, against b's interpolated in time.
    for (const auto& sa : a.blocks) {
      const auto* pa = findBlock(sa, name);
      if (!pa) continue;
      ++e.paired.of;
      Bracket k;
      if (!bracket(b.blocks, state_time, state_time(sa), b_state_period, k)) continue;
      const auto* lo = findBlock(b.blocks[k.lo], name);
      const auto* hi = findBlock(b.blocks[k.hi], name);
      if (!lo || !hi) continue;
      ++e.paired.paired;
      const double x = lo->pose.position.x + k.w * (hi->pose.position.x - lo->pose.position.x);
      const double y = lo->pose.position.y + k.w * (hi->pose.position.y - lo->pose.position.y);
      const double yaw_lo = conversions::yaw(lo->pose.orientation);
      const double yaw =
          yaw_lo + k.w * std::remainder(conversions::yaw(hi->pose.orientation) - yaw_lo, 2 * M_PI);
      e.time.push_back(state_time(sa));
      e.position.push_back(std::hypot(pa->pose.position.x - x, pa->pose.position.y - y));
      e.angle.push_back(
          std::abs(std::remainder(conversions::yaw(pa->pose.orientation) - yaw, 2 * M_PI)));
    }
    e.rms_position = rms(e.position);
    e.rms_angle = rms(e.angle);
    e.final_position = e.position.empty() ? 0 : e.position.back();
    e.final_angle = e.angle.empty() ? 0 : e.angle.back();
    e.first_contact_a = firstContact(a, name);
    e.first_contact_b = firstContact(b, name);
    out.blocks.push_back(std::move(e));
  }
  auto tc = [](const Cloud& c) { return c.time; };
  out.clouds.paired = forNearest(a.clouds, b.clouds, tc, [&](std::size_t i, std::size_t j) {
    out.clouds.time.push_back(a.clouds[i].time);
    out.clouds.distance.push_back(meanNearestDistance(a.clouds[i].xy, b.clouds[j].xy));
    out.clouds.iou.push_back(occupancyIoU(a.clouds[i].xy, b.clouds[j].xy, raster));
    const std::vector<float>&sa = a.clouds[i].sph_xy, &sb = b.clouds[j].sph_xy;
    out.clouds.sph_count_a.push_back(sa.size() / 2);
    out.clouds.sph_count_b.push_back(sb.size() / 2);
    out.clouds.sph_distance.push_back(sa.empty() || sb.empty() ? -1 : meanNearestDistance(sa, sb));
    return true;
  });
  out.fem.paired = forNearest(a.fem_nodes, b.fem_nodes, tc, [&](std::size_t i, std::size_t j) {
    const std::vector<float>&pa = a.fem_nodes[i].xy, &pb = b.fem_nodes[j].xy;
    if (pa.size() != pb.size()) return false;  // different meshes: nothing to compare
    double sum = 0, largest = 0;
    for (std::size_t k = 0; k + 1 < pa.size(); k += 2) {
      const double d = std::hypot(pa[k] - pb[k], pa[k + 1] - pb[k + 1]);
      sum += d * d;
      largest = std::max(largest, d);
    }
    out.fem.time.push_back(a.fem_nodes[i].time);
    out.fem.rms.push_back(pa.empty() ? 0 : std::sqrt(sum / (pa.size() / 2)));
    out.fem.largest.push_back(largest);
    return true;
  });
  auto te = [](const EnergySample& s) { return s.time; };
  double scale = 0;
  for (const auto& s : a.energy) scale = std::max(scale, std::abs(s.total));
  std::vector<double> rel;
  const double b_energy_period = period(b.energy, te);
  out.energy.paired.of = a.energy.size();
  for (const EnergySample& sa : a.energy) {
    Bracket k;
    if (!bracket(b.energy, te, sa.time, b_energy_period, k)) continue;
    ++out.energy.paired.paired;
    const double total_b =
        b.energy[k.lo].total + k.w * (b.energy[k.hi].total - b.energy[k.lo].total);
    out.energy.time.push_back(sa.time);
    out.energy.total_a.push_back(sa.total);
    out.energy.total_b.push_back(total_b);
    rel.push_back(scale > 0 ? (sa.total - total_b) / scale : 0);
  }
  out.energy.rms_relative = rms(rel);
  out.energy.final_relative = rel.empty() ? 0 : std::abs(rel.back());
  return out;
}

std::vector<std::string> fewPaired(const Comparison& c) {
  std::vector<std::string> out;
  auto check = [&](const std::string& kind, const Paired& p) {
    if (p.fraction() < kEnoughPaired)
      out.push_back(kind + ": " + std::to_string(p.paired) + " of " + std::to_string(p.of) +
                    " paired");
  };
  for (const BlockError& e : c.blocks) check("block " + e.name, e.paired);
  check("particle clouds", c.clouds.paired);
  check("FEM nodes", c.fem.paired);
  check("energies", c.energy.paired);
  return out;
}

}  // namespace mpm_sdem::compare
