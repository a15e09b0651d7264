// Issue 20's wheel rig (config/scenes/wheel.yaml, cases::runWheel) at CI resolution: the
// trends terramechanics measures (Bekker 1969; Wong and Reece 1967) and Coulomb's bound. The
// slip and load sweep at two resolutions is the validation case `wheel`.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cases.hpp"
#include "helpers.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

namespace {

cases::WheelRun wheel(Real slip, Real load) {
  Scene scene = loadScene(test::sourcePath("config/scenes/wheel.yaml"));
  cases::setWheelRig(scene.world, slip, load);
  World w(scene.world);
  const cases::WheelRun r = cases::runWheel(w, 1.0);
  std::printf("slip %.1f, W %.0f N/m: DP/W %.3f (sd %.3f), T/(W R) %.3f, sinkage %.2f mm\n", slip,
              load, r.pull / load, r.pull_spread / load, r.torque / (load * r.radius),
              1e3 * r.sinkage);
  return r;
}

}  // namespace

TEST(Wheel, PullRisesWithSlipSinkageWithLoadWithinCoulombsBound) {
  const Real tan_phi = std::tan(
      loadScene(test::sourcePath("config/scenes/wheel.yaml")).world.materials[0].friction_angle);
  // The three runs at once (test/parallel_runs.hpp).
  const std::vector<cases::WheelRun> runs = test::runAll<cases::WheelRun>(3, [](int i) {
    return i == 0 ? wheel(0.1, 200) : i == 1 ? wheel(0.7, 200) : wheel(0.1, 400);
  });
  const cases::WheelRun &low = runs[0], &high = runs[1], &heavy = runs[2];
  // Pull rises with slip: by far more than the pull's own fluctuation over the window.
  EXPECT_GT(high.pull - low.pull, 5 * std::max(low.pull_spread, high.pull_spread));
  // Slip sinkage: the wheel digs in as it spins.
  EXPECT_GT(high.sinkage, low.sinkage);
  // Sinkage rises with load: Bekker's z ~ W^(2 / (2n + 1)) with his sand exponents n <= 1.5
  // gives at least 2^0.5 for twice the load.
  EXPECT_GT(heavy.sinkage, std::sqrt(2.0) * low.sinkage);
  // Motion resistance rises with sinkage: the heavier wheel pulls less per unit of load.
  EXPECT_LT(heavy.pull / 400, low.pull / 200);
  // Neither the gross thrust nor the pull can exceed W tan(phi) in a cohesionless soil.
  for (const auto& [r, load] : {std::pair{low, 200.0}, {high, 200.0}, {heavy, 400.0}}) {
    EXPECT_LT(r.torque / (load * r.radius), tan_phi);
    EXPECT_LT(r.pull / load, tan_phi);
  }
}
