#include "grader/grade/probes/collide_cases.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

namespace clothref::grader::contacts {

void collideCourse(State& s, bool sphere_sphere, float restitution, float correction) {
  if (sphere_sphere)
    collide(s.spheres, restitution, correction);
  else
    collide(s.spheres, s.cloth, restitution, correction);
}

namespace {

State baseState(const Edition& course) {
  State s;
  s.cloth.particles = initializeVertex<float>(kN, static_cast<float>(course.cloth_half_extent),
                                              static_cast<float>(course.cloth_height),
                                              static_cast<float>(course.particle_mass));
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)  // parked 50 m below, 3 m apart: nothing touches them
      s.cloth.particles.position.col(i * kN + j) =
          Vec4<float>(-36.0f + 3.0f * float(j), -50.0f, -36.0f + 3.0f * float(i), 1.0f);
  for (int corner : {0, kN - 1, kN * (kN - 1), kN * kN - 1})
    setMass(s.cloth.particles, corner, 0.0f);
  // The accelerations simulateOneStep() leaves before collide: gravity on every free particle
  // (and on the spheres where they have an external force); the course's collide keeps them.
  const Vec4<float> g(float(course.gravity[0]), float(course.gravity[1]), float(course.gravity[2]),
                      0);
  for (int i = 0; i < kN * kN; ++i)
    if (s.cloth.particles.mass[i] != 0) s.cloth.particles.acceleration.col(i) = g;
  for (int k = 0; k < 3; ++k)
    addSphere(s.spheres, Vec4<float>(100.0f * float(k + 1), 100, 0, 1), kRadii[k],
              static_cast<float>(course.sphere_density));
  if (course.sphere_external_force) s.spheres.particles.acceleration.colwise() = g;
  return s;
}

void place(State& s, bool sphere, int index, Vec4<float> x, Vec4<float> v) {
  auto& p = sphere ? s.spheres.particles : s.cloth.particles;
  p.position.col(index) = x;
  p.velocity.col(index) = v;
}
Vec4<float> P(float x, float y, float z) { return Vec4<float>(x, y, z, 1); }
Vec4<float> V(float x, float y, float z) { return Vec4<float>(x, y, z, 0); }

// The check tables (collideChecks()): the names in the enums' order, each check worth 1.
constexpr const char* kClothCheckNames[] = {
    "approaching pair", "separating pair",  "several spheres",  "sphere at index 2",
    "fixed particle",   "deep penetration", "touching exactly", "momentum conserved"};
constexpr const char* kSphereCheckNames[] = {
    "approaching pair", "separating pair",  "three spheres in a chain", "pair without sphere 0",
    "deep penetration", "touching exactly", "unequal masses",           "momentum conserved"};
static_assert(std::size(kClothCheckNames) == kClothMomentum + 1);
static_assert(std::size(kSphereCheckNames) == kSpheresMomentum + 1);

}  // namespace

std::vector<Case> clothCases(const Edition& course) {
  std::vector<Case> cases;
  const auto make = [&](ClothCheck check, std::vector<int> spheres, std::vector<int> particles,
                        const std::function<void(State&)>& setup, bool free_bodies = true) {
    Case c{check, baseState(course), std::move(spheres), std::move(particles), free_bodies};
    setup(c.state);
    cases.push_back(std::move(c));
  };
  make(kClothApproaching, {0}, {312}, [](State& s) {
    place(s, true, 0, P(0.1f, 0.42f, -0.05f), V(0.3f, -2, 0.1f));
    place(s, false, 312, P(0, 0, 0), V(0.2f, 0.5f, -0.1f));
  });
  make(kClothSeparating, {0}, {312}, [](State& s) {
    place(s, true, 0, P(0.05f, 0.45f, 0), V(0, 1.5f, 0.2f));
    place(s, false, 312, P(0, 0, 0), V(0, -0.3f, 0));
  });
  make(kSeveralSpheres, {0, 1, 2}, {100, 200, 312}, [](State& s) {
    place(s, false, 100, P(-5, 0, 0), V(0, 0, 0));
    place(s, false, 200, P(5, 0, 0), V(0, 0.1f, 0));
    place(s, false, 312, P(0, 0, 5), V(0, 0, 0));
    place(s, true, 0, P(-4.95f, 0.4f, 0), V(0, -1, 0));
    place(s, true, 1, P(4.9f, 0.45f, 0.05f), V(0.5f, -1, 0));
    place(s, true, 2, P(0, 0.9f, 5.2f), V(0, -0.5f, 0.3f));
  });
  make(kSphereAtIndex2, {2}, {312}, [](State& s) {
    place(s, true, 2, P(0.3f, 0.85f, 0), V(0, -1, 0));
    place(s, false, 312, P(0, 0, 0), V(0, 0, 0));
  });
  make(
      kFixedParticle, {0}, {0},
      [](State& s) {
        place(s, false, 0, P(0, 0, 0), V(0, 0, 0));
        place(s, true, 0, P(0, 0.45f, 0.05f), V(0.2f, -1, 0));
      },
      false);
  make(kClothDeep, {0}, {312}, [](State& s) {
    place(s, true, 0, P(0.05f, 0.1f, 0.02f), V(0, -1, 0.5f));
    place(s, false, 312, P(0, 0, 0), V(0, 0.2f, 0));
  });
  make(kClothTouching, {0}, {312}, [](State& s) {
    place(s, true, 0, P(0, 0.5f, 0), V(0, -1, 0));
    place(s, false, 312, P(0, 0, 0), V(0, 0, 0));
  });
  return cases;
}

