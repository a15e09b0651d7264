// Differences between two recorded runs, sample by sample at the times both recorded.
#pragma once

#include <string>
#include <vector>

#include "bag_series.hpp"

namespace mpm_sdem::compare {

struct BlockError {
  std::string name;
  std::vector<double> time, position, angle;  // |p_a - p_b| (m), |theta_a - theta_b| (rad)
  double rms_position = 0, final_position = 0, rms_angle = 0, final_angle = 0;
  double first_contact_a = -1, first_contact_b = -1;  // s; -1: never touched by material
};

struct CloudError {
  std::vector<double> time;
  std::vector<double> distance;  // symmetric mean nearest-neighbour distance (m)
  std::vector<double> iou;       // occupancy intersection over union on a raster
  // SPH particles (seed 001): how many each run has, and the distance between the two SPH
  // sets (as distance; -1 where either has none).
  std::vector<double> sph_count_a, sph_count_b, sph_distance;
};

// FEM bodies' nodes, matched node by node (the same scene meshes the same way).
struct FemError {
  std::vector<double> time;
  std::vector<double> rms, largest;  // of |x_a - x_b| over the nodes (m)
};

struct EnergyError {
  std::vector<double> time, total_a, total_b;
  double rms_relative = 0;    // RMS of (E_a - E_b) / max |E_a|
  double final_relative = 0;  // at the last matched time
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

// raster: IoU cell size (m). Samples are matched when their times agree within 1e-6 s.
Comparison compareRuns(const RunSeries& a, const RunSeries& b, double raster);

// Symmetric mean nearest-neighbour distance between two point sets (x0, y0, x1, ...).
double meanNearestDistance(const std::vector<float>& a, const std::vector<float>& b);
// Intersection over union of the raster cells (size cell) the two point sets occupy.
double occupancyIoU(const std::vector<float>& a, const std::vector<float>& b, double cell);

}  // namespace mpm_sdem::compare
