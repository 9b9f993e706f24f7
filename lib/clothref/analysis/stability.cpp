#include "clothref/analysis/stability.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "clothref/io/error.h"
#include "clothref/verify/analytic.h"

namespace clothref {

namespace {

using Complex = std::complex<double>;

// A mode's two eigenvalues.
std::array<Complex, 2> modeEigenvalues(const Mode& mode) {
  const Complex root = std::sqrt(Complex(mode.delta * mode.delta - 4 * mode.kappa, 0));
  return {(-mode.delta + root) / 2.0, (-mode.delta - root) / 2.0};
}

// Radius above this counts as growth: well above the round-off of the formulas (1e-16) and
// below the smallest growth the limits are defined by (z^4 / 8 at z = 1e-3 is 1.25e-13).
constexpr double kRadiusSlack = 1e-14;

struct ModeLimit {
  TheoryKind kind = TheoryKind::Limit;
  double dt = 0;
};

ModeLimit modeLimit(Method method, const Mode& mode) {
  const double scale = std::max(std::sqrt(mode.kappa), mode.delta);
  if (!(scale > 0)) return {TheoryKind::AlwaysStable, 0};  // a free, undamped direction: R = 1
  const auto unstable = [&](double h) {
    return stepSpectralRadius(method, mode, h) > 1 + kRadiusSlack;
  };
  double h = 1e-3 / scale;
  if (unstable(h)) return {TheoryKind::NeverStable, 0};
  const double h_end = 1e4 / scale;
  for (double next = h * 1.02; next <= h_end; next *= 1.02) {
    if (unstable(next)) {
      double lo = h, hi = next;
      while (hi / lo - 1 > 1e-12) {
        const double mid = 0.5 * (lo + hi);
        (unstable(mid) ? hi : lo) = mid;
      }
      return {TheoryKind::Limit, lo};
    }
    h = next;
  }
  return {TheoryKind::AlwaysStable, 0};
}

template <typename T>
bool finiteAndBounded(const Particles<T>& p, double speed_bound, double position_bound) {
  for (int i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x = double(p.position(k, i));
      const double v = double(p.velocity(k, i));
      // written so that a NaN fails
      if (!(std::abs(x) <= position_bound) || !(std::abs(v) <= speed_bound)) return false;
    }
  }
  return true;
}

template <typename T>
bool clothRunIsStable(const Scene& scene, Method method, double dt,
                      const StabilityCriterion& criterion, CgStats* cg) {
  World<T> simulation = makeWorld<T>(scene, method, dt);
  const auto steps = std::max<std::int64_t>(
      criterion.min_steps, static_cast<std::int64_t>(std::ceil(criterion.horizon / dt - 1e-9)));
  for (std::int64_t s = 0; s < steps; ++s) {
    step(simulation);
    const World<T>& world = simulation;
    if (world.cloth &&
        !finiteAndBounded(world.cloth->particles, criterion.speed_bound, criterion.position_bound))
      return false;
    if (world.spheres && !finiteAndBounded(world.spheres->particles, criterion.speed_bound,
                                           criterion.position_bound))
      return false;
  }
  if (const BackwardEulerSolver<T>* solver = backwardEulerSolver(simulation); cg && solver)
    *cg = solver->stats;
  return true;
}

template <typename T>
bool oscillatorRunIsStable(const Scene& scene, Method method, double dt,
                           const StabilityCriterion& criterion, CgStats* cg) {
  const SpringProblem problem = springProblem(scene);
  const double omega = naturalFrequency(problem.oscillator);
  const Eigen::Vector3d equilibrium = problem.anchor + problem.rest_length * problem.axis;
  World<T> simulation = makeWorld<T>(scene, method, dt);
  // start in the spring's linear range: the scene's displacement and velocity scaled down, so
  // growth is measured before the particle can swing through its anchor (where the 1-D spring
  // turns nonlinear and the amplitude saturates)
  Particles<T>& start = simulation.cloth->particles;
  for (int k = 0; k < 3; ++k) {
    const double offset = double(start.position(k, problem.particle)) - equilibrium[k];
    start.position(k, problem.particle) = T(equilibrium[k] + criterion.initial_scale * offset);
    start.velocity(k, problem.particle) =
        T(criterion.initial_scale * double(start.velocity(k, problem.particle)));
  }
  const int quarter = criterion.steps / 4;
  double initial = 0;
  {
    Eigen::Vector3d x, v;
    for (int k = 0; k < 3; ++k) {
      x[k] = double(start.position(k, problem.particle));
      v[k] = double(start.velocity(k, problem.particle));
    }
    initial = std::sqrt((x - equilibrium).squaredNorm() + v.squaredNorm() / (omega * omega));
  }
  double first = 0, last = 0;
  for (int s = 1; s <= criterion.steps; ++s) {
    step(simulation);
    const Particles<T>& p = simulation.cloth->particles;
    Eigen::Vector3d x, v;
    for (int k = 0; k < 3; ++k) {
      x[k] = double(p.position(k, problem.particle));
      v[k] = double(p.velocity(k, problem.particle));
    }
    const double amplitude =
        std::sqrt((x - equilibrium).squaredNorm() + v.squaredNorm() / (omega * omega));
    if (!std::isfinite(amplitude)) return false;
    if (s <= quarter) first = std::max(first, amplitude);
    if (s > criterion.steps - quarter) last = std::max(last, amplitude);
    // still linear, but far beyond what a stable method reaches
    if (amplitude > criterion.amplitude_bound * initial) return false;
  }
  if (const BackwardEulerSolver<T>* solver = backwardEulerSolver(simulation); cg && solver)
    *cg = solver->stats;
  return !(last > first * (1 + criterion.growth));
}

}  // namespace

