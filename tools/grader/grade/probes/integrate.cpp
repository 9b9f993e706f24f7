// The four integrators, each driven by OUR course-form simulateOneStep inside the child (the
// student's forces and contacts are never used): one step on a random state against clothref's
// method (or an accepted variant), every body integrated, deltaTime unchanged, backups are
// copies, the observed convergence order on a single damped spring, and no blow-up at half the
// method's stability limit. Known mistakes are recognised by simulating them here and comparing.
#include <Eigen/QR>
#include <complex>
#include <fstream>
#include <functional>
#include <mutex>
#include <random>
#include <regex>

#include "clothref/core/cloth.h"
#include "clothref/core/integrator.h"
#include "clothref/core/spheres.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/verify.h"
#include "grader/grade/probes/stages.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
namespace {

const Method kMethods[] = {Method::Explicit, Method::Implicit, Method::Midpoint, Method::Rk4};
const int kTheoreticalOrder[] = {1, 1, 2, 4};

// A small system: a cloth (any particles and springs) and spheres, the course's step parts.
struct System {
  Cloth<float> cloth;
  Spheres<float> spheres;
  float viscous = 0;
  Vec4<float> gravity = Vec4<float>::Zero();
  bool sphere_gravity = false;
  // Sphere-cloth contact inside simulateOneStep, as the course's: it couples the bodies, so a
  // method that advances them one at a time gives another result.
  bool contact = false;
  float dt = 0;
  bool course_size = false;  // the course's 25 x 25 cloth and spheres (retry after a crash)
};

void simulate(System& s) {
  computeExternalForce(s.cloth.particles, s.gravity, s.viscous);
  if (s.sphere_gravity)
    computeExternalForce(s.spheres.particles, s.gravity, s.viscous);
  else
    s.spheres.particles.acceleration.setZero();
  computeSpringForce(s.cloth);
  if (s.contact) collide(s.spheres, s.cloth, 0.0f, 0.15f);
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
// `Alias`: every read of "the backup" sees the live state (a pointer or Eigen::Ref "copy").
enum class Variant {
  ImplicitVNew,
  SymplecticPredictor,  // predictor v first, then x with the new v (implicit and midpoint)
  Alias,
  NoReevaluation,
  NoReevaluationHalfVelocity,  // simulateOneStep() before the half step: x0 + (v0 + a0 h) dt
  ZeroHalfStep,  // the prediction adds nothing (1 / 2 == 0, or kept in locals): re-evaluated at x0
  PerBody,       // one body at a time, each with its own simulateOneStep() calls
  RkIntDivision,
  RkMixedFinal,
  RkK4xInVelocity,
  RkMixedStage,
  RkStageFromCurrent,
  RkStageFromNewVelocity,  // stage x = x0 + dt h (v0 + kv h)
  RkStagesDiscarded,       // x = x0 + k1, v = v0 + k1v
  PositionUsesAcceleration,
  VelocityOnly,
  PositionOnly
};

// The start state of `bodies`: a copy, or with `alias` the live state (what a pointer or
// Eigen::Ref "copy" reads later).
struct Backup {
  Backup(const std::vector<Particles<float>*>& of, bool alias_live)
      : bodies(of), alias(alias_live) {
    for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
  }
  Mat4X<float> x(std::size_t b) const { return alias ? bodies[b]->position : x0[b]; }
  Mat4X<float> v(std::size_t b) const { return alias ? bodies[b]->velocity : v0[b]; }
  const std::vector<Particles<float>*>& bodies;
  bool alias;
  std::vector<Mat4X<float>> x0, v0;
};

// The course's predictor-corrector (implicit h = 1, midpoint h = 1/2) for `bodies` only; the
// others keep their state (a per-body loop).
void predictCorrect(System& s, const std::vector<Particles<float>*>& bodies, float h,
                    Variant variant) {
  const float dt = s.dt;
  const Backup backup(bodies, variant == Variant::Alias);
  const auto X0 = [&](std::size_t b) { return backup.x(b); };
  const auto V0 = [&](std::size_t b) { return backup.v(b); };
  if (variant == Variant::NoReevaluationHalfVelocity) simulate(s);
  if (variant == Variant::ZeroHalfStep) h = 0;
  for (auto* p : bodies) {
    if (variant == Variant::SymplecticPredictor) {
      p->velocity += (p->acceleration * dt) * h;
      p->position += (p->velocity * dt) * h;
    } else {
      p->position += (p->velocity * dt) * h;
      p->velocity += (p->acceleration * dt) * h;
    }
  }
  if (variant != Variant::NoReevaluationHalfVelocity) simulate(s);
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
}

// RK4 in the course's form for `bodies` only, with one mistake switched on.
void rungeKutta(System& s, const std::vector<Particles<float>*>& bodies, Variant variant,
                int stage_index) {
  const float dt = s.dt;
  const Backup backup(bodies, variant == Variant::Alias);
  const auto X0 = [&](std::size_t b) { return backup.x(b); };
  const auto V0 = [&](std::size_t b) { return backup.v(b); };
  std::vector<Mat4X<float>> kx[4], kv[4];
  const float stage[] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    for (auto* p : bodies) kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
    if (k == 3) break;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const bool current = variant == Variant::RkStageFromCurrent && k > 0;
      const Mat4X<float> x = current ? bodies[b]->position : X0(b);
      const Mat4X<float> v = current ? bodies[b]->velocity : V0(b);
      const bool mixed = variant == Variant::RkMixedStage && stage_index == k;
      bodies[b]->velocity = v + kv[k][b] * stage[k];
      if (variant == Variant::RkStageFromNewVelocity)
        bodies[b]->position = x + (bodies[b]->velocity * dt) * stage[k];
      else
        bodies[b]->position = x + (mixed ? kv[k][b] : kx[k][b]) * stage[k];
    }
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Mat4X<float> x = X0(b), v = V0(b);
    if (variant == Variant::RkStagesDiscarded) {
      bodies[b]->position = x + kx[0][b];
      bodies[b]->velocity = v + kv[0][b];
      continue;
    }
    const float w = variant == Variant::RkIntDivision ? 0.0f : 1.0f;
    const auto& kxs = variant == Variant::RkMixedFinal ? kv : kx;
    const Mat4X<float>& kv4 = variant == Variant::RkK4xInVelocity ? kx[3][b] : kv[3][b];
    bodies[b]->position =
        x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kxs[3][b]) / 6.0f * w;
    bodies[b]->velocity = v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv4) / 6.0f * w;
  }
}

