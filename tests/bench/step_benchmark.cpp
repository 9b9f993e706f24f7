// Benchmarks of the step and its kernels on the course scene (course2022, float), the fast paths
// beside the course-form oracle in the same run so ratios are meaningful on a noisy machine:
//   Springs/<path>          the cloth's forces of one evaluation (external force, then springs),
//                           items = springs (ns per spring)
//   SpringsOracle           the course-form computeExternalForce and per-spring loop
//   Collide, CollideOracle  sphere-cloth contacts over states sampled through the 1 s run,
//                           items = sphere-particle pairs
//   Step/<method>, StepOracle/<method>
//   SpringsGrid/<path>/N    an N x N cloth, items = springs (cost per spring against N)
//   Threads/<threads>       a 200 x 200 cloth's spring forces
// Run with --benchmark_repetitions=N --benchmark_report_aggregates_only=true for medians.
#include <benchmark/benchmark.h>

#include <vector>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"

namespace clothref {
namespace {

Scene courseScene(int particles_per_edge = 25) {
  Scene scene = *findBuiltinScene("course2022");
  const int n = particles_per_edge;
  scene.cloth->grid->particles_per_edge = n;
  scene.cloth->fixed = {0, n - 1, n * (n - 1), n * n - 1};
  return scene;
}

// The course world after `steps` explicit steps, with the given execution.
World<float> courseWorld(bool use_fast, fast::SimdPath path, int steps = 3000, int n = 25,
                         int threads = 1) {
  World<float> world = makeWorld<float>(courseScene(n), Method::Explicit);
  for (int k = 0; k < steps; ++k) step(world);
  setExecution(world, use_fast, path, threads);
  return world;
}

void springs(benchmark::State& state, bool use_fast, fast::SimdPath path, int n, int threads) {
  World<float> world = courseWorld(use_fast, path, n == 25 ? 3000 : 0, n, threads);
  const Physics<float>& physics = world.physics;
  Particles<float>& p = world.cloth->particles;
  for (auto _ : state) {
    if (use_fast) {
      fast::evaluateGridCloth(
          world.execution.springs, p.position.data(), p.velocity.data(), p.acceleration.data(),
          p.mass.data(), p.inverse_mass.data(), physics.gravity.data(), physics.viscous_coef,
          world.cloth->spring_coef, world.cloth->damper_coef, path, world.execution.pool.get());
    } else {
      computeExternalForce(p, physics.gravity, physics.viscous_coef);
      computeSpringForce(*world.cloth);
    }
    benchmark::DoNotOptimize(p.acceleration.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(world.cloth->springs.size()));
  state.SetLabel(use_fast ? std::string(fast::simdPathName(path)) : "course-form oracle");
}

std::vector<World<float>> runSnapshots() {
  // states every 0.05 s through the 1 s run: the spheres fall, hit and rest on the cloth
  std::vector<World<float>> snapshots;
  World<float> world = makeWorld<float>(courseScene(), Method::Explicit);
  for (int k = 0; k <= 10000; ++k) {
    if (k % 500 == 0) snapshots.push_back(world);
    step(world);
  }
  return snapshots;
}

void collideOver(benchmark::State& state, bool use_fast) {
  std::vector<World<float>> snapshots = runSnapshots();
  std::vector<World<float>> work = snapshots;
  std::int64_t pairs = 0;
  for (auto _ : state) {
    state.PauseTiming();
    for (std::size_t s = 0; s < work.size(); ++s) {
      work[s].cloth->particles.position = snapshots[s].cloth->particles.position;
      work[s].cloth->particles.velocity = snapshots[s].cloth->particles.velocity;
      work[s].spheres->particles.position = snapshots[s].spheres->particles.position;
      work[s].spheres->particles.velocity = snapshots[s].spheres->particles.velocity;
    }
    state.ResumeTiming();
    for (World<float>& w : work) {
      const Physics<float>& physics = w.physics;
      if (use_fast) {
        Particles<float>& s = w.spheres->particles;
        Particles<float>& c = w.cloth->particles;
        fast::collideSpheresWithCloth<float>(
            {s.position.data(), s.velocity.data(), s.inverse_mass.data(), w.spheres->radius.data(),
             s.size(), c.position.data(), c.velocity.data(), c.inverse_mass.data(), c.size()},
            physics.restitution_cloth, physics.correction, w.execution.simd, w.execution.contacts);
      } else {
        collide(*w.spheres, *w.cloth, physics.restitution_cloth, physics.correction);
      }
      pairs += std::int64_t(w.spheres->size()) * w.cloth->particles.size();
    }
  }
  state.SetItemsProcessed(pairs);
}

void stepMethod(benchmark::State& state, Method method, bool use_fast) {
  World<float> world = makeWorld<float>(courseScene(), method);
  setExecution(world, use_fast, fast::defaultSimdPath(), 1);
  for (int k = 0; k < 100; ++k) step(world);
  for (auto _ : state) step(world);
  state.SetLabel(use_fast ? std::string(fast::simdPathName(world.execution.simd)) : "oracle");
}

void registerAll() {
  benchmark::RegisterBenchmark("SpringsOracle", springs, false, fast::SimdPath::Sse2, 25, 1);
  for (fast::SimdPath path : fast::kAllSimdPaths) {
    if (!fast::simdPathSupported(path)) continue;
    const std::string name(fast::simdPathName(path));
    benchmark::RegisterBenchmark(("Springs/" + name).c_str(), springs, true, path, 25, 1);
    for (int n : {25, 50, 100, 200})
      benchmark::RegisterBenchmark(("SpringsGrid/" + name + "/" + std::to_string(n)).c_str(),
                                   springs, true, path, n, 1);
  }
  for (int n : {25, 50, 100, 200})
    benchmark::RegisterBenchmark(("SpringsGridOracle/" + std::to_string(n)).c_str(), springs, false,
                                 fast::SimdPath::Sse2, n, 1);
  for (int threads : {1, 2})
    benchmark::RegisterBenchmark(("Threads/" + std::to_string(threads)).c_str(), springs, true,
                                 fast::defaultSimdPath(), 200, threads)
        ->UseRealTime();
  benchmark::RegisterBenchmark("Collide", collideOver, true);
  benchmark::RegisterBenchmark("CollideOracle", collideOver, false);
  for (Method method : kAllMethods) {
    const std::string name(methodName(method));
    benchmark::RegisterBenchmark(("Step/" + name).c_str(), stepMethod, method, true);
    benchmark::RegisterBenchmark(("StepOracle/" + name).c_str(), stepMethod, method, false);
  }
}

}  // namespace
}  // namespace clothref

int main(int argc, char** argv) {
  clothref::registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
