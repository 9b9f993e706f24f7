// The four integrators, each driven by OUR course-form simulateOneStep inside the child (the
// student's forces and contacts are never used): one step on a random state against clothref's
// method (or an accepted variant), every body integrated, deltaTime unchanged, backups are
// copies, the observed convergence order on a single damped spring, and no blow-up at half the
// method's stability limit. Known mistakes are recognised by simulating them here and comparing.
#include <Eigen/QR>
#include <complex>
#include <functional>
#include <random>

#include "clothref/core/cloth.h"
#include "clothref/core/integrator.h"
#include "clothref/core/spheres.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/verify.h"
#include "probe_util.h"

namespace clothref::grader {
namespace {

const char* kStubs[] = {"ExplicitEuler::integrate", "ImplicitEuler::integrate",
                        "MidpointEuler::integrate", "RungeKuttaFourth::integrate"};
const Method kMethods[] = {Method::Explicit, Method::Implicit, Method::Midpoint, Method::Rk4};
const int kTheoreticalOrder[] = {1, 1, 2, 4};

// A small system: a cloth (any particles and springs) and spheres, the course's step parts.
struct System {
  Cloth<float> cloth;
  Spheres<float> spheres;
  float viscous = 0;
  Vec4<float> gravity = Vec4<float>::Zero();
  bool sphere_gravity = false;
  float dt = 0;
};

void simulate(System& s) {
  computeExternalForce(s.cloth.particles, s.gravity, s.viscous);
  if (s.sphere_gravity)
    computeExternalForce(s.spheres.particles, s.gravity, s.viscous);
  else
    s.spheres.particles.acceleration.setZero();
  computeSpringForce(s.cloth);
}

using Step = std::function<void(System&)>;

// The course's main loop step: derivatives first, then the integrator.
Step clothrefStep(Method method, int bodies_integrated = 2) {
  return [method, bodies_integrated](System& s) {
    std::array<Particles<float>*, 2> storage{&s.cloth.particles, &s.spheres.particles};
    IntegratorScratch<float> scratch;
    auto sim = [&] { simulate(s); };
    simulate(s);
    integrate(method, Bodies<float>(storage.data(), std::size_t(bodies_integrated)), s.dt,
              FunctionRef<void()>(sim), scratch);
  };
}

// Course-form variants written the way students write them, for the numeric signatures.
// `alias`: every read of "the backup" sees the live state (a pointer or Eigen::Ref "copy").
enum class Variant {
  ImplicitVNew,
  Alias,
  NoReevaluation,
  RkIntDivision,
  RkMixedFinal,
  RkMixedStage,
  RkStageFromCurrent,
  PositionUsesAcceleration,
  VelocityOnly,
  PositionOnly
};

// `stage`: for RkMixedStage, the stage (0..2) whose position uses the velocity increment.
Step variantStep(Method method, Variant variant, int stage_index = -1) {
  return [method, variant, stage_index](System& s) {
    std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
    const float dt = s.dt;
    simulate(s);
    const bool alias = variant == Variant::Alias;
    std::vector<Mat4X<float>> x0, v0;
    for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
    const auto X0 = [&](std::size_t b) { return alias ? bodies[b]->position : x0[b]; };
    const auto V0 = [&](std::size_t b) { return alias ? bodies[b]->velocity : v0[b]; };
    if (method == Method::Explicit || variant == Variant::NoReevaluation) {
      for (auto* p : bodies) {
        if (variant == Variant::PositionUsesAcceleration)
          p->position += p->velocity * dt + p->acceleration * (0.5f * dt * dt);
        else if (variant != Variant::VelocityOnly)
          p->position += p->velocity * dt;
        if (variant != Variant::PositionOnly) p->velocity += p->acceleration * dt;
      }
      return;
    }
    if (method == Method::Implicit || method == Method::Midpoint) {
      const float h = method == Method::Midpoint ? 0.5f : 1.0f;
      for (auto* p : bodies) {
        p->position += (p->velocity * dt) * h;
        p->velocity += (p->acceleration * dt) * h;
      }
      simulate(s);
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        auto* p = bodies[b];
        if (variant == Variant::ImplicitVNew) {
          p->velocity = V0(b) + p->acceleration * dt;
          p->position = X0(b) + p->velocity * dt;
        } else {
          const Mat4X<float> x = X0(b) + p->velocity * dt;
          p->velocity = V0(b) + p->acceleration * dt;
          p->position = x;
        }
      }
      return;
    }
    // RK4
    std::vector<Mat4X<float>> kx[4], kv[4];
    const float stage[] = {0.5f, 0.5f, 1.0f};
    for (int k = 0; k < 4; ++k) {
      if (k > 0) simulate(s);
      for (auto* p : bodies)
        kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
      if (k == 3) break;
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        const bool current = variant == Variant::RkStageFromCurrent && k > 0;
        const Mat4X<float> x = current ? bodies[b]->position : X0(b);
        const Mat4X<float> v = current ? bodies[b]->velocity : V0(b);
        const bool mixed = variant == Variant::RkMixedStage && stage_index == k;
        bodies[b]->position = x + (mixed ? kv[k][b] : kx[k][b]) * stage[k];
        bodies[b]->velocity = v + kv[k][b] * stage[k];
      }
    }
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Mat4X<float> x = X0(b), v = V0(b);
      const float w = variant == Variant::RkIntDivision ? 0.0f : 1.0f;
      const auto& kxs = variant == Variant::RkMixedFinal ? kv : kx;
      bodies[b]->position =
          x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kxs[3][b]) / 6.0f * w;
      bodies[b]->velocity =
          v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv[3][b]) / 6.0f * w;
    }
  };
}