// `stage`: for RkMixedStage, the stage (0..2) whose position uses the velocity increment.
Step variantStep(Method method, Variant variant, int stage_index = -1) {
  return [method, variant, stage_index](System& s) {
    std::vector<Particles<float>*> bodies{&s.cloth.particles, &s.spheres.particles};
    const float dt = s.dt;
    simulate(s);
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
    // A per-body loop: each body alone, later bodies after the earlier ones have moved.
    std::vector<std::vector<Particles<float>*>> groups;
    if (variant == Variant::PerBody)
      for (auto* p : bodies) groups.push_back({p});
    else
      groups.push_back(bodies);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      // A per-body loop's first body uses the derivatives evaluated before integrate(); each later
      // one those of the previous body's last simulateOneStep().
      if (method == Method::Implicit || method == Method::Midpoint)
        predictCorrect(s, groups[g], method == Method::Midpoint ? 0.5f : 1.0f, variant);
      else
        rungeKutta(s, groups[g], variant, stage_index);
    }
  };
}

// ---- The systems.
// Random small perturbations of a cloth at rest: positions by up to 5 cm, free particles'
// velocities up to 0.5 m/s. Sphere 0 presses on a free cloth particle (contact on), so the bodies
// are coupled.
void perturb(System& s, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  auto& p = s.cloth.particles;
  for (int i = 0; i < p.size(); ++i)
    for (int r = 0; r < 3; ++r) {
      p.position(r, i) += 0.05f * u(rng);
      if (p.mass[i] != 0) p.velocity(r, i) = 0.5f * u(rng);
    }
  for (int i = 0; i < s.spheres.size(); ++i)
    for (int r = 0; r < 3; ++r) s.spheres.particles.velocity(r, i) = u(rng);
}

System randomSystem(std::uint64_t seed) {
  System s;
  constexpr int n = 4;
  s.cloth.particles = initializeVertex<float>(n, 0.5f, 0.0f, 1.0f);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setMass(s.cloth.particles, corner, 0.0f);
  initializeSpring(s.cloth, n);
  s.cloth.spring_coef = 500;
  s.cloth.damper_coef = 5;
  addSphere(s.spheres, Vec4<float>(3, 1, 0, 1), 0.5f, 1000.0f);
  addSphere(s.spheres, Vec4<float>(-3, 1.5f, 0.5f, 1), 0.5f, 1000.0f);
  std::mt19937 rng(static_cast<unsigned>(seed));
  perturb(s, rng);
  // Sphere 0 sinks 10 cm into free particle 5 and keeps moving down onto it.
  s.spheres.particles.position.col(0) =
      s.cloth.particles.position.col(5) + Vec4<float>(0, 0.4f, 0, 0);
  s.spheres.particles.velocity.col(0) = Vec4<float>(0.1f, -1, 0, 0);
  s.contact = true;
  s.viscous = 3.4e-4f;
  s.gravity = Vec4<float>(0, -9.8f, 0, 0);
  s.sphere_gravity = true;
  s.dt = 0.01f;
  return s;
}

// The same on the course's own cloth and spheres (25 x 25, the edition's scene), for code that
// only runs there (e.g. indexing particlesPerEdge into the cloth).
System courseSystem(std::uint64_t seed, int edition) {
  const Scene* scene = findBuiltinScene(edition == 2024 ? "course2024" : "course2022");
  const World<float> world = makeWorld<float>(*scene, Method::Explicit);
  System s;
  s.cloth = *world.cloth;
  s.spheres = *world.spheres;
  s.cloth.spring_coef = 500;
  s.cloth.damper_coef = 5;
  std::mt19937 rng(static_cast<unsigned>(seed));
  perturb(s, rng);
  s.viscous = 3.4e-4f;
  s.gravity = Vec4<float>(0, -9.8f, 0, 0);
  s.sphere_gravity = true;
  s.dt = 0.01f;
  s.course_size = true;
  return s;
}

