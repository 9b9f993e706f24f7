#include "clothref/trace/writer.h"

#include <chrono>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "clothref/trace/build_info.h"
#include "clothref/trace/hash.h"

namespace clothref {

bool isRecorded(std::int64_t step, std::int64_t steps, std::int64_t stride) {
  return step % stride == 0 || step == steps;
}

nlohmann::ordered_json traceHeader(const Scene& scene, const TraceSettings& settings) {
  nlohmann::ordered_json header;
  header["format"] = "clothref-trace";
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
  header["hash"] = "xxh3-64 of little-endian x,y,z of positions then velocities, per body";
  header["build"] = {{"clothref", build_info::kVersion},
                     {"compiler", build_info::kCompiler},
                     {"build_type", build_info::kBuildType},
                     {"system", build_info::kSystem},
                     {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                                           EIGEN_MINOR_VERSION)}};
  return header;
}

namespace {

// Shortest round-trip text in the value's own precision; non-finite values as quoted strings.
template <typename T>
void appendNumber(std::string& out, T value) {
  if (std::isfinite(value)) {
    fmt::format_to(std::back_inserter(out), "{}", value);
  } else if (std::isnan(value)) {
    out += "\"NaN\"";
  } else {
    out += value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  }
}

template <typename T>
void appendColumns(std::string& out, const Mat4X<T>& m) {
  out += '[';
  for (Eigen::Index i = 0; i < m.cols(); ++i) {
    if (i) out += ',';
    out += '[';
    appendNumber(out, m(0, i));
    out += ',';
    appendNumber(out, m(1, i));
    out += ',';
    appendNumber(out, m(2, i));
    out += ']';
  }
  out += ']';
}

template <typename T>
void appendBody(std::string& out, const char* name, const Particles<T>& p) {
  fmt::format_to(std::back_inserter(out), "\"{}\":{{\"position\":", name);
  appendColumns(out, p.position);
  out += ",\"velocity\":";
  appendColumns(out, p.velocity);
  out += '}';
}

template <typename T>
TraceSummary run(const Scene& scene, const TraceSettings& settings, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  World<T> world = makeWorld<T>(scene, settings.method, settings.dt);
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

template <typename T>
void appendStepLine(std::string& out, const World<T>& world) {
  const double t = double(world.step) * double(world.physics.dt);
  fmt::format_to(std::back_inserter(out), "{{\"step\":{},\"t\":{},\"hash\":\"{}\",\"bodies\":{{",
                 world.step, t, hashToHex(stateHash(world)));
  bool first = true;
  if (world.cloth) {
    appendBody(out, "cloth", world.cloth->particles);
    first = false;
  }
  if (world.spheres) {
    if (!first) out += ',';
    appendBody(out, "spheres", world.spheres->particles);
  }
  out += "}}\n";
}

TraceSummary writeTrace(const Scene& scene, const TraceSettings& settings, std::ostream& out) {
  return settings.precision == Precision::Float ? run<float>(scene, settings, out)
                                                : run<double>(scene, settings, out);
}

template void appendStepLine(std::string&, const World<float>&);
template void appendStepLine(std::string&, const World<double>&);

}  // namespace clothref
