// clothref bench: how fast a step and its kernels run on the course scene, the fast kernels beside
// the course-form oracle in the same run (so the ratio survives a noisy machine). Prints a table
// (median, min, max over repeated runs) or, with --json, the medians as one JSON object. Speed is
// measured here and in tests/bench (Google Benchmark), never asserted in tests. Allocations are
// counted only where a hook is scoped to the measurement (tests/core/world_test.cpp and the
// clothref_bench target): the shipped binary replaces no allocator.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "clothref/core/world.h"
#include "clothref/io/error.h"
#include "clothref/scene/make_world.h"
#include "commands.h"

namespace clothref::cli {

namespace {

// Single-thread figures use this thread's CPU time: the machine is shared, and time spent
// descheduled is not the kernel's. The thread sweep uses wall time (both threads must count).
struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using time_point = std::chrono::time_point<ThreadCpuClock, duration>;
  static time_point now() {
    timespec t{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return time_point(duration(std::int64_t(t.tv_sec) * 1000000000 + t.tv_nsec));
  }
};
using Clock = ThreadCpuClock;
using WallClock = std::chrono::steady_clock;

struct BenchOptions {
  std::string scene = "course2022";
  std::string simd;  // default: CLOTHREF_SIMD or the best path
  int threads = 1;
  int repetitions = 10;
  double seconds = 1;  // simulated seconds per method and for the contact samples
  bool json = false;
};

// Median, min and max of repeated measurements.
struct Spread {
  double median = 0, min = 0, max = 0;
};

Spread spread(std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  const double median = n % 2 ? samples[n / 2] : (samples[n / 2 - 1] + samples[n / 2]) / 2;
  return {median, samples.front(), samples.back()};
}

template <typename Duration>
double seconds(Duration d) {
  return std::chrono::duration<double>(d).count();
}

struct Figures {
  std::map<std::string, Spread> step_us;
  Spread spring_ns, collide_ns_per_pair;
  std::map<int, Spread> spring_ns_by_n;  // N x N cloth, one thread, wall time
};

inline constexpr int kGridSizes[] = {25, 50, 100, 200};

// Per-step times of `method`: the scene's run split into `repetitions` blocks of equal steps, each
// block one sample (so the samples cover the whole run: falling, contact, rest).
Spread stepMicroseconds(const Scene& scene, double duration, Method method, bool use_fast,
                        fast::SimdPath path, int threads, int repetitions) {
  World<float> world = makeWorld<float>(scene, method);
  setExecution(world, use_fast, path, threads);
  const std::int64_t total =
      std::max<std::int64_t>(std::llround(duration / world.physics.dt), repetitions);
  const std::int64_t block = total / repetitions;
  step(world);  // sizes the scratch buffers
  std::vector<double> samples;
  for (int r = 0; r < repetitions; ++r) {
    const Clock::time_point start = Clock::now();
    for (std::int64_t k = 0; k < block; ++k) step(world);
    samples.push_back(seconds(Clock::now() - start) / double(block) * 1e6);
  }
  return spread(samples);
}

// Worlds sampled every 0.05 s through the scene's first second, explicit Euler.
std::vector<World<float>> runSnapshots(const Scene& scene, double duration) {
  std::vector<World<float>> snapshots;
  World<float> world = makeWorld<float>(scene, Method::Explicit);
  const std::int64_t total = std::llround(duration / world.physics.dt);
  const std::int64_t every = std::max<std::int64_t>(total / 20, 1);
  for (std::int64_t k = 0; k <= total; ++k) {
    if (k % every == 0) snapshots.push_back(world);
    step(world);
  }
  return snapshots;
}

// Nanoseconds per spring of the cloth's forces (external force, then springs) in one evaluation,
// over the snapshots.
Spread springNanoseconds(const std::vector<World<float>>& snapshots, bool use_fast,
                         fast::SimdPath path, int threads, int repetitions) {
  std::vector<double> samples;
  std::vector<World<float>> work = snapshots;
  for (World<float>& w : work) setExecution(w, use_fast, path, threads);
  if (work.empty() || !work[0].cloth || work[0].cloth->springs.empty()) return {};
  const int calls = 20;
  for (int r = 0; r < repetitions; ++r) {
    Clock::duration elapsed{};
    std::int64_t springs = 0;
    for (World<float>& w : work) {
      Cloth<float>& cloth = *w.cloth;
      Particles<float>& p = cloth.particles;
      const Clock::time_point start = Clock::now();
      const Physics<float>& physics = w.physics;
      for (int c = 0; c < calls; ++c) {
        if (use_fast && w.execution.grid) {
          fast::evaluateGridCloth(w.execution.springs, p.position.data(), p.velocity.data(),
                                  p.acceleration.data(), p.mass.data(), p.inverse_mass.data(),
                                  physics.gravity.data(), physics.viscous_coef, cloth.spring_coef,
                                  cloth.damper_coef, path, w.execution.pool.get());
        } else {
          computeExternalForce(p, physics.gravity, physics.viscous_coef);
          computeSpringForce(cloth);
        }
      }
      elapsed += Clock::now() - start;
      springs += calls * std::int64_t(cloth.springs.size());
    }
    samples.push_back(seconds(elapsed) * 1e9 / double(springs));
  }
  return spread(samples);
}

// Nanoseconds per sphere-particle pair of one sphere-cloth collide, averaged over the snapshots
// (all restored before each repetition's timed pass), on `path` (not the snapshots' own path,
// which is the process default).
Spread collideNanoseconds(const std::vector<World<float>>& snapshots, bool use_fast,
                          fast::SimdPath path, int repetitions) {
  std::vector<double> samples;
  if (snapshots.empty() || !snapshots[0].cloth || !snapshots[0].spheres) return {};
  std::vector<World<float>> work = snapshots;
  for (int r = 0; r < repetitions; ++r) {
    for (std::size_t i = 0; i < work.size(); ++i) {
      work[i].spheres->particles.position = snapshots[i].spheres->particles.position;
      work[i].spheres->particles.velocity = snapshots[i].spheres->particles.velocity;
      work[i].cloth->particles.position = snapshots[i].cloth->particles.position;
      work[i].cloth->particles.velocity = snapshots[i].cloth->particles.velocity;
    }
    std::int64_t pairs = 0;
    const Clock::time_point start = Clock::now();
    for (World<float>& w : work) {
      Particles<float>& s = w.spheres->particles;
      Particles<float>& c = w.cloth->particles;
      const Physics<float>& physics = w.physics;
      if (use_fast)
        fast::collideSpheresWithCloth<float>(
            {s.position.data(), s.velocity.data(), s.inverse_mass.data(), w.spheres->radius.data(),
             s.size(), c.position.data(), c.velocity.data(), c.inverse_mass.data(), c.size()},
            physics.restitution_cloth, physics.correction, path, w.execution.contacts);
      else
        collide(*w.spheres, *w.cloth, physics.restitution_cloth, physics.correction);
      pairs += std::int64_t(s.size()) * c.size();
    }
    samples.push_back(seconds(Clock::now() - start) * 1e9 / double(pairs));
  }
  return spread(samples);
}

// Nanoseconds per spring of the cloth's forces on an N x N course cloth (the course scene with
// a bigger grid, at rest), with `threads` threads, in wall time.
Spread gridSpringNanoseconds(const Scene& course, int n, bool use_fast, fast::SimdPath path,
                             int threads, int repetitions) {
  Scene scene = course;
  if (!scene.cloth || !scene.cloth->grid) return {};
  scene.cloth->grid->particles_per_edge = n;
  scene.cloth->fixed = {0, n - 1, n * (n - 1), n * n - 1};
  World<float> w = makeWorld<float>(scene, Method::Explicit);
  setExecution(w, use_fast, path, threads);
  Cloth<float>& cloth = *w.cloth;
  Particles<float>& p = cloth.particles;
  const Physics<float>& physics = w.physics;
  const int calls = std::max(1, 200000 / int(cloth.springs.size()));
  std::vector<double> samples;
  for (int r = 0; r < repetitions; ++r) {
    const WallClock::time_point start = WallClock::now();
    for (int c = 0; c < calls; ++c) {
      if (use_fast && w.execution.grid) {
        fast::evaluateGridCloth(w.execution.springs, p.position.data(), p.velocity.data(),
                                p.acceleration.data(), p.mass.data(), p.inverse_mass.data(),
                                physics.gravity.data(), physics.viscous_coef, cloth.spring_coef,
                                cloth.damper_coef, path, w.execution.pool.get());
      } else {
        computeExternalForce(p, physics.gravity, physics.viscous_coef);
        computeSpringForce(cloth);
      }
    }
    samples.push_back(seconds(WallClock::now() - start) * 1e9 /
                      (double(calls) * double(cloth.springs.size())));
  }
  return spread(samples);
}

Figures measure(const Scene& scene, double duration, bool use_fast, fast::SimdPath path,
                int threads, int repetitions) {
  Figures figures;
  for (Method method : kAllMethods)
    figures.step_us[std::string(methodName(method))] =
        stepMicroseconds(scene, duration, method, use_fast, path, threads, repetitions);
  const std::vector<World<float>> snapshots = runSnapshots(scene, duration);
  figures.spring_ns = springNanoseconds(snapshots, use_fast, path, threads, repetitions);
  figures.collide_ns_per_pair = collideNanoseconds(snapshots, use_fast, path, repetitions);
  for (int n : kGridSizes)
    figures.spring_ns_by_n[n] = gridSpringNanoseconds(scene, n, use_fast, path, 1, repetitions);
  return figures;
}

nlohmann::ordered_json spreadJson(const Spread& s) {
  return {{"median", s.median}, {"min", s.min}, {"max", s.max}};
}

nlohmann::ordered_json figuresJson(const Figures& f) {
  nlohmann::ordered_json out;
  nlohmann::ordered_json steps = nlohmann::ordered_json::object();
  for (Method method : kAllMethods)
    steps[methodName(method)] = f.step_us.at(std::string(methodName(method))).median;
  out["step_us"] = steps;
  out["spring_ns"] = f.spring_ns.median;
  out["collide_ns_per_pair"] = f.collide_ns_per_pair.median;
  nlohmann::ordered_json spreads = nlohmann::ordered_json::object();
  for (Method method : kAllMethods)
    spreads["step_us"][methodName(method)] =
        spreadJson(f.step_us.at(std::string(methodName(method))));
  nlohmann::ordered_json by_n = nlohmann::ordered_json::object();
  for (int n : kGridSizes) by_n[std::to_string(n)] = f.spring_ns_by_n.at(n).median;
  out["spring_ns_by_n"] = by_n;
  spreads["spring_ns"] = spreadJson(f.spring_ns);
  spreads["collide_ns_per_pair"] = spreadJson(f.collide_ns_per_pair);
  out["spread"] = spreads;
  return out;
}

int runBench(const BenchOptions& options) {
  if (options.repetitions < 1)
    throw InputError(fmt::format("--repetitions: must be >= 1 (got {})", options.repetitions));
  if (!(options.seconds > 0 && options.seconds <= 1000))
    throw InputError(fmt::format("--seconds: must be in (0, 1000] (got {})", options.seconds));
  fast::SimdPath path = fast::defaultSimdPath();
  if (!options.simd.empty()) {
    if (!fast::parseSimdPath(options.simd, path))
      throw InputError("--simd: unknown path '" + options.simd + "' (sse2, avx2, avx512)");
    if (!fast::simdPathSupported(path))
      throw InputError("--simd: this CPU cannot run the " + options.simd + " path");
  }
  const Scene scene = loadScene(options.scene);
  const Figures fast_figures =
      measure(scene, options.seconds, true, path, options.threads, options.repetitions);
  const Figures oracle = measure(scene, options.seconds, false, path, 1, options.repetitions);
  // the thread sweep: a 200 x 200 cloth at one thread and at --threads (at least 2)
  const int sweep_threads = std::max(options.threads, 2);
  const Spread one_thread = gridSpringNanoseconds(scene, 200, true, path, 1, options.repetitions);
  const Spread more_threads =
      gridSpringNanoseconds(scene, 200, true, path, sweep_threads, options.repetitions);

  if (options.json) {
    nlohmann::ordered_json out = {{"scene", scene.name}, {"precision", "float"}};
    const nlohmann::ordered_json fast_json = figuresJson(fast_figures);
    for (auto it = fast_json.begin(); it != fast_json.end(); ++it) out[it.key()] = it.value();
    out["simd"] = fast::simdPathName(path);
    out["threads"] = options.threads;
    out["repetitions"] = options.repetitions;
    out["threads_n200"] = {{"threads", sweep_threads},
                           {"ns_per_spring_1", one_thread.median},
                           {"ns_per_spring", more_threads.median},
                           {"speedup", one_thread.median / more_threads.median}};
    out["oracle"] = figuresJson(oracle);
    std::cout << out.dump() << '\n';
    return kExitOk;
  }
  std::cout << fmt::format(
      "clothref bench: {} float, simd {}, threads {}, {} repetitions (median [min, max]; thread "
      "CPU time, N sweep wall time)\n",
      scene.name, fast::simdPathName(path), options.threads, options.repetitions);
  std::cout << fmt::format("{:<26} {:>28} {:>28} {:>8}\n", "figure", "fast", "course-form oracle",
                           "speed-up");
  auto row = [](const std::string& name, const Spread& f, const Spread& o) {
    std::cout << fmt::format(
        "{:<26} {:>9.3f} [{:>7.3f}, {:>7.3f}] {:>9.3f} [{:>7.3f}, {:>7.3f}] {:>7.2f}x\n", name,
        f.median, f.min, f.max, o.median, o.min, o.max, f.median > 0 ? o.median / f.median : 0.0);
  };
  for (Method method : kAllMethods) {
    const std::string name(methodName(method));
    row(name + " step (us)", fast_figures.step_us.at(name), oracle.step_us.at(name));
  }
  row("spring force (ns/spring)", fast_figures.spring_ns, oracle.spring_ns);
  row("collision (ns/pair)", fast_figures.collide_ns_per_pair, oracle.collide_ns_per_pair);
  for (int n : kGridSizes)
    row(fmt::format("N={} spring (ns/spring)", n), fast_figures.spring_ns_by_n.at(n),
        oracle.spring_ns_by_n.at(n));
  std::cout << fmt::format(
      "N=200 spring forces, {} threads against 1 (wall): {:.3f} ns/spring against {:.3f}, "
      "{:.2f}x\n",
      sweep_threads, more_threads.median, one_thread.median,
      one_thread.median / more_threads.median);
  return kExitOk;
}

}  // namespace

Command addBenchCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "bench", "Time the step and its kernels, fast paths beside the course-form oracle");
  auto options = std::make_shared<BenchOptions>();
  app->add_option("--scene", options->scene, "Built-in scene name or scene JSON file")
      ->capture_default_str();
  app->add_option("--simd", options->simd,
                  "sse2 | avx2 | avx512 (default: CLOTHREF_SIMD, else the widest this CPU runs)");
  app->add_option("--threads", options->threads,
                  "Spring sweep threads (used by cloths of 100 x 100 particles and more)")
      ->check(CLI::Range(1, 64))  // as trace: 2000 threads took 54 s and 16.4 GB
      ->capture_default_str();
  app->add_option("--repetitions", options->repetitions,
                  "Samples per figure (the 1 s run is split into this many blocks)")
      ->capture_default_str();
  app->add_option("--seconds", options->seconds,
                  "Simulated seconds per method, and sampled for the contact figure")
      ->capture_default_str();
  app->add_flag("--json", options->json, "Print the medians as one JSON object");
  return {app, [options] { return runBench(*options); }};
}

}  // namespace clothref::cli
