#include "clothref/record/record.h"

#include <chrono>

#include <fmt/format.h>

#include "clothref/record/world_views.h"
#include "clothref/scene/make_world.h"
#include "clothref/trace/build_info.h"
#include "clothref/trace/format.h"

namespace clothref {

nlohmann::ordered_json traceHeader(const Scene& scene, const TraceSettings& settings) {
  nlohmann::ordered_json header;
  header["format"] = kTraceFormat;
  header["version"] = kTraceVersion;
  header["scene"] = sceneToJson(scene);
  header["integrator"] = methodName(settings.method);
  header["precision"] = precisionName(settings.precision);
  header["dt"] = settings.dt;
  header["steps"] = settings.steps;
  header["stride"] = settings.stride;
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  if (scene.cloth) bodies.push_back({{"name", "cloth"}, {"particles", clothParticleCount(scene)}});
  if (scene.spheres)
    bodies.push_back({{"name", "spheres"}, {"particles", scene.spheres->items.size()}});
  header["bodies"] = bodies;
  header["hash"] = kTraceHashDescription;
  header["build"] = {{"clothref", build_info::kVersion},
                     {"compiler", build_info::kCompiler},
                     {"build_type", build_info::kBuildType},
                     {"system", build_info::kSystem},
                     {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                                           EIGEN_MINOR_VERSION)}};
  return header;
}

namespace {

template <typename T>
TraceSummary run(const Scene& scene, const TraceSettings& settings, std::ostream& out,
                 int threads) {
  const auto start = std::chrono::steady_clock::now();
  World<T> world = makeWorld<T>(scene, settings.method, settings.dt);
  setExecution(world, world.execution.use_fast, world.execution.simd, threads);
  out << traceHeader(scene, settings).dump() << '\n';
  TraceSummary summary;
  std::string line;
  for (std::int64_t s = 0;; ++s) {
    if (isRecorded(s, settings.steps, settings.stride)) {
      line.clear();
      appendStepLine(line, world);
      out.write(line.data(), static_cast<std::streamsize>(line.size()));
      ++summary.recorded;
      if (summary.first_nonfinite_step < 0 && !isFinite(world)) summary.first_nonfinite_step = s;
    }
    if (s == settings.steps) break;
    step(world);
  }
  summary.steps = world.step;
  summary.simulated_time = double(world.step) * double(world.physics.dt);
  summary.kinetic_energy = kineticEnergy(world);
  summary.momentum = momentum(world);
  summary.finite = isFinite(world);
  summary.final_hash = stateHash(world);
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace

TraceSummary writeTrace(const Scene& scene, const TraceSettings& settings, std::ostream& out,
                        int threads) {
  return withPrecision(settings.precision,
                       [&]<typename T>() { return run<T>(scene, settings, out, threads); });
}

}  // namespace clothref