double stepSpectralRadius(Method method, const Mode& mode, double h) {
  const Amplification& amplification = methodInfo(method).amplification;
  switch (amplification.kind) {
    case AmplificationKind::Rational:
      break;
    case AmplificationKind::SymplecticEuler: {
      // v1 = v0 + h (-kappa x0 - delta v0), x1 = x0 + h v1
      const double a = 1 - h * h * mode.kappa, b = h * (1 - h * mode.delta);
      const double c = -h * mode.kappa, d = 1 - h * mode.delta;
      // (a - d)^2 + 4 b c rather than trace^2 - 4 det: no cancellation when a drag-only mode
      // (kappa = 0) has the eigenvalues 1 and 1 - h delta
      const double trace = a + d;
      const Complex root = std::sqrt(Complex((a - d) * (a - d) + 4 * b * c, 0));
      return std::max(std::abs((trace + root) / 2.0), std::abs((trace - root) / 2.0));
    }
  }
  double radius = 0;
  for (const Complex& lambda : modeEigenvalues(mode))
    radius = std::max(radius, std::abs(clothref::amplification(amplification, h * lambda)));
  return radius;
}

TheoryLimit theoryLimit(Method method, const std::vector<Mode>& modes) {
  TheoryLimit result{TheoryKind::AlwaysStable, 0};
  for (const Mode& mode : modes) {
    const ModeLimit limit = modeLimit(method, mode);
    if (limit.kind == TheoryKind::NeverStable) return {TheoryKind::NeverStable, 0};
    if (limit.kind == TheoryKind::Limit &&
        (result.kind == TheoryKind::AlwaysStable || limit.dt < result.dt))
      result = {TheoryKind::Limit, limit.dt};
  }
  return result;
}