// clothref's `spring` scene: an anchor at the origin, a unit mass at x = 1.2 on a spring of rest
// length 1, k = 100 N/m, c = 2 N s/m, no gravity or drag; one sphere far away at rest.
// `particles`: the cloth's size; beyond the two spring particles every one is fixed and parked
// far away without springs (the course-size retry gives course-size code its 625 particles).
System springSystem(float dt, int particles = 2) {
  System s;
  s.cloth.particles = makeParticles<float>(particles, 1.0f);
  for (int i = 0; i < particles; ++i)
    if (i != 1) setMass(s.cloth.particles, i, 0.0f);
  for (int i = 2; i < particles; ++i)
    s.cloth.particles.position.col(i) = Vec4<float>(50.0f + float(i), -50, 0, 1);
  s.cloth.particles.position.col(0) = Vec4<float>(0, 0, 0, 1);
  s.cloth.particles.position.col(1) = Vec4<float>(1.2f, 0, 0, 1);
  s.cloth.springs.push_back({0, 1, 1.0f, SpringType::Structural});
  s.cloth.spring_coef = 100;
  s.cloth.damper_coef = 2;
  addSphere(s.spheres, Vec4<float>(100, 100, 0, 1), 0.5f, 1000.0f);
  s.dt = dt;
  s.course_size = particles > 2;
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

// The stage record's system (stages.h): the random state of case 0 with another seed and no
// contact, so that simulateOneStep() only sets accelerations, generic nonlinear functions of the
// state (springs, damper, drag), at the step stages::kStageStep.
System stageSystem(std::uint64_t seed, bool course_size, int edition) {
  System s = course_size ? courseSystem(seed + 1000, edition) : randomSystem(seed + 1000);
  s.contact = false;
  s.dt = stages::kStageStep;
  return s;
}

void addSystem(probe::ProbeMessage& m, int k, const System& s, std::int64_t steps,
               std::int64_t stride) {
  const auto at = [k](const char* name) { return key::perCase(name, k); };
  m.floats[at(key::kClothPos)] = util::flat(s.cloth.particles.position);
  m.floats[at(key::kClothVel)] = util::flat(s.cloth.particles.velocity);
  m.floats[at(key::kClothMass)] = util::flat(s.cloth.particles.mass);
  m.floats[at(key::kSpherePos)] = util::flat(s.spheres.particles.position);
  m.floats[at(key::kSphereVel)] = util::flat(s.spheres.particles.velocity);
  m.floats[at(key::kSphereMass)] = util::flat(s.spheres.particles.mass);
  m.floats[at(key::kSphereRadius)] = s.spheres.radius;
  for (const auto& spring : s.cloth.springs) {
    m.ints[at(key::kSpringStart)].push_back(spring.start);
    m.ints[at(key::kSpringEnd)].push_back(spring.end);
    m.ints[at(key::kSpringType)].push_back(static_cast<std::int64_t>(spring.type));
    m.floats[at(key::kSpringRest)].push_back(spring.rest_length);
  }
  m.floats[at(key::kParams)] = {s.cloth.spring_coef, s.cloth.damper_coef, s.viscous, s.gravity[0],
                                s.gravity[1],        s.gravity[2],        0.0f,      0.8f};
  m.ints[at(key::kFlags)] = {s.sphere_gravity ? 1 : 0, s.contact ? 1 : 0, 0};
  m.floats[at(key::kDt)] = {s.dt};
  m.ints[at(key::kSteps)] = {steps};
  m.ints[at(key::kStride)] = {stride};
}

System answerSystem(const probe::ProbeMessage& a, int k, const System& like) {
  const auto at = [k](const char* name) { return key::perCase(name, k); };
  System s = like;
  s.cloth.particles.position = util::matrix(a.f(at(key::kClothPos)), like.cloth.particles.size());
  s.cloth.particles.velocity = util::matrix(a.f(at(key::kClothVel)), like.cloth.particles.size());
  s.spheres.particles.position = util::matrix(a.f(at(key::kSpherePos)), like.spheres.size());
  s.spheres.particles.velocity = util::matrix(a.f(at(key::kSphereVel)), like.spheres.size());
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
double trajectoryError(const std::vector<float>& trajectory, double dt, std::int64_t stride,
                       int particles = 2) {
  const DampedOscillator o = springOscillator();
  double worst = 0;
  const std::size_t per_record = 4 * std::size_t(particles);
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
  const std::string bodies =
      s.course_size
          ? "the course's " + std::to_string(s.cloth.particles.size()) +
                "-particle cloth (corners fixed, k_s = 500, k_d = 5, positions and velocities "
                "randomly perturbed) and its " +
                std::to_string(s.spheres.size()) + " sphere(s) under gravity"
          : "a 4 x 4 cloth (corners fixed, k_s = 500, k_d = 5, positions and velocities randomly "
            "perturbed) and 2 spheres under gravity, sphere 0 pressing on cloth particle 5 "
            "(sphere-cloth contact inside simulateOneStep)";
  return bodies + ", dt = " + util::num(s.dt) + "; first free cloth particle (index 1): x " +
         util::vec3(s.cloth.particles.position.col(1)) + ", v " +
         util::vec3(s.cloth.particles.velocity.col(1)) + "; sphere 0: x " +
         util::vec3(s.spheres.particles.position.col(0)) + ", v " +
         util::vec3(s.spheres.particles.velocity.col(0));
}

// The checks of an integrator probe, in report order (the names are the tests' names).
enum class Check { OneStep, EveryBody, DeltaTime, Backups, Order, Stability };
struct CheckInfo {
  Check check;
  const char* name;
  double weight;
  bool needs_backup;  // only for methods that back up the state (not explicit)
};
constexpr CheckInfo kChecks[] = {
    {Check::OneStep, "one step on a random state", 2, false},
    {Check::EveryBody, "every body integrated", 1, false},
    {Check::DeltaTime, "deltaTime unchanged", 1, false},
    {Check::Backups, "backups are copies", 1, true},
    {Check::Order, "convergence order", 1, false},
    {Check::Stability, "stable below the stability limit", 1, false},
};

// One integrator probe: the systems sent and the child's answer.
struct IntegratorRun {
  int index = 0;
  Method method = Method::Explicit;
  std::string stub;
  double rel = 0;
  System random;
  std::vector<double> dts;
  std::vector<std::int64_t> strides;
  double end_time = 1.0;
  int spring_particles = 2;  // cloth size of the spring systems
  double limit = 0, stable_dt = 0;
  int stable_case = 0;
  int stage_case = 0;  // the contact-free case whose stages are recorded (stages.h)
  probe::ProbeMessage answer;
  System start;  // the random state after the simulateOneStep() that precedes integrate()
  System actual, expected;
  double distance = 0;  // actual against the course method after one step
};

// Builds the request for `index` (small systems, or the course's cloth when `course_size`) and runs
// it. Returns false with `failure` set when the child did not answer.
bool runIntegrator(const ProbeContext& context, int index, bool course_size, IntegratorRun& run,
                   util::ProbeFailure& failure, ChildRun& child, bool log) {
  run.index = index;
  run.method = kMethods[index];
  run.stub = stubName(integratorStub(index));
  run.rel = context.rubric.tolerances.integrate_rel;
  const std::uint64_t seed = context.seed + 7 * std::uint64_t(index);
  run.random = course_size ? courseSystem(seed, context.edition) : randomSystem(seed);
  run.spring_particles = course_size ? run.random.cloth.particles.size() : 2;
  switch (run.method) {
    case Method::Explicit:
    case Method::Implicit:
      run.dts = {0.002, 0.001, 0.0005, 0.00025};
      break;
    case Method::Midpoint:
      run.dts = {0.01, 0.005, 0.0025, 0.00125};
      break;
    default:
      run.dts = {0.1, 0.05, 0.025};
      run.end_time = 2.0;
      break;
  }
  run.limit = stabilityLimit(run.method);
  run.stable_dt = 0.5 * run.limit;
  const std::int64_t stable_steps = static_cast<std::int64_t>(20.0 / run.stable_dt);

  // Case 0: one step on the random state. Cases 1..: the convergence ladder. Last: stability.
  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kIntegrate;
  request.ints[key::kMethod] = {index};
  addSystem(request, 0, run.random, 1, 0);
  for (std::size_t k = 0; k < run.dts.size(); ++k) {
    const std::int64_t steps = std::llround(run.end_time / run.dts[k]);
    const std::int64_t stride = std::max<std::int64_t>(1, steps / 50);
    run.strides.push_back(stride);
    addSystem(request, int(k) + 1, springSystem(float(run.dts[k]), run.spring_particles), steps,
              stride);
  }
  run.stable_case = int(run.dts.size()) + 1;
  const std::int64_t stable_stride = std::max<std::int64_t>(1, stable_steps / 100);
  addSystem(request, run.stable_case, springSystem(float(run.stable_dt), run.spring_particles),
            stable_steps, stable_stride);
  // Last: the stage record, one step of a contact-free random state (stages.h).
  run.stage_case = run.stable_case + 1;
  addSystem(request, run.stage_case, stageSystem(seed, course_size, context.edition), 1, 0);
  request.ints[key::perCase(key::kRecordStages, run.stage_case)] = {1};
  request.ints[key::kCases] = {run.stage_case + 1};

  ProbeContext quiet = context;
  if (!log) quiet.limits.log = nullptr;  // a crash that the course-size retry may still grade
  const auto answer = util::runGroup(quiet, context.probe, integratorFolder(index, course_size),
                                     request, failure, &child);
  if (!answer) return false;
  run.answer = *answer;
  run.actual = answerSystem(run.answer, 0, run.random);
  run.expected = stepped(run.random, clothrefStep(run.method));
  run.start = run.random;
  simulate(run.start);  // contacts move bodies before integrate() does
  run.distance = distance(run.actual, run.expected);
  return true;
}

// The accepted variants of the method that the rubric switches on: (description, step).
std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method) {
  std::vector<std::pair<std::string, Step>> accepted;
  if (method == Method::Explicit && rubric.accepts("explicit-as-symplectic"))
    accepted.push_back({"explicit written as symplectic Euler (v first, then x with the new v)",
                        clothrefStep(Method::Symplectic)});
  if (method == Method::Implicit && rubric.accepts("implicit-corrector-v-new"))
    accepted.push_back({"the corrector's position uses the new velocity",
                        variantStep(Method::Implicit, Variant::ImplicitVNew)});
  if ((method == Method::Implicit || method == Method::Midpoint) &&
      rubric.accepts("symplectic-predictor"))
    accepted.push_back(
        {"the predictor written as symplectic Euler (v first, then x with the new v)",
         variantStep(method, Variant::SymplecticPredictor)});
  return accepted;
}

// `text` without its comments (a `// step 1/2` comment is not integer division).
std::string withoutComments(const std::string& text) {
  std::string out;
  for (std::size_t k = 0; k < text.size(); ++k) {
    if (text.compare(k, 2, "//") == 0) {
      k = text.find('\n', k);
      if (k == std::string::npos) break;
      out += '\n';
    } else if (text.compare(k, 2, "/*") == 0) {
      k = text.find("*/", k + 2);
      if (k == std::string::npos) break;
      ++k;
      out += ' ';
    } else {
      out += text[k];
    }
  }
  return out;
}

// The body of `stub` in the student's source (from its name to the matching brace, comments
// removed), or "".
std::string stubSource(const ProbeContext& context, const std::string& stub) {
  auto file = context.sources.find("integrator.cpp");
  if (file == context.sources.end()) return "";
  const std::string text = withoutComments(file->second);
  const std::size_t at = text.find(stub + "(");
  if (at == std::string::npos) return "";
  std::size_t open = text.find('{', at);
  if (open == std::string::npos) return "";
  int depth = 0;
  for (std::size_t k = open; k < text.size(); ++k) {
    if (text[k] == '{') ++depth;
    if (text[k] == '}' && --depth == 0) return text.substr(open, k - open + 1);
  }
  return text.substr(open);
}

// `1 / 2` or `1 / 6` written with two integer literals (not 1.0 / 2, 1 / 2.0f).
bool hasIntegerDivision(const std::string& source, int denominator) {
  const std::regex pattern("(^|[^.\\w])1\\s*/\\s*" + std::to_string(denominator) + "(?![.\\w])");
  return std::regex_search(source, pattern);
}

// RK4's final update fitted as x0 + sum w_k kx_k (and v0 + sum u_k kv_k) over the cloth, with the
// stages of the course method. Empty when the update is no such sum.
struct WeightFit {
  bool fits = false;
  Eigen::Vector4d w = Eigen::Vector4d::Zero();
};
std::pair<WeightFit, WeightFit> fitRk4Weights(const System& random, const System& actual) {
  System s = random;
  std::vector<Mat4X<float>> kx, kv;
  simulate(s);
  const Mat4X<float> x0 = s.cloth.particles.position, v0 = s.cloth.particles.velocity;
  const Mat4X<float> sx0 = s.spheres.particles.position, sv0 = s.spheres.particles.velocity;
  const float stage[] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    kx.push_back(s.cloth.particles.velocity * s.dt);
    kv.push_back(s.cloth.particles.acceleration * s.dt);
    const Mat4X<float> skx = s.spheres.particles.velocity * s.dt;
    const Mat4X<float> skv = s.spheres.particles.acceleration * s.dt;
    if (k < 3) {
      s.cloth.particles.position = x0 + kx.back() * stage[k];
      s.cloth.particles.velocity = v0 + kv.back() * stage[k];
      s.spheres.particles.position = sx0 + skx * stage[k];
      s.spheres.particles.velocity = sv0 + skv * stage[k];
    }
  }
  const auto fit = [](const std::vector<Mat4X<float>>& k, const Mat4X<float>& start,
                      const Mat4X<float>& end) {
    WeightFit result;
    const Eigen::Index n = start.size();
    Eigen::MatrixXd a(n, 4);
    for (int j = 0; j < 4; ++j)
      a.col(j) = Eigen::Map<const Eigen::VectorXf>(k[std::size_t(j)].data(), n).cast<double>();
    const Eigen::VectorXd b = (Eigen::Map<const Eigen::VectorXf>(end.data(), n) -
                               Eigen::Map<const Eigen::VectorXf>(start.data(), n))
                                  .cast<double>();
    result.w = a.colPivHouseholderQr().solve(b);
    const double scale = 1e-12 + a.cwiseAbs().rowwise().sum().norm();
    result.fits = result.w.allFinite() && (a * result.w - b).norm() <= 1e-4 * scale;
    return result;
  };
  return {fit(kx, x0, actual.cloth.particles.position),
          fit(kv, v0, actual.cloth.particles.velocity)};
}