std::vector<Case> sphereCases(const Edition& course) {
  std::vector<Case> cases;
  const auto make = [&](SphereCheck check, std::vector<int> spheres,
                        const std::function<void(State&)>& setup) {
    Case c{check, baseState(course), std::move(spheres), {}, true};
    setup(c.state);
    cases.push_back(std::move(c));
  };
  make(kSpheresApproaching, {0, 1}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(1, 0.2f, 0));
    place(s, true, 1, P(0.9f, 0.1f, 0), V(-0.5f, 0, 0.3f));
  });
  make(kSpheresSeparating, {0, 1}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(-1, 0, 0));
    place(s, true, 1, P(0.95f, 0, 0), V(0.5f, 0, 0));
  });
  make(kChain, {0, 1, 2}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(1, 0, 0));
    place(s, true, 1, P(0.95f, 0, 0), V(0, 0, 0));
    place(s, true, 2, P(2.4f, 0.05f, 0), V(-1, 0, 0));
  });
  make(kPairWithoutSphere0, {1, 2}, [](State& s) {
    place(s, true, 1, P(0, 0, 0), V(0.5f, 0, 0));
    place(s, true, 2, P(1.4f, 0.2f, 0), V(-0.5f, 0, 0.1f));
  });
  make(kSpheresDeep, {0, 1}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(0.3f, 0, 0));
    place(s, true, 1, P(0.3f, 0.05f, 0.02f), V(-0.3f, 0, 0));
  });
  make(kSpheresTouching, {0, 1}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(1, 0, 0));
    place(s, true, 1, P(1, 0, 0), V(0, 0, 0));
  });
  make(kUnequalMasses, {0, 2}, [](State& s) {
    place(s, true, 0, P(0, 0, 0), V(2, 0, 0));
    place(s, true, 2, P(1.45f, 0.1f, 0), V(0, 0, 0));
  });
  return cases;
}

std::vector<PlannedTest> checkTable(bool sphere_sphere) {
  const std::string& stub = stubName(sphere_sphere ? Stub::CollideSpheres : Stub::CollideCloth);
  std::vector<PlannedTest> checks;
  for (const char* name :
       sphere_sphere
           ? std::vector<const char*>(std::begin(kSphereCheckNames), std::end(kSphereCheckNames))
           : std::vector<const char*>(std::begin(kClothCheckNames), std::end(kClothCheckNames)))
    checks.push_back({stub, name, 1});
  return checks;
}

Outcome outcomeOf(const State& s) {
  return {s.cloth.particles.position,     s.cloth.particles.velocity,
          s.spheres.particles.position,   s.spheres.particles.velocity,
          s.cloth.particles.acceleration, s.spheres.particles.acceleration};
}

double distance(const Outcome& a, const Outcome& b) {
  double worst = 0;
  const auto one = [&](const Mat4X<float>& x, const Mat4X<float>& y) {
    for (int k = 0; k < x.size(); ++k) {
      const double d =
          std::abs(double(x.data()[k]) - double(y.data()[k])) / (1 + std::abs(double(y.data()[k])));
      worst = std::isfinite(d) ? std::max(worst, d) : 1e300;
    }
  };
  one(a.cloth_x, b.cloth_x);
  one(a.cloth_v, b.cloth_v);
  one(a.sphere_x, b.sphere_x);
  one(a.sphere_v, b.sphere_v);
  one(a.cloth_a, b.cloth_a);
  one(a.sphere_a, b.sphere_a);
  return worst;
}

Vec4<double> momentum(const State& s, const Outcome& o) {
  Vec4<double> total = Vec4<double>::Zero();
  for (int i = 0; i < s.cloth.particles.size(); ++i)
    total += double(s.cloth.particles.mass[i]) * o.cloth_v.col(i).cast<double>();
  for (int i = 0; i < s.spheres.size(); ++i)
    total += double(s.spheres.particles.mass[i]) * o.sphere_v.col(i).cast<double>();
  return total;
}

double momentumTolerance(const Case& c) {
  double scale = 0;
  for (int q : c.spheres)
    scale += c.state.spheres.particles.mass[q] *
             c.state.spheres.particles.velocity.col(q).cast<double>().norm();
  for (int q : c.particles)
    scale += c.state.cloth.particles.mass[q] *
             c.state.cloth.particles.velocity.col(q).cast<double>().norm();
  return 1e-5 * (1 + scale);
}

bool conserves(const Case& c, const Outcome& after) {
  const Vec4<double> change = momentum(c.state, after) - momentum(c.state, outcomeOf(c.state));
  return change.norm() <= momentumTolerance(c);
}

}  // namespace clothref::grader::contacts
