// The integrator probe's test systems and clothref's step of them (systems.h).
#include "grader/grade/probes/integrate/systems.h"

#include <array>
#include <random>

#include "clothref/analysis/stability.h"
#include "clothref/core/integrator.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/verify/analytic.h"
#include "grader/bridge/probe_protocol.h"
#include "grader/grade/explain/stages/stages.h"
#include "grader/grade/probes/util.h"
#include "grader/grade/submission/edition.h"

namespace clothref::grader::integrators {
namespace {

// Random small perturbations of a cloth at rest: positions by up to 5 cm, free particles'
// velocities up to 0.5 m/s; the spheres' velocities up to 1 m/s.
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

// The course's forces and contact constants, from the edition's record: gravity, drag,
// restitutions and correction factor; and its sphere density (a sphere's mass, density r^3).
float courseConstants(System& s, int edition) {
  const Edition course = courseEdition(edition);
  s.viscous = float(course.viscous_coef);
  s.gravity = Vec4<float>(float(course.gravity[0]), float(course.gravity[1]),
                          float(course.gravity[2]), 0.0f);
  s.restitution_cloth = float(course.restitution_cloth);
  s.restitution_sphere = float(course.restitution_sphere);
  s.correction = float(course.correction);
  return float(course.sphere_density);
}

DampedOscillator springOscillator() {
  DampedOscillator o;
  o.stiffness = 100;
  o.damping = 2;
  o.mass = 1;
  o.displacement0 = 0.2;
  return o;
}

}  // namespace

Method integratorMethod(int index) {
  return index >= 0 && std::size_t(index) < kMethods.size() ? kMethods[std::size_t(index)].method
                                                            : Method::Explicit;
}

System randomSystem(std::uint64_t seed, int edition) {
  System s;
  const float density = courseConstants(s, edition);
  constexpr int n = 4;
  s.cloth.particles = initializeVertex<float>(n, 0.5f, 0.0f, 1.0f);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setMass(s.cloth.particles, corner, 0.0f);
  initializeSpring(s.cloth, n);
  s.cloth.spring_coef = 500;
  s.cloth.damper_coef = 5;
  addSphere(s.spheres, Vec4<float>(3, 1, 0, 1), 0.5f, density);
  addSphere(s.spheres, Vec4<float>(-3, 1.5f, 0.5f, 1), 0.5f, density);
  std::mt19937 rng(static_cast<unsigned>(seed));
  perturb(s, rng);
  // Sphere 0 sinks 10 cm into free particle 5 and keeps moving down onto it.
  s.spheres.particles.position.col(0) =
      s.cloth.particles.position.col(5) + Vec4<float>(0, 0.4f, 0, 0);
  s.spheres.particles.velocity.col(0) = Vec4<float>(0.1f, -1, 0, 0);
  s.contact = true;
  s.sphere_gravity = true;
  s.dt = 0.01f;
  return s;
}

// For code that only runs on the course's cloth (e.g. indexing particlesPerEdge into it).
System courseSystem(std::uint64_t seed, int edition, bool corners_free) {
  const Scene* scene = findBuiltinScene(edition == 2024 ? "course2024" : "course2022");
  const World<float> world = makeWorld<float>(*scene, Method::Explicit);
  System s;
  s.cloth = *world.cloth;
  s.spheres = *world.spheres;
  // An unpinned corner gets a free particle's mass, as the 2024 program's keys do (particle 1,
  // on the first edge between two corners, is free).
  const float free_mass = s.cloth.particles.mass[1];
  if (corners_free)
    for (int i : scene->cloth->fixed) setMass(s.cloth.particles, i, free_mass);
  s.cloth.spring_coef = 500;
  s.cloth.damper_coef = 5;
  std::mt19937 rng(static_cast<unsigned>(seed));
  perturb(s, rng);
  courseConstants(s, edition);
  s.sphere_gravity = true;
  s.dt = 0.01f;
  s.course_size = true;
  return s;
}

// An anchor at the origin, a unit mass at x = 1.2, no gravity or drag; one sphere far away at
// rest. Beyond the two spring particles every one is fixed and parked far away without springs
// (the course-size retry gives course-size code its 625 particles).
System springSystem(float dt, int particles, int edition) {
  System s;
  System course;  // the sphere's density only: the spring system has no gravity, drag or contact
  const float density = courseConstants(course, edition);
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
  addSphere(s.spheres, Vec4<float>(100, 100, 0, 1), 0.5f, density);
  s.dt = dt;
  s.course_size = particles > 2;
  return s;
}

double stabilityLimit(Method method) {
  const DampedOscillator o = springOscillator();
  return theoryLimit(method, {Mode{o.stiffness / o.mass, o.damping / o.mass}}).dt;
}

// No contact, so that simulateOneStep() only sets accelerations, generic nonlinear functions of
// the state (springs, damper, drag).
System stageSystem(std::uint64_t seed, bool course_size, int edition) {
  System s = course_size ? courseSystem(seed + 1000, edition) : randomSystem(seed + 1000, edition);
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
  m.floats[at(key::kParams)] = {s.cloth.spring_coef, s.cloth.damper_coef,  s.viscous,
                                s.gravity[0],        s.gravity[1],         s.gravity[2],
                                s.restitution_cloth, s.restitution_sphere, s.correction};
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

double distance(const System& a, const System& b, int body) {
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

double trajectoryError(const std::vector<float>& trajectory, double dt, std::int64_t stride,
                       int particles) {
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

}  // namespace clothref::grader::integrators