bool near(const Eigen::Vector4d& w, const Eigen::Vector4d& target) {
  return (w - target).cwiseAbs().maxCoeff() < 1e-3;
}

// The known mistakes of `method` that change the first step, as (cause id, its step): the
// student's numbers equal to one of these name that cause.
std::vector<std::pair<std::string, Step>> oneStepSignatures(Method method) {
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
    signatures.push_back({"per-body-loop", variantStep(method, Variant::PerBody)});
  }
  if (method == Method::Midpoint) {
    signatures.push_back({"midpoint-full-step", clothrefStep(Method::Implicit)});
    signatures.push_back(
        {"no-reevaluation", variantStep(method, Variant::NoReevaluationHalfVelocity)});
    // simulateOneStep() at the unchanged start state; a contact in it is applied a second time,
    // so this is not explicit Euler's result.
    signatures.push_back({"no-reevaluation", variantStep(method, Variant::ZeroHalfStep)});
  }
  if (method == Method::Rk4) {
    signatures.push_back({"integer-division-rk4", variantStep(method, Variant::RkIntDivision)});
    signatures.push_back({"rk4-mixed-increments", variantStep(method, Variant::RkMixedFinal)});
    signatures.push_back({"rk4-mixed-increments", variantStep(method, Variant::RkK4xInVelocity)});
    for (int k = 0; k < 3; ++k)
      signatures.push_back({"rk4-mixed-increments", variantStep(method, Variant::RkMixedStage, k)});
    signatures.push_back(
        {"rk4-stage-not-from-backup", variantStep(method, Variant::RkStageFromCurrent)});
    signatures.push_back(
        {"rk4-stage-from-wrong-increment", variantStep(method, Variant::RkStageFromNewVelocity)});
    signatures.push_back({"rk4-stages-discarded", variantStep(method, Variant::RkStagesDiscarded)});
  }
  return signatures;
}

