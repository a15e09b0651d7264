// libFuzzer target: arbitrary obstacle requests (every number of ~spawn_obstacle and a twist)
// against the block rules the node applies (blockProblem, World::placementProblem, twistProblem)
// and, when they are accepted, a small world that takes the block and steps. A finding is an
// accepted request that crashes (Box2D's float asserts: issue 16's density 1e300), leaves a
// non-finite state, or stops the clock.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/core/world.hpp"
#include "small_world.hpp"

using namespace mpm_sdem;

namespace {

// Any double, including NaN, infinities and denormals, or (half the time) a plausible one.
double number(FuzzedDataProvider& in, double lo, double hi) {
  if (in.ConsumeBool()) return in.ConsumeFloatingPoint<double>();
  return in.ConsumeFloatingPointInRange(lo, hi);
}

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "finding: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  BlockDef d;
  d.name = in.ConsumeBool() ? "rock" : in.ConsumeRandomLengthString(80);
  d.type = static_cast<BodyType>(in.ConsumeIntegralInRange(0, 2));
  const int n = in.ConsumeIntegralInRange(1, 9);
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * M_PI * k / n;
    const double r = number(in, 0.001, 0.05);
    d.core.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  d.rounding = number(in, 1e-4, 0.01);
  d.position = Vec2(number(in, 0, 0.2), number(in, 0.05, 0.2));
  d.angle = number(in, -7, 7);
  d.velocity = Vec2(number(in, -10, 10), number(in, -10, 10));
  d.angular_velocity = number(in, -100, 100);
  d.density = number(in, 0, 1e4);
  d.friction = number(in, 0, 1);
  d.restitution = number(in, 0, 1);
  const auto model = in.ConsumeBool() ? BlockContactModel::kPenalty : BlockContactModel::kBox2D;
  d.adhesion = in.ConsumeBool() ? number(in, 0, 100) : 0;
  const Vec2 twist(number(in, -10, 10), number(in, -10, 10));
  const double spin = number(in, -100, 100);

  if (!blockProblem(d, model).empty()) return 0;  // refused: the expected answer
  World world(smallWorld(model));
  if (!world.placementProblem(d, in.ConsumeBool()).empty()) return 0;
  const BlockId id = world.addBlock(d);
  for (int step = 0; step < 3; ++step) {
    const TimeStepChoice dt = world.chooseTimeStep();
    if (!(dt.dt >= limits::kMinTimeStep)) return 0;  // the node undoes such a spawn
    if (!world.step(dt.dt).finite) finding("an accepted block made the state non-finite");
    if (step == 0 && twistProblem(world.blocks()->def(0), twist, spin).empty())
      world.setBlockVelocity(id, twist, spin);
  }
  const BlockState& s = world.blocks()->state(0);
  if (!s.position.allFinite() || !std::isfinite(s.angle)) finding("a non-finite block pose");
  return 0;
}