std::vector<Mode> sceneModes(const Scene& scene) {
  if (!scene.cloth || (scene.cloth->springs.empty() && !scene.cloth->grid))
    throw InputError("scene '" + scene.name + "': stability theory needs a cloth with springs");
  const World<double> world = makeWorld<double>(scene, Method::Explicit);
  const Cloth<double>& cloth = *world.cloth;
  const Particles<double>& p = cloth.particles;
  std::vector<int> free_index(p.size(), -1);
  int free_count = 0;
  double mass = 0;
  for (int i = 0; i < p.size(); ++i) {
    if (p.mass[i] == 0) continue;
    if (free_count > 0 && p.mass[i] != mass)
      throw InputError("scene '" + scene.name +
                       "': stability theory needs equal masses for the free particles");
    mass = p.mass[i];
    free_index[i] = free_count++;
  }
  // mass-scaled stiffness at the initial state, free particles only
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(3 * free_count, 3 * free_count);
  for (const Spring<double>& spring : cloth.springs) {
    const int s = int(spring.start), e = int(spring.end);
    const Eigen::Vector3d d = p.position.col(s).head<3>() - p.position.col(e).head<3>();
    const double length = d.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector3d n = d / length;
    const Eigen::Matrix3d nn = n * n.transpose();
    const double transverse = std::max(0.0, 1 - spring.rest_length / length);
    const Eigen::Matrix3d block =
        cloth.spring_coef / mass * (nn + transverse * (Eigen::Matrix3d::Identity() - nn));
    const int fs = free_index[s], fe = free_index[e];
    if (fs >= 0) stiffness.block<3, 3>(3 * fs, 3 * fs) += block;
    if (fe >= 0) stiffness.block<3, 3>(3 * fe, 3 * fe) += block;
    if (fs >= 0 && fe >= 0) {
      stiffness.block<3, 3>(3 * fs, 3 * fe) -= block;
      stiffness.block<3, 3>(3 * fe, 3 * fs) -= block;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& kappas = solver.eigenvalues();
  const double kappa_max = kappas.size() ? kappas.maxCoeff() : 0.0;
  const double ratio = cloth.spring_coef != 0 ? cloth.damper_coef / cloth.spring_coef : 0.0;
  const double drag = scene.viscous_coef / mass;
  std::vector<Mode> modes;
  for (Eigen::Index i = 0; i < kappas.size(); ++i) {
    // eigenvalues of a positive semi-definite matrix: round-off can make a zero slightly negative
    const double kappa = kappas[i] > 1e-12 * kappa_max ? kappas[i] : 0.0;
    modes.push_back(Mode{kappa, ratio * kappa + drag});
  }
  return modes;
}

StabilityCriterion stabilityCriterion(const Scene& scene) {
  StabilityCriterion criterion;
  if (isSpringScene(scene)) {
    criterion.kind = StabilityCriterion::Kind::Oscillator;
    criterion.steps = 20000;
    criterion.growth = 1e-2;
    criterion.initial_scale = 1e-2;
    criterion.amplitude_bound = 100;
    criterion.text =
        "20000 steps from the scene's state with its displacement and velocity scaled by 0.01 "
        "(linear range); unstable when the state turns non-finite, the amplitude "
        "A = sqrt(|x - x_eq|^2 + |v|^2 / omega^2) exceeds 100 A(0), or the largest A of the last "
        "quarter exceeds the first quarter's by more than 1 %";
  } else {
    criterion.kind = StabilityCriterion::Kind::Cloth;
    criterion.horizon = 0.5;
    criterion.min_steps = 50;
    criterion.speed_bound = 100;
    criterion.position_bound = 100;
    criterion.text =
        "0.5 s simulated, at least 50 steps; unstable when a position or velocity turns "
        "non-finite, a velocity "
        "component exceeds 100 m/s or a coordinate exceeds 100 m";
  }
  return criterion;
}

bool runIsStable(const Scene& scene, Method method, Precision precision, double dt,
                 const StabilityCriterion& criterion, CgStats* cg) {
  if (criterion.kind == StabilityCriterion::Kind::Oscillator)
    return precision == Precision::Float
               ? oscillatorRunIsStable<float>(scene, method, dt, criterion, cg)
               : oscillatorRunIsStable<double>(scene, method, dt, criterion, cg);
  return precision == Precision::Float ? clothRunIsStable<float>(scene, method, dt, criterion, cg)
                                       : clothRunIsStable<double>(scene, method, dt, criterion, cg);
}

SearchRange searchRange(const Scene& scene) {
  if (isSpringScene(scene)) return {1e-2, 1.0, 1e-3};
  return {3e-5, 2e-2, 1e-2};
}

MeasuredLimit measureLimit(const Scene& scene, Method method, Precision precision,
                           const StabilityCriterion& criterion, const SearchRange& range) {
  MeasuredLimit result;
  const auto stable = [&](double dt) {
    ++result.runs;
    CgStats cg;
    const bool stable = runIsStable(scene, method, precision, dt, criterion, &cg);
    // the CG effort of the largest dt found stable so far (the bisection only moves it up)
    if (stable && method == Method::BackwardEuler && cg.solves > 0) {
      result.cg_iterations = cg.meanIterations();
      result.cg_max_iterations = cg.max_iterations_seen;
    }
    return stable;
  };
  double lo = range.low, hi = range.high;
  if (!stable(lo)) {
    result.kind = MeasuredKind::UnstableAtLow;
    return result;
  }
  if (stable(hi)) {
    result.kind = MeasuredKind::StableAtHigh;
    result.dt = hi;
    return result;
  }
  // the limit is in (lo, hi]: halve the ratio hi / lo until it is within the resolution
  while (hi / lo - 1 > range.resolution) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  result.dt = lo;
  return result;
}

std::vector<StabilityResult> stabilityStudy(const std::vector<Scene>& scenes,
                                            const std::vector<Method>& methods,
                                            const std::vector<Precision>& precisions,
                                            const std::function<void(const std::string&)>& progress,
                                            std::optional<double> high) {
  std::vector<StabilityResult> results;
  for (const Scene& scene : scenes) {
    const std::vector<Mode> modes = sceneModes(scene);
    double kappa_max = 0;
    for (const Mode& mode : modes) kappa_max = std::max(kappa_max, mode.kappa);
    const StabilityCriterion criterion = stabilityCriterion(scene);
    SearchRange range = searchRange(scene);
    if (high) range.high = *high;
    for (Method method : methods) {
      const TheoryLimit theory = theoryLimit(method, modes);
      for (Precision precision : precisions) {
        const auto start = std::chrono::steady_clock::now();
        StabilityResult result;
        result.scene = scene.name;
        result.method = std::string(methodName(method));
        result.precision = precision;
        result.theory = theory;
        result.measured = measureLimit(scene, method, precision, criterion, range);
        if (scene.cloth && scene.cloth->grid) result.omega_max = std::sqrt(kappa_max);
        result.criterion = criterion.text;
        result.range = range;
        result.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        results.push_back(result);
        if (progress)
          progress(fmt::format("stability: {} {} {}: measured {} ({} runs, {:.1f} s)", scene.name,
                               result.method, precisionName(precision),
                               result.measured.kind == MeasuredKind::Limit
                                   ? fmt::format("{:.6g} s", result.measured.dt)
                               : result.measured.kind == MeasuredKind::UnstableAtLow
                                   ? std::string("unstable at the range's low end")
                                   : std::string("stable at the range's high end"),
                               result.measured.runs, result.seconds));
      }
    }
  }
  return results;
}

namespace {

nlohmann::ordered_json optionalNumber(bool present, double value) {
  return present ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

std::string measuredNote(const StabilityResult& r) {
  switch (r.measured.kind) {
    case MeasuredKind::Limit:
      return fmt::format("bisection to {:g} relative", r.range.resolution);
    case MeasuredKind::UnstableAtLow:
      return fmt::format("unstable at every dt tried, down to {:g} s", r.range.low);
    case MeasuredKind::StableAtHigh:
      return fmt::format("stable at every dt tried, up to {:g} s", r.range.high);
  }
  return "";
}

std::string theoryNote(const StabilityResult& r) {
  switch (r.theory.kind) {
    case TheoryKind::Limit:
      return "first dt where the step's spectral radius exceeds 1 on a linear mode";
    case TheoryKind::NeverStable:
      return "the spectral radius exceeds 1 at every dt > 0";
    case TheoryKind::AlwaysStable:
      return "the spectral radius never exceeds 1 (no limit)";
  }
  return "";
}

}  // namespace

nlohmann::ordered_json stabilityToJson(const std::vector<StabilityResult>& results) {
  nlohmann::ordered_json items = nlohmann::ordered_json::array();
  for (const StabilityResult& r : results) {
    const bool measured = r.measured.kind == MeasuredKind::Limit;
    const bool theory = r.theory.kind == TheoryKind::Limit;
    nlohmann::ordered_json item;
    item["scene"] = r.scene;
    item["method"] = r.method;
    item["precision"] = std::string(precisionName(r.precision));
    item["dt_max_measured"] = optionalNumber(measured, r.measured.dt);
    item["dt_max_theory"] = optionalNumber(theory, r.theory.dt);
    item["criterion"] = r.criterion;
    item["ratio"] = optionalNumber(measured && theory, r.measured.dt / r.theory.dt);
    item["measured_note"] = measuredNote(r);
    item["theory_note"] = theoryNote(r);
    item["omega_max"] = optionalNumber(r.omega_max.has_value(), r.omega_max.value_or(0));
    item["resolution"] = r.range.resolution;
    item["search_low"] = r.range.low;
    item["search_high"] = r.range.high;
    item["runs"] = r.measured.runs;
    item["cg_iterations_per_step"] =
        optionalNumber(r.measured.cg_iterations.has_value(), r.measured.cg_iterations.value_or(0));
    item["cg_max_iterations"] =
        optionalNumber(r.measured.cg_iterations.has_value(), r.measured.cg_max_iterations);
    item["seconds"] = r.seconds;
    items.push_back(item);
  }
  nlohmann::ordered_json root;
  root["results"] = items;
  return root;
}

std::string stabilityTable(const std::vector<StabilityResult>& results) {
  std::string out = fmt::format("{:<16} {:<15} {:<7} {:>13} {:>13} {:>7}  {}\n", "scene", "method",
                                "prec", "measured (s)", "theory (s)", "ratio", "note");
  for (const StabilityResult& r : results) {
    const bool measured = r.measured.kind == MeasuredKind::Limit;
    const bool theory = r.theory.kind == TheoryKind::Limit;
    const std::string m = measured ? fmt::format("{:.6g}", r.measured.dt)
                          : r.measured.kind == MeasuredKind::StableAtHigh
                              ? fmt::format(">={:g}", r.range.high)
                              : std::string("none");
    const std::string t = theory ? fmt::format("{:.6g}", r.theory.dt)
                          : r.theory.kind == TheoryKind::AlwaysStable ? std::string("inf")
                                                                      : std::string("none");
    const std::string ratio =
        measured && theory ? fmt::format("{:.4f}", r.measured.dt / r.theory.dt) : std::string("-");
    std::string note = measuredNote(r);
    if (r.omega_max) note += fmt::format("; omega_max {:.1f} rad/s", *r.omega_max);
    if (r.measured.cg_iterations)
      note += fmt::format("; CG {:.1f} iterations per step (max {})", *r.measured.cg_iterations,
                          r.measured.cg_max_iterations);
    out += fmt::format("{:<16} {:<15} {:<7} {:>13} {:>13} {:>7}  {}\n", r.scene, r.method,
                       precisionName(r.precision), m, t, ratio, note);
  }
  return out;
}

}  // namespace clothref
