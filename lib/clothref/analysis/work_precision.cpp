#include "clothref/analysis/work_precision.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <optional>
#include <thread>
#include <utility>

#include "clothref/analysis/stability.h"
#include "clothref/io/error.h"
#include "clothref/trace/build_info.h"
#include "clothref/verify/analytic.h"

namespace clothref {

namespace {

// Positions of every particle, cloth then spheres, as one vector of 3N doubles.
template <typename T>
Eigen::VectorXd positions(const World<T>& world) {
  const int cloth = world.cloth ? world.cloth->particles.size() : 0;
  const int spheres = world.spheres ? world.spheres->particles.size() : 0;
  Eigen::VectorXd out(3 * (cloth + spheres));
  for (int i = 0; i < cloth; ++i)
    for (int k = 0; k < 3; ++k) out[3 * i + k] = double(world.cloth->particles.position(k, i));
  for (int i = 0; i < spheres; ++i)
    for (int k = 0; k < 3; ++k)
      out[3 * (cloth + i) + k] = double(world.spheres->particles.position(k, i));
  return out;
}

// Max over particles of the position error.
double maxParticleError(const Eigen::VectorXd& x, const Eigen::VectorXd& reference) {
  double worst = 0;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i)
    worst = std::max(worst, (x.segment<3>(3 * i) - reference.segment<3>(3 * i)).norm());
  return worst;
}

template <typename T>
bool withinBounds(const Particles<T>& p) {
  for (int i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(double(p.position(k, i))) <= 100) ||
          !(std::abs(double(p.velocity(k, i))) <= 100))
        return false;
  return true;
}

template <typename T>
bool withinBounds(const World<T>& world) {
  return (!world.cloth || withinBounds(world.cloth->particles)) &&
         (!world.spheres || withinBounds(world.spheres->particles));
}

int samples(const SweepSettings& settings) {
  return static_cast<int>(std::llround(settings.horizon / settings.sample_interval));
}