// RK4 whose first step matches no signature: right stages, other weights? Fits both updates on
// the course's stages, says what they fit in `output`, and returns the cause ("" = none).
std::string rk4WeightCause(const IntegratorRun& run, const std::string& source,
                           std::string& output) {
  const auto [x, v] = fitRk4Weights(run.random, run.actual);
  const Eigen::Vector4d course(1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6);
  const Eigen::Vector4d zero = Eigen::Vector4d::Zero();
  const bool missing_term = (x.fits && near(x.w, zero)) || (v.fits && near(v.w, zero)) ||
                            (x.fits && x.w[0] == 0 && near(x.w, {0, 1.0 / 3, 1.0 / 3, 0}));
  for (const auto& [what, fit] : {std::pair{"position", x}, std::pair{"velocity", v}})
    if (fit.fits && !near(fit.w, course))
      output += "\nYour " + std::string(what) + " update fits x0 + " + util::num(fit.w[0]) +
                " k1 + " + util::num(fit.w[1]) + " k2 + " + util::num(fit.w[2]) + " k3 + " +
                util::num(fit.w[3]) + " k4 (the course: 1/6, 1/3, 1/3, 1/6).\n";
  // A weight of zero where the course has 1/6 is integer division only when the source has it.
  if (missing_term && hasIntegerDivision(source, 6)) return "integer-division-rk4";
  if ((x.fits && !near(x.w, course)) || (v.fits && !near(v.w, course))) return "rk4-wrong-weights";
  return "";
}