// ---- The systems.
System randomSystem(std::uint64_t seed) {
  System s;
  constexpr int n = 4;
  s.cloth.particles = initializeVertex<float>(n, 0.5f, 0.0f, 1.0f);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setMass(s.cloth.particles, corner, 0.0f);
  initializeSpring(s.cloth, n);
  s.cloth.spring_coef = 500;
  s.cloth.damper_coef = 5;
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::uniform_real_distribution<float> u(-1, 1);
  for (int i = 0; i < n * n; ++i)
    for (int r = 0; r < 3; ++r) {
      s.cloth.particles.position(r, i) += 0.05f * u(rng);
      if (s.cloth.particles.mass[i] != 0) s.cloth.particles.velocity(r, i) = 0.5f * u(rng);
    }
  addSphere(s.spheres, Vec4<float>(3, 1, 0, 1), 0.5f, 1000.0f);
  addSphere(s.spheres, Vec4<float>(-3, 1.5f, 0.5f, 1), 0.5f, 1000.0f);
  for (int i = 0; i < 2; ++i)
    for (int r = 0; r < 3; ++r) s.spheres.particles.velocity(r, i) = u(rng);
  s.viscous = 3.4e-4f;
  s.gravity = Vec4<float>(0, -9.8f, 0, 0);
  s.sphere_gravity = true;
  s.dt = 0.01f;
  return s;
}

// clothref's `spring` scene: an anchor at the origin, a unit mass at x = 1.2 on a spring of rest
// length 1, k = 100 N/m, c = 2 N s/m, no gravity or drag; one sphere far away at rest.
System springSystem(float dt) {
  System s;
  s.cloth.particles = makeParticles<float>(2, 1.0f);
  setMass(s.cloth.particles, 0, 0.0f);
  s.cloth.particles.position.col(1) = Vec4<float>(1.2f, 0, 0, 1);
  s.cloth.springs.push_back({0, 1, 1.0f, SpringType::Structural});
  s.cloth.spring_coef = 100;
  s.cloth.damper_coef = 2;
  addSphere(s.spheres, Vec4<float>(100, 100, 0, 1), 0.5f, 1000.0f);
  s.dt = dt;
  return s;
}

DampedOscillator springOscillator() {
  DampedOscillator o;
  o.stiffness = 100;
  o.damping = 2;
  o.mass = 1;
  o.displacement0 = 0.2;
  return o;
}

