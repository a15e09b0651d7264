#include "compare.hpp"

#include "mpm_sdem/ros/conversions.hpp"

#include <opencv2/flann.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace mpm_sdem::compare {

namespace {

constexpr double kSameTime = 1e-6;  // s

// Calls f(i, j) for every pair of samples of a and b recorded at the same time.
template <class A, class B, class TimeA, class TimeB, class F>
void forMatched(const std::vector<A>& a, const std::vector<B>& b, TimeA ta, TimeB tb, F f) {
  std::size_t j = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    while (j < b.size() && tb(b[j]) < ta(a[i]) - kSameTime) ++j;
    if (j < b.size() && std::abs(tb(b[j]) - ta(a[i])) <= kSameTime) f(i, j);
  }
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
  for (const std::string& name : names_a) {
    if (!in_b.count(name)) continue;
    BlockError e;
    e.name = name;
    auto t = [](const mpm_sdem::BlockStates& s) { return s.header.stamp.toSec(); };
    forMatched(a.blocks, b.blocks, t, t, [&](std::size_t i, std::size_t j) {
      const auto* pa = findBlock(a.blocks[i], name);
      const auto* pb = findBlock(b.blocks[j], name);
      if (!pa || !pb) return;
      e.time.push_back(t(a.blocks[i]));
      e.position.push_back(std::hypot(pa->pose.position.x - pb->pose.position.x,
                                      pa->pose.position.y - pb->pose.position.y));
      e.angle.push_back(std::abs(std::remainder(
          conversions::yaw(pa->pose.orientation) - conversions::yaw(pb->pose.orientation),
          2 * M_PI)));
    });
    e.rms_position = rms(e.position);
    e.rms_angle = rms(e.angle);
    e.final_position = e.position.empty() ? 0 : e.position.back();
    e.final_angle = e.angle.empty() ? 0 : e.angle.back();
    e.first_contact_a = firstContact(a, name);
    e.first_contact_b = firstContact(b, name);
    out.blocks.push_back(std::move(e));
  }
  auto tc = [](const Cloud& c) { return c.time; };
  forMatched(a.clouds, b.clouds, tc, tc, [&](std::size_t i, std::size_t j) {
    out.clouds.time.push_back(a.clouds[i].time);
    out.clouds.distance.push_back(meanNearestDistance(a.clouds[i].xy, b.clouds[j].xy));
    out.clouds.iou.push_back(occupancyIoU(a.clouds[i].xy, b.clouds[j].xy, raster));
    const std::vector<float>&sa = a.clouds[i].sph_xy, &sb = b.clouds[j].sph_xy;
    out.clouds.sph_count_a.push_back(sa.size() / 2);
    out.clouds.sph_count_b.push_back(sb.size() / 2);
    out.clouds.sph_distance.push_back(sa.empty() || sb.empty() ? -1 : meanNearestDistance(sa, sb));
  });
  forMatched(a.fem_nodes, b.fem_nodes, tc, tc, [&](std::size_t i, std::size_t j) {
    const std::vector<float>&pa = a.fem_nodes[i].xy, &pb = b.fem_nodes[j].xy;
    if (pa.size() != pb.size()) return;  // different meshes: nothing to match
    double sum = 0, largest = 0;
    for (std::size_t k = 0; k + 1 < pa.size(); k += 2) {
      const double d = std::hypot(pa[k] - pb[k], pa[k + 1] - pb[k + 1]);
      sum += d * d;
      largest = std::max(largest, d);
    }
    out.fem.time.push_back(a.fem_nodes[i].time);
    out.fem.rms.push_back(pa.empty() ? 0 : std::sqrt(sum / (pa.size() / 2)));
    out.fem.largest.push_back(largest);
  });
  auto te = [](const EnergySample& s) { return s.time; };
  double scale = 0;
  for (const auto& s : a.energy) scale = std::max(scale, std::abs(s.total));
  std::vector<double> rel;
  forMatched(a.energy, b.energy, te, te, [&](std::size_t i, std::size_t j) {
    out.energy.time.push_back(a.energy[i].time);
    out.energy.total_a.push_back(a.energy[i].total);
    out.energy.total_b.push_back(b.energy[j].total);
    rel.push_back(scale > 0 ? (a.energy[i].total - b.energy[j].total) / scale : 0);
  });
  out.energy.rms_relative = rms(rel);
  out.energy.final_relative = rel.empty() ? 0 : std::abs(rel.back());
  return out;
}

}  // namespace mpm_sdem::compare
