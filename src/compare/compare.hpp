// Differences between two recorded runs, at run a's sample times. Runs whose steps differ record
// their samples at different times (each at the first step on or after its due time), so b is
// read at a's times: block states and energies interpolated linearly between b's samples on
// either side, particle and FEM snapshots (which cannot be interpolated) paired with b's nearest
// within half a recording period. Each kind counts how many of a's samples found a partner.
#pragma once

#include <string>
#include <vector>

#include "bag_series.hpp"

namespace mpm_sdem::compare {

// Below this fraction of a's samples paired, a kind's errors rest on too few samples: the tool
// warns (a run that ends earlier, a block spawned later, a gap in a recording).
constexpr double kEnoughPaired = 0.9;

// How many of run a's samples of one kind were paired with run b.
struct Paired {
  std::size_t paired = 0, of = 0;
  double largest_offset = 0;  // s, |t_a - t_b| of the worst snapshot pair (0: interpolated kinds)
  double fraction() const { return of ? static_cast<double>(paired) / of : 1.0; }
};

struct BlockError {
  std::string name;
  std::vector<double> time, position, angle;  // |p_a - p_b| (m), |theta_a - theta_b| (rad)
  double rms_position = 0, final_position = 0, rms_angle = 0, final_angle = 0;
  double first_contact_a = -1, first_contact_b = -1;  // s; -1: never touched by material
  Paired paired;                                      // of a's states holding this block
};

struct CloudError {
  std::vector<double> time;
  std::vector<double> distance;  // symmetric mean nearest-neighbour distance (m)
  std::vector<double> iou;       // occupancy intersection over union on a raster
  // SPH particles (seed 001): how many each run has, and the distance between the two SPH
  // sets (as distance; -1 where either has none).
  std::vector<double> sph_count_a, sph_count_b, sph_distance;
  Paired paired;
};

// FEM bodies' nodes, matched node by node (the same scene meshes the same way).
struct FemError {
  std::vector<double> time;
  std::vector<double> rms, largest;  // of |x_a - x_b| over the nodes (m)
  Paired paired;
};

struct EnergyError {
  std::vector<double> time, total_a, total_b;
  double rms_relative = 0;    // RMS of (E_a - E_b) / max |E_a|
  double final_relative = 0;  // at the last paired time
  Paired paired;
};

struct Comparison {
  // Blocks present in both runs at some time, spawned ones included (compared where both
  // recorded them), in the order they first appear in a; and those present in one run only.
  std::vector<BlockError> blocks;
  std::vector<std::string> only_a, only_b;
  CloudError clouds;
  FemError fem;  // empty unless both runs recorded the same FEM nodes
  EnergyError energy;
  double raster = 0;  // m, cell of the occupancy raster
};

// raster: IoU cell size (m).
Comparison compareRuns(const RunSeries& a, const RunSeries& b, double raster);

// Symmetric mean nearest-neighbour distance between two point sets (x0, y0, x1, ...).
double meanNearestDistance(const std::vector<float>& a, const std::vector<float>& b);
// Intersection over union of the raster cells (size cell) the two point sets occupy.
double occupancyIoU(const std::vector<float>& a, const std::vector<float>& b, double cell);

// The kinds of which fewer than kEnoughPaired of a's samples were paired, each as
// "particle clouds: 2 of 31 paired"; empty when every kind pairs.
std::vector<std::string> fewPaired(const Comparison& c);

}  // namespace mpm_sdem::compare