// Largest dt with |R(lambda dt)| <= 1 for the spring's eigenvalues (bisection on [0, 1]).
double stabilityLimit(Method method) {
  const DampedOscillator o = springOscillator();
  const double w = std::sqrt(o.stiffness / o.mass),
               zeta = o.damping / (2 * std::sqrt(o.stiffness * o.mass));
  const std::complex<double> lambda(-zeta * w, w * std::sqrt(1 - zeta * zeta));
  const auto stable = [&](double h) {
    return std::abs(amplification(methodInfo(method).amplification, lambda * h)) <= 1.0;
  };
  double lo = 1e-6, hi = 1.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

void addSystem(probe::ProbeMessage& m, int k, const System& s, std::int64_t steps,
               std::int64_t stride) {
  const std::string n = "." + std::to_string(k);
  m.floats["c.pos" + n] = util::flat(s.cloth.particles.position);
  m.floats["c.vel" + n] = util::flat(s.cloth.particles.velocity);
  m.floats["c.mass" + n] = util::flat(s.cloth.particles.mass);
  m.floats["s.pos" + n] = util::flat(s.spheres.particles.position);
  m.floats["s.vel" + n] = util::flat(s.spheres.particles.velocity);
  m.floats["s.mass" + n] = util::flat(s.spheres.particles.mass);
  m.floats["s.rad" + n] = s.spheres.radius;
  const std::string sp = "sp" + n + ".";
  for (const auto& spring : s.cloth.springs) {
    m.ints[sp + "start"].push_back(spring.start);
    m.ints[sp + "end"].push_back(spring.end);
    m.ints[sp + "type"].push_back(static_cast<std::int64_t>(spring.type));
    m.floats[sp + "rest"].push_back(spring.rest_length);
  }
  m.floats["params" + n] = {s.cloth.spring_coef, s.cloth.damper_coef, s.viscous, s.gravity[0],
                            s.gravity[1],        s.gravity[2],        0.0f,      0.8f};
  m.ints["flags" + n] = {s.sphere_gravity ? 1 : 0, 0, 0};
  m.floats["dt" + n] = {s.dt};
  m.ints["steps" + n] = {steps};
  m.ints["stride" + n] = {stride};
}

System answerSystem(const probe::ProbeMessage& a, int k, const System& like) {
  const std::string n = "." + std::to_string(k);
  System s = like;
  s.cloth.particles.position = util::matrix(a.f("c.pos" + n), like.cloth.particles.size());
  s.cloth.particles.velocity = util::matrix(a.f("c.vel" + n), like.cloth.particles.size());
  s.spheres.particles.position = util::matrix(a.f("s.pos" + n), like.spheres.size());
  s.spheres.particles.velocity = util::matrix(a.f("s.vel" + n), like.spheres.size());
  return s;
}

// Largest |a - b| / (1 + |b|) over positions and velocities of body 0, 1 or both (-1).
double distance(const System& a, const System& b, int body = -1) {
  double worst = 0;
  const auto one = [&](const Mat4X<float>& x, const Mat4X<float>& y) {
    if (x.size() != y.size()) {
      worst = 1e300;
      return;
    }
    for (int k = 0; k < x.size(); ++k) {
      const double d =
          std::abs(double(x.data()[k]) - double(y.data()[k])) / (1 + std::abs(double(y.data()[k])));
      worst = std::isfinite(d) ? std::max(worst, d) : 1e300;
    }
  };
  if (body != 1)
    one(a.cloth.particles.position, b.cloth.particles.position),
        one(a.cloth.particles.velocity, b.cloth.particles.velocity);
  if (body != 0)
    one(a.spheres.particles.position, b.spheres.particles.position),
        one(a.spheres.particles.velocity, b.spheres.particles.velocity);
  return worst;
}

System stepped(const System& s, const Step& step) {
  System copy = s;
  step(copy);
  return copy;
}

// Errors |x - x_exact| of the free particle, max over the recorded trajectory.
double trajectoryError(const std::vector<float>& trajectory, double dt, std::int64_t stride) {
  const DampedOscillator o = springOscillator();
  double worst = 0;
  const std::size_t per_record = 8;  // two particles x 4
  for (std::size_t r = 0; (r + 1) * per_record <= trajectory.size(); ++r) {
    const double t = double(r + 1) * double(stride) * dt;
    const double x = trajectory[r * per_record + 4];
    const double exact = 1.0 + oscillatorState(o, t).position;
    const double e = std::abs(x - exact);
    worst = std::isfinite(e) ? std::max(worst, e) : 1e300;
  }
  return worst;
}

// The same trajectory error for clothref's method (the expected observed order).
double referenceError(Method method, double dt, std::int64_t steps, std::int64_t stride) {
  System s = springSystem(float(dt));
  std::vector<float> trajectory;
  const Step step = clothrefStep(method);
  for (std::int64_t k = 1; k <= steps; ++k) {
    step(s);
    if (k % stride == 0) {
      const auto x = util::flat(s.cloth.particles.position);
      trajectory.insert(trajectory.end(), x.begin(), x.end());
    }
  }
  return trajectoryError(trajectory, dt, stride);
}

std::string systemText(const System& s) {
  return "a 4 x 4 cloth (corners fixed, k_s = 500, k_d = 5, positions and velocities randomly "
         "perturbed) and 2 spheres under gravity, dt = " +
         util::num(s.dt) +
         "; first free cloth "
         "particle (index 1): x " +
         util::vec3(s.cloth.particles.position.col(1)) + ", v " +
         util::vec3(s.cloth.particles.velocity.col(1)) + "; sphere 0: x " +
         util::vec3(s.spheres.particles.position.col(0)) + ", v " +
         util::vec3(s.spheres.particles.velocity.col(0));
}

}  // namespace

