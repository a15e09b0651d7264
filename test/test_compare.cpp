// mpm_sdem_compare: its metrics on point sets with known answers, and on recorded runs: a run
// against itself differs by exactly nothing, a run with a perturbed parameter by something.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "bag_series.hpp"
#include "compare.hpp"

namespace fs = std::filesystem;
using namespace mpm_sdem::compare;

namespace {

// A square lattice of n x n points with spacing s, shifted by (dx, dy).
std::vector<float> lattice(int n, float s, float dx, float dy) {
  std::vector<float> xy;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      xy.push_back(i * s + dx);
      xy.push_back(j * s + dy);
    }
  }
  return xy;
}

// Runs the runner on a scene of test/data with extra arguments, recording a bag; its path.
std::string record(const std::string& name, const std::string& extra,
                   const std::string& scene = "node_bed.yaml --set time.end=0.2") {
  const fs::path dir = fs::temp_directory_path() / "mpm_sdem_test_compare";
  fs::create_directories(dir);
  const std::string bag = (dir / (name + ".bag")).string();
  const std::string cmd = std::string(MPM_SDEM_RUNNER) + " " + MPM_SDEM_SOURCE_DIR + "/test/data/" +
                          scene + " --threads 1 --quiet --out " + (dir / name).string() +
                          " --bag " + bag + " --bag-cloud-rate 30 " + extra + " 2>/dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return bag;
}

}  // namespace

TEST(CompareMetrics, ShiftedLatticeIsAsFarAsTheShift) {
  // Spacing 5 mm, shift 1 mm: every point's nearest neighbour in the other set is its own
  // shifted copy, 1 mm away (the next candidate is 4 mm away).
  const auto a = lattice(40, 0.005f, 0, 0), b = lattice(40, 0.005f, 0.001f, 0);
  EXPECT_NEAR(meanNearestDistance(a, a), 0.0, 1e-9);
  EXPECT_NEAR(meanNearestDistance(a, b), 0.001, 1e-6);
  // Occupancy: identical sets share every cell; sets 1 m apart share none.
  EXPECT_DOUBLE_EQ(occupancyIoU(a, a, 0.005), 1.0);
  EXPECT_DOUBLE_EQ(occupancyIoU(a, lattice(40, 0.005f, 1.0f, 0), 0.005), 0.0);
}

TEST(CompareRuns, SelfIsZeroPerturbedIsNot) {
  const RunSeries a = readRun(record("base", ""));
  const RunSeries b = readRun(record("steeper", "--set materials.sand.friction_angle=25"));
  const Comparison self = compareRuns(a, a, 0.005);
  ASSERT_EQ(self.blocks.size(), 2u);  // post and box
  for (const BlockError& e : self.blocks) {
    EXPECT_EQ(e.rms_position, 0.0) << e.name;
    EXPECT_EQ(e.rms_angle, 0.0) << e.name;
    EXPECT_EQ(e.first_contact_a, e.first_contact_b);
  }
  ASSERT_EQ(self.clouds.time.size(), 7u);  // 0 to 0.2 s at 30 Hz
  for (double d : self.clouds.distance) EXPECT_EQ(d, 0.0);
  for (double iou : self.clouds.iou) EXPECT_EQ(iou, 1.0);
  EXPECT_EQ(self.energy.rms_relative, 0.0);

  // A different friction angle changes how the bed settles under the box.
  const Comparison diff = compareRuns(a, b, 0.005);
  ASSERT_EQ(diff.blocks.size(), 2u);
  EXPECT_EQ(diff.blocks[0].rms_position, 0.0) << "the static post does not move";
  EXPECT_GT(diff.blocks[1].rms_position, 1e-6) << "the box on the bed does";
  EXPECT_GT(diff.clouds.distance.back(), 1e-7);
  EXPECT_GT(diff.energy.rms_relative, 1e-6);
  std::printf(
      "perturbed run: box RMS position error %.3g m, final cloud distance %.3g m, energy "
      "RMS %.3g\n",
      diff.blocks[1].rms_position, diff.clouds.distance.back(), diff.energy.rms_relative);

  // The command-line tool writes its table, CSV and plot.
  const fs::path out = fs::temp_directory_path() / "mpm_sdem_test_compare" / "cmp";
  const std::string cmd = std::string(MPM_SDEM_COMPARE) + " " + a.path + " " + b.path + " --out " +
                          out.string() + " >/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_GT(fs::file_size(out.string() + ".csv"), 100u);
  EXPECT_GT(fs::file_size(out.string() + ".png"), 1000u);
  fs::remove_all(fs::temp_directory_path() / "mpm_sdem_test_compare");
}