double threadCpuSeconds() {
  timespec now{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

struct RunOutcome {
  bool stable = true;
  double seconds = 0;  // wall
  double cpu_seconds = 0;
  double simulated = 0;  // s
  double error_final = 0;
  double error_rms = 0;
  std::optional<double> cg_iterations;
};

// One run of `method`, or of the odeint peer when `peer` is given (the world's method is then
// not used: the peer steps it).
template <typename T>
RunOutcome runOnce(const Scene& scene, Method method, std::optional<PeerStepper> peer, double dt,
                   int substeps, const SweepSettings& settings, const SweepReference* reference) {
  World<T> simulation = makeWorld<T>(scene, method, dt);
  std::optional<OdeintPeer<T>> odeint;
  if (peer) odeint.emplace(simulation, *peer);
  const int count = samples(settings);
  RunOutcome outcome;
  double sum_squares = 0;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  std::int64_t steps = 0;
  for (int m = 1; m <= count && outcome.stable; ++m) {
    for (int s = 0; s < substeps; ++s) {
      if (odeint)
        odeint->step();
      else
        step(simulation);
      ++steps;
    }
    if (!withinBounds(simulation)) {
      outcome.stable = false;
      break;
    }
    if (reference) {
      const double error = maxParticleError(positions(simulation), reference->positions[m - 1]);
      sum_squares += error * error;
      if (m == count) outcome.error_final = error;
    }
  }
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.cpu_seconds = threadCpuSeconds() - cpu_start;
  outcome.simulated = double(steps) * dt;
  outcome.error_rms = std::sqrt(sum_squares / count);
  if (const BackwardEulerSolver<T>* solver = backwardEulerSolver(simulation);
      solver && solver->stats.solves > 0)
    outcome.cg_iterations = solver->stats.meanIterations();
  return outcome;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string machineName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string optionalCsv(const std::optional<double>& value) {
  return value ? fmt::format("{}", *value) : std::string();
}

nlohmann::ordered_json optionalJson(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

SweepSettings defaultSweepSettings(const Scene& scene) {
  SweepSettings settings;
  if (isSpringScene(scene)) {
    settings.horizon = 1;
    settings.sample_interval = 0.1;
    settings.substeps = {1, 2, 5, 10, 20, 40, 80, 160, 320, 640, 1280, 2560, 5120, 10240};
  } else {
    settings.horizon = 1;
    settings.sample_interval = 0.01;
    settings.substeps = {1, 2, 4, 10, 20, 25, 32, 40, 50, 64, 80, 100, 160, 250};
    settings.backward_euler_substeps = {1, 2, 4, 10, 20, 40, 100};
    settings.reference_substeps = 1000;
  }
  return settings;
}

SweepReference sweepReference(const Scene& scene, const SweepSettings& settings) {
  SweepReference reference;
  const int count = samples(settings);
  if (isSpringScene(scene)) {
    const SpringProblem problem = springProblem(scene);
    const World<double> world = makeWorld<double>(scene, Method::Explicit);
    const Eigen::VectorXd initial = positions(world);
    for (int m = 1; m <= count; ++m) {
      Eigen::VectorXd x = initial;
      x.segment<3>(3 * problem.particle) =
          springState(problem, m * settings.sample_interval).position;
      reference.positions.push_back(x);
    }
    reference.description = scene.name + ": closed form of the damped oscillator";
    return reference;
  }
  const double dt = settings.sample_interval / settings.reference_substeps;
  World<double> simulation = makeWorld<double>(scene, Method::Rk4, dt);
  for (int m = 1; m <= count; ++m) {
    for (int s = 0; s < settings.reference_substeps; ++s) step(simulation);
    if (!withinBounds(simulation))
      throw InputError("scene '" + scene.name + "': the double RK4 reference is not stable");
    reference.positions.push_back(positions(simulation));
  }
  reference.description = fmt::format("{}: double RK4 at dt = {:g} s", scene.name, dt);
  return reference;
}

namespace {

// A point of `method`, stepped by the library or, when `peer` is given, by odeint.
SweepPoint measurePoint(const Scene& scene, Method method, std::optional<PeerStepper> peer,
                        Precision precision, int substeps, const SweepSettings& settings,
                        const SweepReference& reference) {
  SweepPoint point;
  point.scene = scene.name;
  point.method = std::string(peer ? peerStepperName(*peer) : methodName(method));
  point.precision = precision;
  point.dt = settings.sample_interval / substeps;
  point.steps = std::int64_t(samples(settings)) * substeps;
  point.evaluations = point.steps * methodInfo(method).evaluations;
  const auto run = [&](const SweepReference* ref) {
    return precision == Precision::Float
               ? runOnce<float>(scene, method, peer, point.dt, substeps, settings, ref)
               : runOnce<double>(scene, method, peer, point.dt, substeps, settings, ref);
  };
  const RunOutcome first = run(&reference);
  std::vector<double> times = {first.seconds / first.simulated};
  std::vector<double> cpu_times = {first.cpu_seconds / first.simulated};
  point.stable = first.stable;
  point.cg_iterations = first.cg_iterations;
  if (first.stable) {
    point.error_final = first.error_final;
    point.error_rms = first.error_rms;
    for (int r = 1; r < settings.repeats; ++r) {
      const RunOutcome again = run(nullptr);
      times.push_back(again.seconds / again.simulated);
      cpu_times.push_back(again.cpu_seconds / again.simulated);
    }
  }
  // on the spring scenes a run can grow without leaving the bounds within the horizon: judge it
  // by the stability criterion as well (clothref stability's)
  if (point.stable && isSpringScene(scene))
    point.stable = runIsStable(scene, method, precision, point.dt, stabilityCriterion(scene));
  point.runs = static_cast<int>(times.size());
  point.seconds_median = median(times);
  point.seconds_min = *std::min_element(times.begin(), times.end());
  point.seconds_max = *std::max_element(times.begin(), times.end());
  point.cpu_seconds_median = median(cpu_times);
  point.cpu_seconds_min = *std::min_element(cpu_times.begin(), cpu_times.end());
  point.cpu_seconds_max = *std::max_element(cpu_times.begin(), cpu_times.end());
  return point;
}

}  // namespace

SweepPoint sweepPoint(const Scene& scene, Method method, Precision precision, int substeps,
                      const SweepSettings& settings, const SweepReference& reference) {
  return measurePoint(scene, method, std::nullopt, precision, substeps, settings, reference);
}

SweepPoint sweepPeerPoint(const Scene& scene, PeerStepper stepper, Precision precision,
                          int substeps, const SweepSettings& settings,
                          const SweepReference& reference) {
  return measurePoint(scene, peerCounterpart(stepper), stepper, precision, substeps, settings,
                      reference);
}

SweepResult sweep(const std::vector<Scene>& scenes, const std::vector<Method>& methods,
                  const std::vector<Precision>& precisions,
                  const std::function<SweepSettings(const Scene&)>& settings_for,
                  const std::function<void(const std::string&)>& progress,
                  const std::vector<PeerStepper>& peers) {
  SweepResult result;
  for (const Scene& scene : scenes) {
    const SweepSettings settings = settings_for(scene);
    if (progress) progress(fmt::format("sweep: {}: computing the reference", scene.name));
    const SweepReference reference = sweepReference(scene, settings);
    result.references.push_back(reference.description);
    const auto ladder = [&settings](Method method) -> const std::vector<int>& {
      return method == Method::BackwardEuler && !settings.backward_euler_substeps.empty()
                 ? settings.backward_euler_substeps
                 : settings.substeps;
    };
    // the library's methods, then the peers (each on its counterpart's ladder)
    std::vector<std::pair<Method, std::optional<PeerStepper>>> runs;
    for (Method method : methods) runs.emplace_back(method, std::nullopt);
    for (PeerStepper peer : peers) runs.emplace_back(peerCounterpart(peer), peer);
    std::size_t total = 0, done = 0;
    for (const auto& [method, peer] : runs) total += precisions.size() * ladder(method).size();
    for (const auto& [method, peer] : runs) {
      for (Precision precision : precisions) {
        for (int substeps : ladder(method)) {
          const SweepPoint point =
              measurePoint(scene, method, peer, precision, substeps, settings, reference);
          result.points.push_back(point);
          ++done;
          if (progress)
            progress(fmt::format("sweep: {} [{}/{}] {} {} dt={:g}: {}, {:.3g} s per simulated s",
                                 scene.name, done, total, point.method, precisionName(precision),
                                 point.dt,
                                 point.stable ? fmt::format("error {:.3e} m", *point.error_final)
                                              : std::string("unstable"),
                                 point.seconds_median));
        }
      }
    }
  }
  return result;
}

std::string sweepToCsv(const SweepResult& result) {
  std::string out =
      "scene,method,precision,dt,steps,evaluations,stable,error_final,error_rms,"
      "seconds_median,seconds_min,seconds_max,cpu_seconds_median,cpu_seconds_min,"
      "cpu_seconds_max,runs,cg_iterations\n";
  for (const SweepPoint& p : result.points) {
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", p.scene, p.method,
                       precisionName(p.precision), p.dt, p.steps, p.evaluations,
                       p.stable ? "true" : "false", optionalCsv(p.error_final),
                       optionalCsv(p.error_rms), p.seconds_median, p.seconds_min, p.seconds_max,
                       p.cpu_seconds_median, p.cpu_seconds_min, p.cpu_seconds_max, p.runs,
                       optionalCsv(p.cg_iterations));
  }
  return out;
}

nlohmann::ordered_json sweepToJson(const SweepResult& result) {
  nlohmann::ordered_json root;
  root["format"] = "clothref-sweep";
  root["version"] = 1;
  root["machine"] =
      fmt::format("{} ({} hardware threads)", machineName(), std::thread::hardware_concurrency());
  root["compiler"] = build_info::kCompiler;
  root["build_type"] = build_info::kBuildType;
  root["norms"] = {
      {"error_final", "max over particles of |x - x_ref| at the horizon (m)"},
      {"error_rms", "RMS over the sample times of the max over particles of |x - x_ref| (m)"},
      {"seconds", "wall seconds per simulated second; median, min, max over the runs"},
      {"cpu_seconds", "the thread's CPU seconds per simulated second; median, min, max"}};
  root["references"] = result.references;
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const SweepPoint& p : result.points) {
    nlohmann::ordered_json item;
    item["scene"] = p.scene;
    item["method"] = p.method;
    item["precision"] = std::string(precisionName(p.precision));
    item["dt"] = p.dt;
    item["steps"] = p.steps;
    item["evaluations"] = p.evaluations;
    item["stable"] = p.stable;
    item["error_final"] = optionalJson(p.error_final);
    item["error_rms"] = optionalJson(p.error_rms);
    item["seconds_median"] = p.seconds_median;
    item["seconds_min"] = p.seconds_min;
    item["seconds_max"] = p.seconds_max;
    item["cpu_seconds_median"] = p.cpu_seconds_median;
    item["cpu_seconds_min"] = p.cpu_seconds_min;
    item["cpu_seconds_max"] = p.cpu_seconds_max;
    item["runs"] = p.runs;
    item["cg_iterations"] = optionalJson(p.cg_iterations);
    points.push_back(item);
  }
  root["points"] = points;
  return root;
}

}  // namespace clothref