std::vector<TestResult> probeIntegrator(const ProbeContext& context, int index) {
  const std::string stub = kStubs[index];
  const Method method = kMethods[index];
  const double rel = context.rubric.tolerances.integrate_rel;
  const bool has_backup = method != Method::Explicit;

  // Case 0: one step on a random state. Cases 1..: the convergence ladder. Last: stability.
  const System random = randomSystem(context.seed + 7 * std::uint64_t(index));
  std::vector<double> dts;
  double end_time = 1.0;
  switch (method) {
    case Method::Explicit:
    case Method::Implicit:
      dts = {0.002, 0.001, 0.0005, 0.00025};
      break;
    case Method::Midpoint:
      dts = {0.01, 0.005, 0.0025, 0.00125};
      break;
    default:
      dts = {0.1, 0.05, 0.025};
      end_time = 2.0;
      break;
  }
  const double limit = stabilityLimit(method);
  const double stable_dt = 0.5 * limit;
  const std::int64_t stable_steps = static_cast<std::int64_t>(20.0 / stable_dt);

  probe::ProbeMessage request;
  request.texts["group"] = "integrate";
  request.ints["method"] = {index};
  addSystem(request, 0, random, 1, 0);
  std::vector<std::int64_t> strides;
  for (std::size_t k = 0; k < dts.size(); ++k) {
    const std::int64_t steps = std::llround(end_time / dts[k]);
    const std::int64_t stride = std::max<std::int64_t>(1, steps / 50);
    strides.push_back(stride);
    addSystem(request, int(k) + 1, springSystem(float(dts[k])), steps, stride);
  }
  const int stable_case = int(dts.size()) + 1;
  const std::int64_t stable_stride = std::max<std::int64_t>(1, stable_steps / 100);
  addSystem(request, stable_case, springSystem(float(stable_dt)), stable_steps, stable_stride);
  request.ints["cases"] = {stable_case + 1};

  std::vector<std::string> checks = {"one step on a random state", "every body integrated",
                                     "deltaTime unchanged"};
  if (has_backup) checks.push_back("backups are copies");
  checks.push_back("convergence order");
  checks.push_back("stable below the stability limit");
  std::string failure;
  const auto answer = util::runGroup(context, context.probe, "integrate-" + std::to_string(index),
                                     request, failure);
  std::vector<TestResult> tests;
  if (!answer) {
    const std::string id = util::verdictId(failure);
    for (const auto& check : checks)
      tests.push_back(util::failedTest(stub, check, check == checks[0] ? 2 : 1,
                                       failure + "\n\n" + context.catalogue->cause(id, true),
                                       {id}));
    return tests;
  }

  // One step.
  const System actual = answerSystem(*answer, 0, random);
  const System expected = stepped(random, clothrefStep(method));
  std::vector<std::pair<std::string, Step>> accepted;
  if (method == Method::Explicit && context.rubric.accepts("explicit-as-symplectic"))
    accepted.push_back({"explicit written as symplectic Euler (v first, then x with the new v)",
                        clothrefStep(Method::Symplectic)});
  if (method == Method::Implicit && context.rubric.accepts("implicit-corrector-v-new"))
    accepted.push_back({"the corrector's position uses the new velocity",
                        variantStep(Method::Implicit, Variant::ImplicitVNew)});
  TestResult one = makeTest(stub, checks[0], 2);
  const double d = distance(actual, expected);
  std::string matched_variant;
  for (const auto& [what, step] : accepted)
    if (distance(actual, stepped(random, step)) <= rel) matched_variant = what;
  std::vector<std::string> ids;
  if (d <= rel || !matched_variant.empty()) {
    one.fraction = 1;
    one.output = matched_variant.empty()
                     ? "Matches the course method after one step (every body, x and v)."
                     : "Matches an accepted variant: " + matched_variant + ".";
  } else {
    one.output = "State: " + systemText(random) + ".\n\nAfter one step:\n\n" +
                 "- expected (course method) particle 1: x " +
                 util::vec3(expected.cloth.particles.position.col(1)) + ", v " +
                 util::vec3(expected.cloth.particles.velocity.col(1)) + "; sphere 0: x " +
                 util::vec3(expected.spheres.particles.position.col(0)) + "\n" +
                 "- actual particle 1: x " + util::vec3(actual.cloth.particles.position.col(1)) +
                 ", v " + util::vec3(actual.cloth.particles.velocity.col(1)) + "; sphere 0: x " +
                 util::vec3(actual.spheres.particles.position.col(0)) + "\n";
    std::vector<std::pair<std::string, Step>> signatures = {
        {"only-first-body", clothrefStep(method, 1)}};
    if (method == Method::Explicit) {
      signatures.push_back({"only-first-body", clothrefStep(Method::Symplectic, 1)});
      signatures.push_back(
          {"position-uses-acceleration", variantStep(method, Variant::PositionUsesAcceleration)});
      signatures.push_back({"velocity-not-integrated", variantStep(method, Variant::PositionOnly)});
      signatures.push_back({"position-not-integrated", variantStep(method, Variant::VelocityOnly)});
    } else {
      signatures.push_back({"backup-alias", variantStep(method, Variant::Alias)});
      signatures.push_back({"no-reevaluation", variantStep(method, Variant::NoReevaluation)});
    }
    if (method == Method::Midpoint)
      signatures.push_back({"midpoint-full-step", clothrefStep(Method::Implicit)});
    if (method == Method::Rk4) {
      signatures.push_back({"integer-division-rk4", variantStep(method, Variant::RkIntDivision)});
      signatures.push_back({"rk4-mixed-increments", variantStep(method, Variant::RkMixedFinal)});
      for (int k = 0; k < 3; ++k)
        signatures.push_back(
            {"rk4-mixed-increments", variantStep(method, Variant::RkMixedStage, k)});
      signatures.push_back(
          {"rk4-stage-not-from-backup", variantStep(method, Variant::RkStageFromCurrent)});
    }
    for (const auto& [id, step] : signatures)
      if (distance(actual, stepped(random, step)) <= 10 * rel &&
          std::find(ids.begin(), ids.end(), id) == ids.end())
        ids.push_back(id);
    if (ids.empty() && method == Method::Rk4) {
      // Right stages, wrong weights? Fit x1 - x0 = sum w_k kx_k on the cloth positions.
      System s = random;
      std::vector<Mat4X<float>> kx;
      std::array<Particles<float>*, 2> storage{&s.cloth.particles, &s.spheres.particles};
      (void)storage;
      simulate(s);
      const Mat4X<float> x0 = s.cloth.particles.position, v0 = s.cloth.particles.velocity;
      const float stage[] = {0.5f, 0.5f, 1.0f};
      for (int k = 0; k < 4; ++k) {
        if (k > 0) simulate(s);
        kx.push_back(s.cloth.particles.velocity * s.dt);
        if (k < 3) {
          const Mat4X<float> kv = s.cloth.particles.acceleration * s.dt;
          s.cloth.particles.position = x0 + kx.back() * stage[k];
          s.cloth.particles.velocity = v0 + kv * stage[k];
        }
      }
      Eigen::MatrixXd a(x0.size(), 4);
      for (int k = 0; k < 4; ++k)
        a.col(k) = Eigen::Map<const Eigen::VectorXf>(kx[k].data(), x0.size()).cast<double>();
      const Eigen::VectorXd b =
          (Eigen::Map<const Eigen::VectorXf>(actual.cloth.particles.position.data(), x0.size()) -
           Eigen::Map<const Eigen::VectorXf>(x0.data(), x0.size()))
              .cast<double>();
      const Eigen::Vector4d w = a.colPivHouseholderQr().solve(b);
      if ((a * w - b).norm() <= 1e-4 * (1e-12 + b.norm()) && w.allFinite()) {
        ids.push_back("rk4-wrong-weights");
        one.output += "\nYour position update fits x0 + " + util::num(w[0]) + " k1 + " +
                      util::num(w[1]) + " k2 + " + util::num(w[2]) + " k3 + " + util::num(w[3]) +
                      " k4 (the course: 1/6, 1/3, 1/3, 1/6).\n";
      }
    }
    const float dt_after = answer->f("dt_after.0").empty() ? random.dt : answer->f("dt_after.0")[0];
    if (dt_after != random.dt) ids.push_back("deltatime-mutated");
    // simulateOneStep calls during integrate: 1 (implicit, midpoint) or 3 (RK4) in the course.
    const std::int64_t calls = answer->i("calls.0").empty() ? -1 : answer->i("calls.0")[0];
    const std::int64_t expected_calls = method == Method::Rk4        ? 3
                                        : method == Method::Explicit ? 0
                                                                     : 1;
    if (calls >= 0 && calls < expected_calls) {
      one.output += "\nsimulateOneStep() was called " + std::to_string(calls) +
                    " times during integrate(); the course method calls it " +
                    std::to_string(expected_calls) + " times.\n";
      ids.erase(std::remove(ids.begin(), ids.end(), "no-reevaluation"), ids.end());
      ids.push_back("no-reevaluation");
    } else if (method == Method::Midpoint && calls == expected_calls) {
      // Explicit Euler's result despite a re-evaluation: the half step added nothing.
      if (std::find(ids.begin(), ids.end(), "no-reevaluation") != ids.end()) {
        ids.erase(std::remove(ids.begin(), ids.end(), "no-reevaluation"), ids.end());
        ids.push_back("integer-division-half");
      }
    }
    if (ids.empty()) {
      one.output += "\n" + context.catalogue->cause("unknown", true) + "\n";
      ids.push_back("unknown");
    } else {
      for (const auto& id : ids) one.output += "\n" + context.catalogue->cause(id) + "\n";
    }
    one.diagnoses = ids;
  }
  tests.push_back(one);

  // Every body integrated: each body the course method moves must move.
  TestResult all = makeTest(stub, checks[1], 1);
  std::string stuck;
  if (distance(expected, random, 0) > rel && distance(actual, random, 0) <= rel)
    stuck += "the cloth (particles[0])";
  if (distance(expected, random, 1) > rel && distance(actual, random, 1) <= rel)
    stuck += std::string(stuck.empty() ? "" : " and ") + "the spheres (particles[1])";
  all.fraction = stuck.empty() ? 1 : 0;
  if (stuck.empty()) {
    all.output = "Every Particles* in the vector was integrated.";
  } else {
    all.output = "After one step " + stuck +
                 " did not move at all, although the course method "
                 "moves it (state: " +
                 systemText(random) + ").\n\n";
    const bool only_spheres = stuck.find("cloth") == std::string::npos;
    const std::string id = only_spheres            ? "only-first-body"
                           : method == Method::Rk4 ? "integer-division-rk4"
                                                   : "unknown";
    all.output += context.catalogue->cause(id, !only_spheres && method != Method::Rk4) + "\n";
    all.diagnoses.push_back(id);
  }
  tests.push_back(all);

  // deltaTime unchanged.
  TestResult dt_test = makeTest(stub, checks[2], 1);
  const auto& after = answer->f("dt_after.0");
  const float dt_after = after.empty() ? std::nanf("") : after[0];
  dt_test.fraction = dt_after == random.dt ? 1 : 0;
  dt_test.output = dt_test.fraction == 1
                       ? "The global deltaTime is unchanged after integrate()."
                       : "deltaTime was " + util::num(random.dt) + " before integrate() and " +
                             util::num(dt_after) + " after.\n\n" +
                             context.catalogue->cause("deltatime-mutated") + "\n";
  if (dt_test.fraction == 0) dt_test.diagnoses.push_back("deltatime-mutated");
  tests.push_back(dt_test);

  if (has_backup) {
    TestResult copies = makeTest(stub, checks[3], 1);
    const bool alias =
        distance(actual, stepped(random, variantStep(method, Variant::Alias))) <= 10 * rel &&
        d > rel;
    copies.fraction = alias ? 0 : 1;
    copies.output = alias ? "The result is exactly what a step gives when the backup follows the "
                            "live state (same state as the one-step test).\n\n" +
                                context.catalogue->cause("backup-alias") + "\n"
                          : "The backed-up start state is not changed by the later stages.";
    if (alias) copies.diagnoses.push_back("backup-alias");
    tests.push_back(copies);
  }

  // Convergence order on the spring.
  TestResult order = makeTest(stub, "convergence order", 1);
  std::vector<double> student_errors, reference_errors;
  for (std::size_t k = 0; k < dts.size(); ++k) {
    const std::int64_t steps = std::llround(end_time / dts[k]);
    student_errors.push_back(
        trajectoryError(answer->f("trajectory." + std::to_string(k + 1)), dts[k], strides[k]));
    reference_errors.push_back(referenceError(method, dts[k], steps, strides[k]));
  }
  bool usable = true;
  for (double e : student_errors) usable = usable && std::isfinite(e) && e > 0 && e < 1e299;
  const double expected_order = fitOrder(dts, reference_errors);
  const double observed = usable ? fitOrder(dts, student_errors) : std::nan("");
  order.fraction =
      usable && std::abs(observed - expected_order) <= context.rubric.tolerances.order ? 1 : 0;
  std::string table = "| dt (s) | your max error (m) | course method's |\n|---|---|---|\n";
  for (std::size_t k = 0; k < dts.size(); ++k)
    table += "| " + util::num(dts[k]) + " | " + util::num(student_errors[k]) + " | " +
             util::num(reference_errors[k]) + " |\n";
  order.output =
      "A unit mass on a damped spring (k = 100 N/m, c = 2 N s/m, rest 1 m, released at "
      "1.2 m), " +
      util::num(end_time) + " s against the closed form, at " + std::to_string(dts.size()) +
      " step sizes. Observed order " +
      (usable ? util::num(observed) : std::string("not measurable")) + ", the course method's " +
      util::num(expected_order) + " (theory " + std::to_string(kTheoreticalOrder[index]) +
      ").\n\n" + table;
  if (order.fraction == 0) {
    const std::string id = one.fraction == 1       ? "wrong-order"
                           : one.diagnoses.empty() ? "wrong-order"
                                                   : one.diagnoses.front();
    order.output += "\n" + context.catalogue->cause(id, id == "unknown") + "\n";
    order.diagnoses.push_back(id);
  }
  tests.push_back(order);

  // No blow-up at half the stability limit.
  TestResult stable = makeTest(stub, "stable below the stability limit", 1);
  const auto& trajectory = answer->f("trajectory." + std::to_string(stable_case));
  double amplitude = 0;
  for (std::size_t r = 0; r + 8 <= trajectory.size(); r += 8) {
    const double u = std::abs(double(trajectory[r + 4]) - 1.0);
    amplitude = std::isfinite(u) ? std::max(amplitude, u) : 1e300;
  }
  stable.fraction = amplitude <= 0.3 ? 1 : 0;
  stable.output = "The same spring for 20 s at dt = " + util::num(stable_dt) +
                  " s, half the course "
                  "method's stability limit " +
                  util::num(limit) + " s. Largest |stretch| " +
                  (amplitude >= 1e299 ? std::string("not finite") : util::num(amplitude)) +
                  " m (released at 0.2 m; must stay below 0.3 m).\n";
  if (stable.fraction == 0) {
    stable.output += "\n" + context.catalogue->cause("unstable") + "\n";
    stable.diagnoses.push_back("unstable");
  }
  tests.push_back(stable);
  return tests;
}

}  // namespace clothref::grader