// Likely causes of a wrong first step: the numeric signatures of the known mistakes, refined by
// the simulateOneStep() count and the source (integer literals divided). Adds notes to `output`;
// a per-body loop suggested only by the call count is a guess, in `guesses`.
std::vector<std::string> diagnoseOneStep(const ProbeContext& context, const IntegratorRun& run,
                                         std::string& output, std::vector<std::string>& guesses) {
  const Method method = run.method;
  const std::vector<std::pair<std::string, Step>> signatures = oneStepSignatures(method);
  std::vector<std::string> ids;
  const auto add = [&](const std::string& id) {
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  };
  const auto drop = [&](const std::string& id) {
    ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
  };
  for (const auto& [id, step] : signatures)
    if (distance(run.actual, stepped(run.random, step)) <= 10 * run.rel) add(id);
  // Nothing added by the final update is integer division only when the source divides 1 by 6.
  const std::string source = stubSource(context, run.stub);
  if (std::find(ids.begin(), ids.end(), "integer-division-rk4") != ids.end() && !source.empty() &&
      !hasIntegerDivision(source, 6)) {
    drop("integer-division-rk4");
    add("rk4-wrong-weights");
  }

  if (ids.empty() && method == Method::Rk4) {
    const std::string id = rk4WeightCause(run, source, output);
    if (!id.empty()) add(id);
  }
  const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
  if (!after.empty() && after[0] != run.random.dt) add("deltatime-mutated");

  // simulateOneStep calls during integrate: 0 (explicit), 1 (implicit, midpoint), 3 (RK4).
  const auto& calls_out = run.answer.i(key::perCase(key::kCalls, 0));
  const std::int64_t calls = calls_out.empty() ? -1 : calls_out[0];
  const std::int64_t expected_calls = method == Method::Rk4        ? 3
                                      : method == Method::Explicit ? 0
                                                                   : 1;
  if (calls >= 0 && calls != expected_calls)
    output += "\nsimulateOneStep() was called " + std::to_string(calls) +
              " times during integrate(); the course method calls it " +
              std::to_string(expected_calls) + " times.\n";
  if (calls >= 0 && calls < expected_calls) {
    drop("no-reevaluation");
    add("no-reevaluation");
  } else if (method == Method::Midpoint && calls == expected_calls &&
             distance(run.actual,
                      stepped(run.random, variantStep(method, Variant::ZeroHalfStep))) <=
                 10 * run.rel) {
    // simulateOneStep() ran at the start state: the half step added nothing, or was never written
    // back. Integer division only when the source divides 1 by 2.
    if (hasIntegerDivision(source, 2)) {
      drop("no-reevaluation");
      add("integer-division-half");
    }
  }
  // RK4 that called simulateOneStep() three times and then kept only k1 gives explicit Euler's
  // numbers: the stages were discarded, not skipped.
  if (method == Method::Rk4 && calls == expected_calls &&
      std::find(ids.begin(), ids.end(), "rk4-stages-discarded") != ids.end())
    drop("no-reevaluation");
  if (calls >= 0 && calls < expected_calls) drop("rk4-stages-discarded");
  // A per-body loop calls simulateOneStep() once per body and stage.
  if (calls > expected_calls && expected_calls > 0 && calls % expected_calls == 0 &&
      std::find(ids.begin(), ids.end(), "per-body-loop") == ids.end() && ids.empty())
    guesses.push_back("per-body-loop");
  return ids;
}