// Runs whose steps differ stamp their samples at different times (each at the first step on or
// after its due time): a denser sand (its contact springs' step is longer: 3.09e-4 against
// 2.78e-4 s) and a halved CFL number (2.08e-4 s, set by the CFL term). Pairing by equal stamps
// paired 2 of a's 7 snapshots with either (the start and one more). Every sample of a now pairs;
// the halved step moves the box by less than 1 mm (issue 77's bound on a position when the step
// halves) and the energy by less than 1% of its largest value; a run that stops at half the time
// pairs about half of a's samples and is named by fewPaired, and the tool's table warns.
TEST(CompareRuns, PairsRunsWhoseStepsDiffer) {
  const RunSeries a = readRun(record("steps_base", ""));
  const RunSeries half = readRun(record("steps_half_cfl", "--set time.cfl=0.15"));
  const RunSeries dense = readRun(record("steps_dense", "--set materials.sand.density=1600"));
  for (const RunSeries* b : {&half, &dense}) {
    SCOPED_TRACE(b->path);
    // The stamps differ, so pairing by equal times would miss most samples.
    std::size_t same = 0;
    for (std::size_t k = 1; k < std::min(a.clouds.size(), b->clouds.size()); ++k)
      same += std::abs(a.clouds[k].time - b->clouds[k].time) <= 1e-6;
    EXPECT_LT(same, a.clouds.size() / 2);
    std::printf("%zu of %zu snapshots at the same time\n", same + 1, a.clouds.size());
    const Comparison c = compareRuns(a, *b, 0.005);
    EXPECT_TRUE(fewPaired(c).empty());
    ASSERT_EQ(c.blocks.size(), 2u);
    for (const BlockError& e : c.blocks) EXPECT_EQ(e.paired.paired, e.paired.of) << e.name;
    EXPECT_EQ(c.clouds.paired.paired, a.clouds.size());
    EXPECT_EQ(c.energy.paired.paired, a.energy.size());
    // Snapshots pair within half the 1/30 s recording period.
    EXPECT_LE(c.clouds.paired.largest_offset, 0.5 / 30 + 1e-6);
  }
  const Comparison c = compareRuns(a, half, 0.005);
  EXPECT_LT(c.blocks[1].final_position, 1e-3) << "the box, when the step halves";
  EXPECT_LT(c.energy.final_relative, 0.01);
  std::printf(
      "halved step: box final position difference %.3g m, energy %.3g; denser sand: %.3g m\n",
      c.blocks[1].final_position, c.energy.final_relative,
      compareRuns(a, dense, 0.005).blocks[1].final_position);

  const RunSeries short_run =
      readRun(record("steps_short", "", "node_bed.yaml --set time.end=0.1"));
  const Comparison cut = compareRuns(a, short_run, 0.005);
  EXPECT_NEAR(cut.clouds.paired.fraction(), 0.5, 0.1);
  const std::vector<std::string> few = fewPaired(cut);
  ASSERT_FALSE(few.empty());
  EXPECT_NE(few[0].find("of"), std::string::npos);
  // The tool says so in its table.
  const fs::path out = fs::temp_directory_path() / "mpm_sdem_test_compare" / "cut";
  const std::string cmd = std::string(MPM_SDEM_COMPARE) + " " + a.path + " " + short_run.path +
                          " --out " + out.string() + " 2>/dev/null | grep -q WARNING";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// Blocks spawned while running appear in the states from their spawn on: a block both runs
// spawned is compared wherever both recorded it, and one spawned in a single run is listed as
// present there only (before, only the blocks of each run's first state were compared).
TEST(CompareRuns, SpawnedBlocksAreComparedAndOneSidedOnesListed) {
  auto states = [](double t, std::vector<std::pair<std::string, double>> blocks) {
    mpm_sdem::BlockStates s;
    s.header.stamp.fromSec(t);
    for (const auto& [name, x] : blocks) {
      mpm_sdem::RigidBlockState b;
      b.name = name;
      b.pose.position.x = x;
      b.pose.orientation.w = 1;
      s.blocks.push_back(b);
    }
    return s;
  };
  RunSeries a, b;
  a.blocks = {states(0, {{"post", 0}}), states(0.1, {{"post", 0}, {"rock", 0.5}}),
              states(0.2, {{"post", 0}, {"rock", 0.6}, {"only_a", 1}})};
  b.blocks = {states(0, {{"post", 0}}), states(0.1, {{"post", 0}, {"rock", 0.5}}),
              states(0.2, {{"post", 0}, {"rock", 0.7}}), states(0.3, {{"post", 0}, {"only_b", 2}})};
  const Comparison c = compareRuns(a, b, 0.005);
  ASSERT_EQ(c.blocks.size(), 2u);
  EXPECT_EQ(c.blocks[1].name, "rock");
  ASSERT_EQ(c.blocks[1].time.size(), 2u);  // 0.1 and 0.2 s
  EXPECT_NEAR(c.blocks[1].final_position, 0.1, 1e-12);
  EXPECT_EQ(c.only_a, std::vector<std::string>{"only_a"});
  EXPECT_EQ(c.only_b, std::vector<std::string>{"only_b"});
}

// Runs with FEM bodies: their nodes are recorded (~fem_nodes) and compared node by node; a run
// against itself differs by nothing, a barrier twice as stiff by half of the sag under its
// own weight.
TEST(CompareRuns, FemNodesAreRecordedAndCompared) {
  const RunSeries a = readRun(record("fem_base", "", "valid_fem.yaml"));
  const RunSeries b =
      readRun(record("fem_stiff", "--set fem_bodies.barrier.youngs_modulus=2e6", "valid_fem.yaml"));
  ASSERT_FALSE(a.fem_nodes.empty());
  EXPECT_EQ(a.fem_nodes.size(), a.clouds.size());  // recorded with each particle cloud
  const Comparison self = compareRuns(a, a, 0.005);
  ASSERT_EQ(self.fem.time.size(), a.fem_nodes.size());
  EXPECT_EQ(self.fem.largest.back(), 0.0);
  const Comparison other = compareRuns(a, b, 0.005);
  EXPECT_GT(other.fem.largest.back(), 0.0);
}

// Runs with SPH particles (seed 001): the clouds carry each point's kind, and the SPH sets are
// counted and compared on their own; a run whose region is smaller has fewer SPH particles.
TEST(CompareRuns, SphParticlesAreRecordedAndCompared) {
  const std::string scene = "valid_sph.yaml --set time.end=0.1";
  const RunSeries a = readRun(record("sph_base", "", scene));
  const RunSeries b = readRun(record("sph_small", "--set sph.regions.0.max=[0.08,0.25]", scene));
  ASSERT_FALSE(a.clouds.empty());
  ASSERT_FALSE(a.clouds.back().sph_xy.empty());
  EXPECT_LT(b.clouds.back().sph_xy.size(), a.clouds.back().sph_xy.size());
  const Comparison self = compareRuns(a, a, 0.005);
  ASSERT_FALSE(self.clouds.sph_distance.empty());
  EXPECT_EQ(self.clouds.sph_distance.back(), 0.0);
  EXPECT_EQ(self.clouds.sph_count_a.back(), a.clouds.back().sph_xy.size() / 2);
  const Comparison other = compareRuns(a, b, 0.005);
  EXPECT_GT(other.clouds.sph_count_a.back(), other.clouds.sph_count_b.back());
}
