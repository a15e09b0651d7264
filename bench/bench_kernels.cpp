// Google Benchmark kernels: the P2G and G2P transfers and the constitutive update (linear
// elastic, Drucker-Prager, granular), per particle and across points in SIMD lanes, on the
// column scene (APIC, quadratic B-spline), the whole step per material, and the whole step with
// material points or SPH particles; writing and restoring a checkpoint. Counters report
// particles per second.
#include <benchmark/benchmark.h>

#include "bench_scenes.hpp"
#include "mpm/transfer.hpp"
#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/mesh/mesher.hpp"

using namespace mpm_sdem;

namespace {

World settledWorld(long n, MaterialModel model, bool volume_fit = false) {
  WorldDef def = bench::columnWorld(n, model);
  def.solver.volume_fit = volume_fit;
  World w(def);
  for (int s = 0; s < 20; ++s) stepStable(w);  // non-trivial stresses and B
  return w;
}

void BM_P2G(benchmark::State& state) {
  World w = settledWorld(state.range(0), MaterialModel::kLinearElastic);
  Grid g = w.grid();
  Tiles tiles;
  tiles.init(g);
  tiles.bin(w.particles(), g);
  for (auto _ : state) {
    detail::particleToGrid(KernelType::kQuadraticBSpline, {true, true, true}, w.particles(), g,
                           tiles);
    benchmark::DoNotOptimize(g.mass.data());
  }
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(w.particles().size()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}

void BM_G2P(benchmark::State& state) {
  World w = settledWorld(state.range(0), MaterialModel::kLinearElastic);
  Particles backup = w.particles();
  detail::G2PSettings s{0, 0.0, w.def().domain.min, w.def().domain.max};
  for (auto _ : state) {
    long clamped = 0;
    bool finite = true;
    detail::gridToParticle(KernelType::kQuadraticBSpline, TransferScheme::kApic, false,
                           w.particles(), w.grid(), s, clamped, finite);
    benchmark::DoNotOptimize(w.particles().vx.data());
  }
  state.counters["particles/s"] = benchmark::Counter(static_cast<double>(backup.size()),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}

// Arg 1: the material, 0 linear elastic, 1 Drucker-Prager, 2 granular (mu(I), issue 41).
MaterialModel benchModel(long index) {
  constexpr MaterialModel kModels[] = {MaterialModel::kLinearElastic, MaterialModel::kDruckerPrager,
                                       MaterialModel::kGranular};
  return kModels[index];
}

void BM_Constitutive(benchmark::State& state) {
  World w = settledWorld(state.range(0), benchModel(state.range(1)));
  const MaterialParams m = w.materialParams()[0];
  Particles& P = w.particles();
  const long n = static_cast<long>(P.size());
  for (auto _ : state) {
    for (long p = 0; p < n; ++p) {
      Stress s{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]};
      s = jaumannElasticUpdate(m, s, {P.lxx[p], P.lxy[p], P.lyx[p], P.lyy[p]}, 1e-6);
      if (m.model == MaterialModel::kDruckerPrager) druckerPragerReturn(m, s);
      if (m.model == MaterialModel::kGranular) granularReturn(m, s, P.J[p], 1e-6);
      P.sxx[p] = s.xx;
      P.syy[p] = s.yy;
      P.sxy[p] = s.xy;
      P.szz[p] = s.zz;
    }
    benchmark::DoNotOptimize(P.sxx.data());
  }
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

// The same update across points in SIMD lanes (issue 42, updateStressBatch; linear elastic and
// Drucker-Prager), 16 points at a time copied in and out as the stress sweep does; J is updated
// too.
void BM_ConstitutiveBatch(benchmark::State& state) {
  World w = settledWorld(state.range(0), benchModel(state.range(1)));
  Particles& P = w.particles();
  const int n = static_cast<int>(P.size());
  auto nothing = [](int, int) {};
  for (auto _ : state) {
    detail::StressBatcher batcher(P, w.materialParams(), 1e-6);
    for (int p = 0; p < n; ++p) {
      batcher.add(p, nothing);
      if (batcher.full()) batcher.flush(nothing);
    }
    batcher.flush(nothing);
    benchmark::DoNotOptimize(P.sxx.data());
  }
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}

// An FEM body's whole step (internal forces, trial velocities, the step itself; seed 002 sec.
// 2.3): a 1 x 0.05 m corotational beam meshed at element_size = 0.05 / arg, clamped at one end,
// no material. Counter: element-steps per second.
void BM_FemStep(benchmark::State& state) {
  WorldDef def;
  def.domain.min = Vec2(-0.5, -0.5);
  def.domain.max = Vec2(1.5, 0.5);
  def.cell_size = 0.1;
  FemBodyDef beam;
  beam.name = "beam";
  beam.mesh = meshPolygon({{0, -0.025}, {1, -0.025}, {1, 0.025}, {0, 0.025}},
                          0.05 / static_cast<Real>(state.range(0)));
  beam.youngs_modulus = 1e9;
  beam.held = {Box{Vec2(-1, -1), Vec2(1e-9, 1)}};
  def.fem_bodies = {beam};
  World w(def);
  const Real dt = w.chooseTimeStep().dt;
  for (auto _ : state) w.step(dt);
  state.counters["element-steps/s"] =
      benchmark::Counter(static_cast<double>(w.femBodies()->totalElements()),
                         benchmark::Counter::kIsIterationInvariantRate);
  state.counters["elements"] = w.femBodies()->totalElements();
}

// The whole step of the column scene (APIC, linear elastic), its points all material points
// (arg 1 = 0) or all SPH particles (seed 001, cubic spline, h_s one cell; arg 1 = 1), at the
// step each takes. Counter: particle-steps per second.
void BM_Step(benchmark::State& state) {
  WorldDef def = bench::columnWorld(state.range(0), MaterialModel::kLinearElastic);
  if (state.range(1)) def.sph.bodies = {0};
  World w(def);
  for (int s = 0; s < 5; ++s) stepStable(w);
  for (auto _ : state) stepStable(w);
  state.counters["particle-steps/s"] = benchmark::Counter(
      static_cast<double>(w.particles().size()), benchmark::Counter::kIsIterationInvariantRate);
}

// The whole step of the column scene (APIC) for each material (arg 1 as in BM_Constitutive):
// what the granular material costs against Drucker-Prager per particle-step (issue 41); arg 2:
// with volume-consistent points (SolverDef::volume_fit, issue 79: the collapsing column shears).
void BM_StepMaterial(benchmark::State& state) {
  World w = settledWorld(state.range(0), benchModel(state.range(1)), state.range(2));
  for (auto _ : state) stepStable(w);
  state.counters["particle-steps/s"] = benchmark::Counter(
      static_cast<double>(w.particles().size()), benchmark::Counter::kIsIterationInvariantRate);
}

// A checkpoint of the settled column: written (arg 1 = 0) or restored into a fresh world of the
// same scene (arg 1 = 1). Counters: particles per second and bytes per particle.
void BM_Checkpoint(benchmark::State& state) {
  World w = settledWorld(state.range(0), MaterialModel::kDruckerPrager);
  const std::string bytes = saveCheckpoint(w, "column");
  World fresh(w.def());
  for (auto _ : state) {
    if (state.range(1))
      restoreCheckpoint(fresh, bytes);
    else
      benchmark::DoNotOptimize(saveCheckpoint(w, "column"));
  }
  const double n = static_cast<double>(w.particles().size());
  state.counters["particles/s"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/particle"] = static_cast<double>(bytes.size()) / n;
}

}  // namespace

BENCHMARK(BM_Checkpoint)
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Step)
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepMaterial)
    ->Args({100000, 0, 0})
    ->Args({100000, 1, 0})
    ->Args({100000, 2, 0})
    ->Args({100000, 2, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FemStep)->Arg(4)->Arg(16)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_P2G)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_G2P)->Arg(10000)->Arg(100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Constitutive)
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ConstitutiveBatch)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