TestResult checkOneStep(const ProbeContext& context, const IntegratorRun& run) {
  TestResult one = makeTest(run.stub, kChecks[0].name, kChecks[0].weight);
  std::string matched_variant;
  for (const auto& [what, step] : acceptedVariants(context.rubric, run.method))
    if (distance(run.actual, stepped(run.random, step)) <= run.rel) matched_variant = what;
  if (run.distance <= run.rel || !matched_variant.empty()) {
    one.fraction = 1;
    one.output = matched_variant.empty()
                     ? "Matches the course method after one step (every body, x and v)."
                     : "Matches an accepted variant: " + matched_variant + ".";
    return one;
  }
  const System& e = run.expected;
  const System& a = run.actual;
  const util::Tolerance tolerance{run.rel, run.rel};
  one.output = "State: " + systemText(run.random) +
               ".\n\nAfter one step (expected: the course method's):\n\n" +
               util::compareVectors("cloth particle 1, x", e.cloth.particles.position.col(1),
                                    a.cloth.particles.position.col(1), tolerance, "m") +
               util::compareVectors("cloth particle 1, v", e.cloth.particles.velocity.col(1),
                                    a.cloth.particles.velocity.col(1), tolerance, "m/s") +
               util::compareVectors("sphere 0, x", e.spheres.particles.position.col(0),
                                    a.spheres.particles.position.col(0), tolerance, "m");
  std::vector<std::string> guesses;
  const std::vector<std::string> ids = diagnoseOneStep(context, run, one.output, guesses);
  for (const auto& id : ids) one.addCause(id);
  if (ids.empty()) {
    for (const auto& id : guesses) one.addCause(id, false);
    one.addCause("unknown", false);
  }
  return one;
}

// What the one-step check named as likely first, the mistake the other checks of the stub follow
// from; "unknown" when it named none.
std::string firstLikelyCause(const TestResult& one) {
  for (const Cause& cause : one.causes)
    if (cause.likely) return cause.id;
  return "unknown";
}

// Each body the course method moves must move.
TestResult checkEveryBody(const ProbeContext& /*context*/, const IntegratorRun& run,
                          const TestResult& one) {
  TestResult all = makeTest(run.stub, kChecks[1].name, kChecks[1].weight);
  std::string stuck;
  if (distance(run.expected, run.start, 0) > run.rel &&
      distance(run.actual, run.start, 0) <= run.rel)
    stuck += "the cloth (particles[0])";
  if (distance(run.expected, run.start, 1) > run.rel &&
      distance(run.actual, run.start, 1) <= run.rel)
    stuck += std::string(stuck.empty() ? "" : " and ") + "the spheres (particles[1])";
  all.fraction = stuck.empty() ? 1 : 0;
  if (stuck.empty()) {
    all.output = "Every Particles* in the vector was integrated.";
    return all;
  }
  all.output = "After one step " + stuck +
               " did not move at all, although the course method moves it (state: " +
               systemText(run.random) + ").\n\n";
  const bool only_spheres = stuck.find("cloth") == std::string::npos;
  // Nothing moved: the one-step diagnosis says why (integer division, ...), when it has one.
  const std::string first = firstLikelyCause(one);
  const std::string id = only_spheres ? "only-first-body" : first;
  all.addCause(id, id != "unknown");
  return all;
}

TestResult checkDeltaTime(const ProbeContext& /*context*/, const IntegratorRun& run) {
  TestResult t = makeTest(run.stub, kChecks[2].name, kChecks[2].weight);
  const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
  const float dt_after = after.empty() ? std::nanf("") : after[0];
  t.fraction = dt_after == run.random.dt ? 1 : 0;
  t.output = t.fraction == 1 ? "The global deltaTime is unchanged after integrate()."
                             : "deltaTime was " + util::num(run.random.dt) +
                                   " before integrate() and " + util::num(dt_after) + " after.\n";
  if (t.fraction == 0) t.addCause("deltatime-mutated");
  return t;
}

TestResult checkBackups(const ProbeContext& /*context*/, const IntegratorRun& run) {
  TestResult t = makeTest(run.stub, kChecks[3].name, kChecks[3].weight);
  const bool alias =
      distance(run.actual, stepped(run.random, variantStep(run.method, Variant::Alias))) <=
          10 * run.rel &&
      run.distance > run.rel;
  t.fraction = alias ? 0 : 1;
  t.output = alias ? "The result is exactly what a step gives when the backup follows the live "
                     "state (same state as the one-step test).\n"
                   : "The backed-up start state is not changed by the later stages.";
  if (alias) t.addCause("backup-alias");
  return t;
}

TestResult checkOrder(const ProbeContext& context, const IntegratorRun& run,
                      const TestResult& one) {
  TestResult order = makeTest(run.stub, kChecks[4].name, kChecks[4].weight);
  std::vector<double> student_errors, reference_errors;
  for (std::size_t k = 0; k < run.dts.size(); ++k) {
    const std::int64_t steps = std::llround(run.end_time / run.dts[k]);
    student_errors.push_back(
        trajectoryError(run.answer.f(key::perCase(key::kTrajectory, int(k) + 1)), run.dts[k],
                        run.strides[k], run.spring_particles));
    reference_errors.push_back(referenceError(run.method, run.dts[k], steps, run.strides[k]));
  }
  bool usable = true;
  for (double e : student_errors) usable = usable && std::isfinite(e) && e > 0 && e < 1e299;
  const double expected_order = fitOrder(run.dts, reference_errors);
  const double observed = usable ? fitOrder(run.dts, student_errors) : std::nan("");
  order.fraction =
      usable && std::abs(observed - expected_order) <= context.rubric.tolerances.order ? 1 : 0;
  std::string table = "| dt (s) | your max error (m) | course method's |\n|---|---|---|\n";
  for (std::size_t k = 0; k < run.dts.size(); ++k)
    table += "| " + util::num(run.dts[k]) + " | " + util::num(student_errors[k]) + " | " +
             util::num(reference_errors[k]) + " |\n";
  order.output =
      "A unit mass on a damped spring (k = 100 N/m, c = 2 N s/m, rest 1 m, released at 1.2 m), " +
      util::num(run.end_time) + " s against the closed form, at " + std::to_string(run.dts.size()) +
      " step sizes. Observed order " +
      (usable ? util::num(observed) : std::string("not measurable")) + ", the course method's " +
      util::num(expected_order) + " (theory " + std::to_string(kTheoreticalOrder[run.index]) +
      ").\n\n" + table;
  if (order.fraction == 0) {
    const std::string id = one.fraction == 1 ? "wrong-order" : firstLikelyCause(one);
    order.addCause(id, id != "unknown");
  }
  return order;
}

