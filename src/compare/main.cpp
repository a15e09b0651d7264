// mpm_sdem_compare: the differences between two recorded runs (bags written by the node or by
// mpm_sdem_run --bag). Prints a table, writes a CSV of the time series and a PNG plot.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "compare.hpp"
#include "plot.hpp"

using namespace mpm_sdem::compare;

namespace {

const char* kUsage =
    "usage: mpm_sdem_compare A.bag B.bag [--out PREFIX] [--raster M]\n"
    "  --out PREFIX  write PREFIX.csv and PREFIX.png (default: A_vs_B in the current directory)\n"
    "  --raster M    cell size of the occupancy IoU raster, m (default 0.005)\n"
    "B is read at A's sample times, so runs whose steps differ compare: block states and\n"
    "energies are interpolated in B's time, particle and FEM snapshots paired with B's\n"
    "nearest within half a recording period. The table says how many of A's samples paired\n"
    "and warns of each kind where fewer than 90% did.\n"
    "exit status: 0 compared, 1 unreadable bag or output, 2 bad command line\n";

void writeCsv(const Comparison& c, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(10);
  f << "time,quantity,block,value_a,value_b,error\n";
  for (const BlockError& b : c.blocks) {
    for (std::size_t k = 0; k < b.time.size(); ++k) {
      f << b.time[k] << ",position_error_m," << b.name << ",,," << b.position[k] << "\n";
      f << b.time[k] << ",angle_error_rad," << b.name << ",,," << b.angle[k] << "\n";
    }
  }
  for (std::size_t k = 0; k < c.clouds.time.size(); ++k) {
    f << c.clouds.time[k] << ",cloud_mean_nn_distance_m,,,," << c.clouds.distance[k] << "\n";
    f << c.clouds.time[k] << ",cloud_occupancy_iou,,,," << c.clouds.iou[k] << "\n";
    if (c.clouds.sph_count_a[k] + c.clouds.sph_count_b[k] == 0) continue;
    f << c.clouds.time[k] << ",sph_particles,," << c.clouds.sph_count_a[k] << ","
      << c.clouds.sph_count_b[k] << "," << c.clouds.sph_count_a[k] - c.clouds.sph_count_b[k]
      << "\n";
    f << c.clouds.time[k] << ",sph_mean_nn_distance_m,,,," << c.clouds.sph_distance[k] << "\n";
  }
  for (std::size_t k = 0; k < c.fem.time.size(); ++k) {
    f << c.fem.time[k] << ",fem_node_rms_distance_m,,,," << c.fem.rms[k] << "\n";
    f << c.fem.time[k] << ",fem_node_largest_distance_m,,,," << c.fem.largest[k] << "\n";
  }
  for (std::size_t k = 0; k < c.energy.time.size(); ++k) {
    f << c.energy.time[k] << ",total_energy_J_per_m,," << c.energy.total_a[k] << ","
      << c.energy.total_b[k] << "," << c.energy.total_a[k] - c.energy.total_b[k] << "\n";
  }
}

// How many of a's samples each kind paired, then a warning for each kind that paired too few.
void printPairing(const Comparison& c) {
  std::size_t states = 0, states_of = 0;
  for (const BlockError& b : c.blocks) states += b.paired.paired, states_of += b.paired.of;
  std::printf("paired with b: block states %zu of %zu, particle clouds %zu of %zu", states,
              states_of, c.clouds.paired.paired, c.clouds.paired.of);
  if (c.fem.paired.of) std::printf(", FEM nodes %zu of %zu", c.fem.paired.paired, c.fem.paired.of);
  std::printf(", energies %zu of %zu (snapshots at most %.3g s apart)\n", c.energy.paired.paired,
              c.energy.paired.of,
              std::max(c.clouds.paired.largest_offset, c.fem.paired.largest_offset));
  for (const std::string& few : fewPaired(c)) {
    std::printf("WARNING: %s; its errors rest on those alone\n", few.c_str());
    std::fprintf(stderr, "mpm_sdem_compare: warning: %s (fewer than %.0f%%)\n", few.c_str(),
                 100 * kEnoughPaired);
  }
}

void printTable(const Comparison& c) {
  printPairing(c);
  std::printf("%-12s %12s %12s %12s %12s %10s %10s\n", "block", "rms pos (m)", "final pos (m)",
              "rms ang (rad)", "final ang", "contact a", "contact b");
  for (const BlockError& b : c.blocks) {
    std::printf("%-12s %12.4g %12.4g %12.4g %12.4g %10.4g %10.4g\n", b.name.c_str(), b.rms_position,
                b.final_position, b.rms_angle, b.final_angle, b.first_contact_a, b.first_contact_b);
  }
  // Blocks one run recorded and the other never did (spawned in one only, or renamed): named,
  // since they are not compared.
  for (const auto& [side, names] : {std::pair{"a", &c.only_a}, std::pair{"b", &c.only_b}}) {
    if (names->empty()) continue;
    std::printf("only in %s, not compared:", side);
    for (const std::string& n : *names) std::printf(" %s", n.c_str());
    std::printf("\n");
  }
  double dmax = 0, dmean = 0, iou_min = 1;
  for (std::size_t k = 0; k < c.clouds.time.size(); ++k) {
    dmax = std::max(dmax, c.clouds.distance[k]);
    dmean += c.clouds.distance[k] / c.clouds.time.size();
    iou_min = std::min(iou_min, c.clouds.iou[k]);
  }
  std::printf(
      "particle clouds: %zu paired, mean nearest-neighbour distance %.4g m (largest "
      "%.4g m), smallest occupancy IoU %.4f (%g m cells)\n",
      c.clouds.time.size(), dmean, dmax, iou_min, c.raster);
  double sph_largest = -1;
  for (double d : c.clouds.sph_distance) sph_largest = std::max(sph_largest, d);
  if (sph_largest >= 0)
    std::printf(
        "SPH particles: last sample %.0f and %.0f, largest mean nearest-neighbour "
        "distance %.4g m\n",
        c.clouds.sph_count_a.back(), c.clouds.sph_count_b.back(), sph_largest);
  if (!c.fem.time.empty()) {
    double largest = 0;
    for (double d : c.fem.largest) largest = std::max(largest, d);
    std::printf("FEM nodes: %zu paired, final RMS distance %.4g m, largest %.4g m\n",
                c.fem.time.size(), c.fem.rms.back(), largest);
  }
  std::printf("total energy: %zu paired, RMS difference %.4g and final %.4g of max |E_a|\n",
              c.energy.time.size(), c.energy.rms_relative, c.energy.final_relative);
  std::printf("(first contact: first time a material point touches the block, s; -1: never)\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> bags;
  std::string prefix;
  double raster = 0.005;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if ((a == "--out" || a == "--raster") && i + 1 < argc) {
      if (a == "--out") {
        prefix = argv[++i];
      } else {
        char* end = nullptr;
        raster = std::strtod(argv[++i], &end);
        if (*end != '\0' || !(raster > 0)) {
          std::cerr << "mpm_sdem_compare: --raster takes a length > 0 m\n" << kUsage;
          return 2;
        }
      }
    } else if (!a.empty() && a[0] == '-') {
      std::cerr << "mpm_sdem_compare: unknown option or missing value '" << a << "'\n" << kUsage;
      return 2;
    } else {
      bags.push_back(a);
    }
  }
  if (bags.size() != 2) {
    std::cerr << "mpm_sdem_compare: give two bags\n" << kUsage;
    return 2;
  }
  namespace fs = std::filesystem;
  if (prefix.empty())
    prefix = fs::path(bags[0]).stem().string() + "_vs_" + fs::path(bags[1]).stem().string();
  try {
    const RunSeries a = readRun(bags[0]), b = readRun(bags[1]);
    const Comparison c = compareRuns(a, b, raster);
    std::printf("a: %s\nb: %s\n", bags[0].c_str(), bags[1].c_str());
    printTable(c);
    writeCsv(c, prefix + ".csv");
    plotComparison(c, fs::path(bags[0]).filename().string(), fs::path(bags[1]).filename().string(),
                   prefix + ".png");
    std::printf("wrote %s.csv and %s.png\n", prefix.c_str(), prefix.c_str());
  } catch (const std::exception& e) {
    std::cerr << "mpm_sdem_compare: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