TestResult checkStability(const ProbeContext& /*context*/, const IntegratorRun& run,
                          const TestResult& one) {
  TestResult stable = makeTest(run.stub, kChecks[5].name, kChecks[5].weight);
  const auto& trajectory = run.answer.f(key::perCase(key::kTrajectory, run.stable_case));
  const std::size_t per_record = 4 * std::size_t(run.spring_particles);
  double amplitude = 0;
  for (std::size_t r = 0; r + per_record <= trajectory.size(); r += per_record) {
    const double u = std::abs(double(trajectory[r + 4]) - 1.0);
    amplitude = std::isfinite(u) ? std::max(amplitude, u) : 1e300;
  }
  stable.fraction = amplitude <= 0.3 ? 1 : 0;
  stable.output = "The same spring for 20 s at dt = " + util::num(run.stable_dt) +
                  " s, half the course method's stability limit " + util::num(run.limit) +
                  " s. Largest |stretch| " +
                  (amplitude >= 1e299 ? std::string("not finite") : util::num(amplitude)) +
                  " m (released at 0.2 m; must stay below 0.3 m).\n";
  if (stable.fraction == 0) {
    // The blow-up is a consequence: the one-step finding names the mistake when there is one.
    const std::string first = firstLikelyCause(one);
    const std::string id = one.fraction == 1 || first == "unknown" ? "unstable" : first;
    stable.addCause(id);
  }
  return stable;
}

}  // namespace

std::vector<PlannedTest> integratorChecks(int method) {
  std::vector<PlannedTest> checks;
  for (const CheckInfo& info : kChecks)
    if (!info.needs_backup || kMethods[method] != Method::Explicit)
      checks.push_back({stubName(integratorStub(method)), info.name, info.weight});
  return checks;
}

// The stage explanation (stages.h) of the recorded case, as JSON beside the probe's files when
// the work folder is kept (--keep-work); the report does not show it yet.
void keepStages(const ProbeContext& context, const IntegratorRun& run, bool course_size) {
  stages::StageRecord record;
  if (!context.limits.keep_files ||
      !stages::stageRecordFrom(run.answer, run.stage_case, double(stages::kStageStep), record))
    return;
  const stages::StageFit fit = stages::fitStages(record);
  const stages::StageExplanation explanation =
      stages::explainStages(fit, run.index, stages::sourceHints(stubSource(context, run.stub)));
  std::ofstream(context.work_dir / integratorFolder(run.index, course_size) / "stages.json")
      << stages::stageJson(fit, explanation);
}

std::vector<TestResult> probeIntegrator(const ProbeContext& context, int index) {
  const Method method = kMethods[index];
  IntegratorRun run;
  util::ProbeFailure failure;
  ChildRun child;
  std::string note;  // why the course-size cloth was used
  bool ok = runIntegrator(context, index, false, run, failure, child, false);
  if (!ok && failure.verdict == Verdict::Crashed) {
    // Code written for the course's cloth (e.g. indexing particlesPerEdge into it) crashes on the
    // small probe cloth: grade it on the course's cloth instead, and say so.
    note = "On the 4 x 4 probe cloth the probe process " + child.describe() +
           " (code written for the course's 25 x 25 cloth?), so this stub was graded on the "
           "course's cloth and spheres.\n\n";
    util::ProbeFailure again;
    IntegratorRun course;
    ok = runIntegrator(context, index, true, course, again, child, true);
    if (ok)
      run = std::move(course);
    else
      failure = {again.verdict, "On the 4 x 4 probe cloth: " + failure.text +
                                  "\n\nOn the course's cloth: " + again.text};
  } else if (!ok && context.limits.log) {
    std::lock_guard<std::mutex> lock(context.limits.log->mutex);
    context.limits.log->verdicts.push_back(child.verdict());
  }
  std::vector<TestResult> tests;
  if (!ok) {
    for (const PlannedTest& check : integratorChecks(index))
      tests.push_back(util::failedTest(check, failure.text, {util::guess(failure.causeId())}));
    return tests;
  }
  keepStages(context, run, !note.empty());
  const TestResult one = checkOneStep(context, run);
  tests.push_back(one);
  tests.push_back(checkEveryBody(context, run, one));
  tests.push_back(checkDeltaTime(context, run));
  if (method != Method::Explicit) tests.push_back(checkBackups(context, run));
  tests.push_back(checkOrder(context, run, one));
  tests.push_back(checkStability(context, run, one));
  if (!note.empty())
    for (TestResult& t : tests) t.output = note + t.output;
  return tests;
}

}  // namespace clothref::grader
