// Spheres::collide(Cloth*) and Spheres::collide(): crafted contacts (approaching, separating,
// several spheres, a sphere at an index other than 0, a fixed particle, deep penetration,
// touching exactly, unequal masses) compared with clothref's contact code, plus momentum.
// Three spheres are added once; unused ones and the rest of the cloth are parked far away, so
// each case touches only the bodies it names and the loop order cannot matter.
#include <functional>
#include <iterator>
#include <set>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
namespace {

constexpr int kN = 25;
const float kRadii[] = {0.5f, 0.5f, 1.0f};

enum class ContactMistake {
  None,
  NoApproachCheck,
  RestitutionFull,
  CorrectionSphereOnly,
  CorrectionOtherOnly,
  NoCorrection,
  FixedMassless,
  FirstSphereOnly,
  NormalSign,
  TouchingSkipped,
  RestitutionZero,
  RestitutionOne,
  PairTwice,
  ImpulseNotDivided
};

struct State {
  Cloth<float> cloth;
  Spheres<float> spheres;
};

// One contact in the course's form with one mistake switched on. a = sphere i, b = body j.
void contact(Particles<float>& a, int i, Particles<float>& b, int j, float reach, float e,
             ContactMistake m) {
  Vec4<float> n = a.position.col(i) - b.position.col(j);
  if (m == ContactMistake::NormalSign) n = -n;
  const float penetration = reach - n.norm();
  if (penetration < 0 || (m == ContactMistake::TouchingSkipped && penetration <= 0)) return;
  n.normalize();
  if (m == ContactMistake::RestitutionZero) e = 0;
  if (m == ContactMistake::RestitutionOne) e = 1;
  const Vec4<float> relative = a.velocity.col(i) - b.velocity.col(j);
  const float approach = relative.dot(n);
  if (approach < 0 || m == ContactMistake::NoApproachCheck) {
    if (m == ContactMistake::FixedMassless) {
      // The textbook mass formula with mass 0 meaning massless.
      const float ma = a.mass[i], mb = b.mass[j];
      const Vec4<float> ua = n * a.velocity.col(i).dot(n), ub = n * b.velocity.col(j).dot(n);
      const Vec4<float> va = (ma * ua + mb * ub + mb * e * (ub - ua)) / (ma + mb);
      const Vec4<float> vb = (ma * ua + mb * ub + ma * e * (ua - ub)) / (ma + mb);
      a.velocity.col(i) += va - ua;
      b.velocity.col(j) += vb - ub;
    } else {
      const Vec4<float> u =
          m == ContactMistake::RestitutionFull ? relative : Vec4<float>(n * approach);
      const Vec4<float> impulse =
          m == ContactMistake::ImpulseNotDivided
              ? Vec4<float>(-(1 + e) * u)
              : Vec4<float>((-(1 + e) * u) / (b.inverse_mass[j] + a.inverse_mass[i]));
      a.velocity.col(i) += impulse * a.inverse_mass[i];
      b.velocity.col(j) -= impulse * b.inverse_mass[j];
    }
  }
  if (m == ContactMistake::NoCorrection) return;
  const Vec4<float> c = (penetration * n) * 0.15f;
  if (m != ContactMistake::CorrectionOtherOnly) a.position.col(i) += c;
  if (m != ContactMistake::CorrectionSphereOnly) b.position.col(j) -= c;
}

void collideVariant(State& s, bool sphere_sphere, float e, ContactMistake m) {
  auto& sp = s.spheres.particles;
  const int count = m == ContactMistake::FirstSphereOnly ? 1 : s.spheres.size();
  if (!sphere_sphere) {
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < s.cloth.particles.size(); ++j)
        contact(sp, i, s.cloth.particles, j, s.spheres.radius[i], e, m);
    return;
  }
  for (int i = 0; i < count; ++i)
    for (int j = m == ContactMistake::PairTwice ? 0 : i + 1; j < s.spheres.size(); ++j)
      if (j != i) contact(sp, i, sp, j, s.spheres.radius[i] + s.spheres.radius[j], e, m);
}

State baseState(int edition) {
  State s;
  s.cloth.particles = initializeVertex<float>(kN, 2.0f, edition == 2024 ? 1.0f : 0.0f, 1.0f);
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)  // parked 50 m below, 3 m apart: nothing touches them
      s.cloth.particles.position.col(i * kN + j) =
          Vec4<float>(-36.0f + 3.0f * float(j), -50.0f, -36.0f + 3.0f * float(i), 1.0f);
  for (int corner : {0, kN - 1, kN * (kN - 1), kN * kN - 1})
    setMass(s.cloth.particles, corner, 0.0f);
  for (int k = 0; k < 3; ++k)
    addSphere(s.spheres, Vec4<float>(100.0f * float(k + 1), 100, 0, 1), kRadii[k], 1000.0f);
  return s;
}

// Rows of the check tables (checkTable()): one case each, then momentum over them all.
enum ClothCheck {
  kClothApproaching,
  kClothSeparating,
  kSeveralSpheres,
  kSphereAtIndex2,
  kFixedParticle,
  kClothDeep,
  kClothTouching,
  kClothMomentum
};
enum SphereCheck {
  kSpheresApproaching,
  kSpheresSeparating,
  kChain,
  kPairWithoutSphere0,
  kSpheresDeep,
  kSpheresTouching,
  kUnequalMasses,
  kSpheresMomentum
};

struct Case {
  int check;  // a row of the check table
  State state;
  std::vector<int> spheres, particles;  // the bodies the case places (for the report)
  bool free_bodies = true;              // momentum must be conserved
};

void place(State& s, bool sphere, int index, Vec4<float> x, Vec4<float> v) {
  auto& p = sphere ? s.spheres.particles : s.cloth.particles;
  p.position.col(index) = x;
  p.velocity.col(index) = v;
}
Vec4<float> P(float x, float y, float z) { return Vec4<float>(x, y, z, 1); }
Vec4<float> V(float x, float y, float z) { return Vec4<float>(x, y, z, 0); }

std::vector<Case> clothCases(int edition) {
  std::vector<Case> cases;
  const auto make = [&](ClothCheck check, std::vector<int> spheres, std::vector<int> particles,
                        const std::function<void(State&)>& setup, bool free_bodies = true) {
    Case c{check, baseState(edition), std::move(spheres), std::move(particles), free_bodies};
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

std::vector<Case> sphereCases(int edition) {
  std::vector<Case> cases;
  const auto make = [&](SphereCheck check, std::vector<int> spheres,
                        const std::function<void(State&)>& setup) {
    Case c{check, baseState(edition), std::move(spheres), {}, true};
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

struct Outcome {
  Mat4X<float> cloth_x, cloth_v, sphere_x, sphere_v;
};

Outcome outcomeOf(const State& s) {
  return {s.cloth.particles.position, s.cloth.particles.velocity, s.spheres.particles.position,
          s.spheres.particles.velocity};
}

// Largest |a - b| / (1 + |b|) over every value (NaN counts as infinitely far).
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

// The check tables (collideChecks()): the names in the enums' order, each check worth 1.
constexpr const char* kClothCheckNames[] = {
    "approaching pair", "separating pair",  "several spheres",  "sphere at index 2",
    "fixed particle",   "deep penetration", "touching exactly", "momentum conserved"};
constexpr const char* kSphereCheckNames[] = {
    "approaching pair", "separating pair",  "three spheres in a chain", "pair without sphere 0",
    "deep penetration", "touching exactly", "unequal masses",           "momentum conserved"};
static_assert(std::size(kClothCheckNames) == kClothMomentum + 1);
static_assert(std::size(kSphereCheckNames) == kSpheresMomentum + 1);

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

std::vector<TestResult> probeContacts(const ProbeContext& context, bool sphere_sphere) {
  const std::vector<PlannedTest> checks = checkTable(sphere_sphere);
  const float e = sphere_sphere ? 0.8f : 0.0f;
  const double rel = context.rubric.tolerances.collide_rel;
  std::vector<Case> cases =
      sphere_sphere ? sphereCases(context.edition) : clothCases(context.edition);
  probe::ProbeMessage request;
  const char* group_name = sphere_sphere ? group::kCollideSpheres : group::kCollideCloth;
  request.texts[key::kGroup] = group_name;
  request.ints[key::kCases] = {static_cast<std::int64_t>(cases.size())};
  request.floats[key::kSphereRadius] = std::vector<float>(std::begin(kRadii), std::end(kRadii));
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const int n = static_cast<int>(k);
    const State& s = cases[k].state;
    request.floats[key::perCase(key::kClothPos, n)] = util::flat(s.cloth.particles.position);
    request.floats[key::perCase(key::kClothVel, n)] = util::flat(s.cloth.particles.velocity);
    request.floats[key::perCase(key::kClothMass, n)] = util::flat(s.cloth.particles.mass);
    request.floats[key::perCase(key::kSpherePos, n)] = util::flat(s.spheres.particles.position);
    request.floats[key::perCase(key::kSphereVel, n)] = util::flat(s.spheres.particles.velocity);
    request.floats[key::perCase(key::kSphereMass, n)] = util::flat(s.spheres.particles.mass);
  }
  util::ProbeFailure failure;
  const auto answer = util::runGroup(context, context.probe, group_name, request, failure);
  std::vector<std::pair<ContactMistake, const char*>> signatures = {
      {ContactMistake::NoApproachCheck, "no-approach-check"},
      {ContactMistake::RestitutionFull, "restitution-full-velocity"},
      {ContactMistake::CorrectionSphereOnly, "correction-one-body"},
      {ContactMistake::CorrectionOtherOnly, "correction-one-body"},
      {ContactMistake::NoCorrection, "no-position-correction"},
      {ContactMistake::FirstSphereOnly, "first-sphere-only"},
      {ContactMistake::NormalSign, "collision-normal-sign"},
      {ContactMistake::TouchingSkipped, "touching-skipped"},
      {ContactMistake::ImpulseNotDivided, "wrong-mass-split"}};
  // coefRestitution overwritten (e = 0 or 1); a case where it cannot matter is skipped below.
  signatures.push_back({ContactMistake::RestitutionZero, "restitution-ignored"});
  signatures.push_back({ContactMistake::RestitutionOne, "restitution-ignored"});
  if (sphere_sphere) {
    signatures.push_back({ContactMistake::PairTwice, "pair-processed-twice"});
  } else {
    signatures.push_back({ContactMistake::FixedMassless, "fixed-particle-massless"});
  }
  std::vector<TestResult> tests;
  std::string momentum_report;
  bool momentum_ok = true;
  bool momentum_non_finite = false;  // a failed case's momentum is NaN or infinite
  // A mistake is consistent when its simulation gives the student's numbers in every case, the
  // passed ones included; a case may not tell two mistakes apart, the whole probe usually does.
  std::vector<bool> consistent(signatures.size(), bool(answer));
  std::vector<std::size_t> failed;  // indices into tests, causes still to be written
  // NaN or infinity out of the student's call, per case, and whether the case had a body at rest
  // (velocity exactly 0): NaN only where a body rests is a division by its speed.
  std::vector<bool> non_finite(cases.size(), false), at_rest(cases.size(), false);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    for (int q : c.spheres)
      at_rest[k] = at_rest[k] || c.state.spheres.particles.velocity.col(q).isZero(0);
    for (int q : c.particles)
      at_rest[k] = at_rest[k] || c.state.cloth.particles.velocity.col(q).isZero(0);
  }
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    if (!answer) {
      tests.push_back(util::failedTest(checks[c.check], failure.text, {util::guess(failure.causeId())}));
      continue;
    }
    const int n = static_cast<int>(k);
    const Outcome actual{util::matrix(answer->f(key::perCase(key::kClothPos, n)), kN * kN),
                         util::matrix(answer->f(key::perCase(key::kClothVel, n)), kN * kN),
                         util::matrix(answer->f(key::perCase(key::kSpherePos, n)), 3),
                         util::matrix(answer->f(key::perCase(key::kSphereVel, n)), 3)};
    State reference = c.state;
    if (sphere_sphere)
      collide(reference.spheres, e, 0.15f);
    else
      collide(reference.spheres, reference.cloth, e, 0.15f);
    const Outcome expected = outcomeOf(reference);
    if (c.free_bodies) {
      const Vec4<double> before = momentum(c.state, outcomeOf(c.state));
      const Vec4<double> after = momentum(c.state, actual);
      double scale = 0;
      for (int q : c.spheres)
        scale += c.state.spheres.particles.mass[q] *
                 c.state.spheres.particles.velocity.col(q).cast<double>().norm();
      for (int q : c.particles)
        scale += c.state.cloth.particles.mass[q] *
                 c.state.cloth.particles.velocity.col(q).cast<double>().norm();
      if (!((after - before).norm() <= 1e-5 * (1 + scale))) {
        momentum_ok = false;
        momentum_non_finite = momentum_non_finite || !after.allFinite();
        momentum_report += util::compareVectors(
            checks[c.check].check + ": total momentum after your call (expected: as before it)",
            before, after, util::Tolerance{1e-5 * (1 + scale), 0}, "kg m/s");
      }
    }
    TestResult t = util::test(checks[c.check]);
    if (distance(actual, expected) <= rel) {
      t.fraction = 1;
      t.output = "Velocities and positions of every body match.";
      tests.push_back(t);
      continue;
    }
    t.output = "State tried (" +
               std::string(sphere_sphere ? "coefRestitution 0.8" : "coefRestitution 0") +
               ", radii 0.5, 0.5, 1.0, sphere masses 1000 r^3; all other bodies far away):\n\n";
    // Each body the case placed: a line of the text, and a body of the report's picture.
    const auto body = [&](const char* what, const char* short_name, int index,
                          const Mat4X<float>& x0, const Mat4X<float>& v0, float mass, float radius,
                          const Mat4X<float>& xe, const Mat4X<float>& ve, const Mat4X<float>& xa,
                          const Mat4X<float>& va) {
      t.output += "- " + std::string(what) + " " + std::to_string(index) + " (mass " +
                  util::num(mass) + "), before the call: x " + util::vec3(x0.col(index)) +
                  " m, v " + util::vec3(v0.col(index)) + " m/s\n" +
                  util::compareVectors("x after the call", xe.col(index), xa.col(index),
                                       util::Tolerance{rel, rel}, "m", "  ") +
                  util::compareVectors("v after the call", ve.col(index), va.col(index),
                                       util::Tolerance{rel, rel}, "m/s", "  ");
      const auto xyz = [index](const Mat4X<float>& m) {
        return std::array<float, 3>{m(0, index), m(1, index), m(2, index)};
      };
      t.sketch.bodies.push_back({std::string(short_name) + " " + std::to_string(index), xyz(x0),
                                 radius, xyz(v0), xyz(ve), xyz(va)});
    };
    const auto& spheres = c.state.spheres;
    const auto& cloth = c.state.cloth.particles;
    for (int q : c.spheres)
      body("sphere", "sphere", q, spheres.particles.position, spheres.particles.velocity,
           spheres.particles.mass[q], spheres.radius[q], expected.sphere_x, expected.sphere_v,
           actual.sphere_x, actual.sphere_v);
    for (int q : c.particles)
      body("cloth particle", "particle", q, cloth.position, cloth.velocity, cloth.mass[q], 0,
           expected.cloth_x, expected.cloth_v, actual.cloth_x, actual.cloth_v);
    for (std::size_t m = 0; m < signatures.size(); ++m) {
      const auto& [mistake, id] = signatures[m];
      State variant = c.state;
      collideVariant(variant, sphere_sphere, e, mistake);
      const Outcome v = outcomeOf(variant);
      if (distance(v, expected) <= rel) {  // this case cannot tell them apart
        consistent[m] = false;             // ... but the student's numbers are not the course's
        continue;
      }
      const bool matches = distance(actual, v) <= 10 * rel;
      if (!matches) consistent[m] = false;
      if (matches) t.addCause(id);
    }
    non_finite[k] =
        !util::finite(util::flat(actual.sphere_v)) || !util::finite(util::flat(actual.cloth_v)) ||
        !util::finite(util::flat(actual.sphere_x)) || !util::finite(util::flat(actual.cloth_x));
    if (t.causes.empty()) {
      if (non_finite[k])
        t.addCause("non-finite");
      else if (!sphere_sphere && c.check == kFixedParticle &&
               actual.cloth_v.col(0) != c.state.cloth.particles.velocity.col(0))
        t.addCause("fixed-particle-massless");
    }
    failed.push_back(tests.size());
    tests.push_back(t);
  }
  // Passed cases: a mistake whose simulation differs from the course there is refuted.
  if (answer)
    for (std::size_t k = 0; k < cases.size(); ++k) {
      if (!tests[k].passed()) continue;
      for (std::size_t m = 0; m < signatures.size(); ++m) {
        if (!consistent[m]) continue;
        State variant = cases[k].state, reference = cases[k].state;
        collideVariant(variant, sphere_sphere, e, signatures[m].first);
        collideVariant(reference, sphere_sphere, e, ContactMistake::None);
        if (distance(outcomeOf(variant), outcomeOf(reference)) > 10 * rel) consistent[m] = false;
      }
    }
  std::set<std::string> explains_all;
  for (std::size_t m = 0; m < signatures.size(); ++m)
    if (consistent[m]) explains_all.insert(signatures[m].second);
  // Every case with a body at rest went non-finite and no other case did: measured, not guessed.
  bool divides_by_speed = std::find(non_finite.begin(), non_finite.end(), true) != non_finite.end();
  for (std::size_t k = 0; k < cases.size(); ++k)
    if (non_finite[k] != at_rest[k]) divides_by_speed = false;
  for (std::size_t k : failed) {
    TestResult& t = tests[k];
    // One mistake that explains every case wins over those a single case cannot rule out.
    if (!explains_all.empty()) {
      std::vector<Cause> kept;
      for (const Cause& cause : t.causes)
        if (explains_all.count(cause.id) || cause.id == "non-finite") kept.push_back(cause);
      if (!kept.empty()) t.causes = kept;
    }
    if (divides_by_speed && t.names("non-finite"))
      t.causes.insert(t.causes.begin(), util::likely("division-by-speed"));
    if (t.causes.empty()) t.addCause("unknown", false);
  }
  if (answer) {
    TestResult t = util::test(checks.back());
    t.fraction = momentum_ok ? 1 : 0;
    if (momentum_ok) {
      t.output = "Total momentum (sum of m v) is unchanged by every contact between free bodies.";
    } else {
      t.output =
          "The impulse must change the two bodies' momenta by equal and opposite amounts.\n\n" +
          momentum_report;
      // NaN momentum says nothing of the mass split: the cases' own cause explains it.
      if (momentum_non_finite && divides_by_speed)
        t.causes = {util::likely("division-by-speed"), util::likely("non-finite")};
      else if (momentum_non_finite)
        t.causes = {util::likely("non-finite")};
      else
        t.causes = {util::guess("wrong-mass-split")};
    }
    tests.push_back(t);
  } else {
    tests.push_back(util::failedTest(checks.back(), failure.text, {util::guess(failure.causeId())}));
  }
  return tests;
}

}  // namespace

std::vector<PlannedTest> collideChecks(bool sphere_sphere) { return checkTable(sphere_sphere); }

std::vector<TestResult> probeCollideCloth(const ProbeContext& context) {
  return probeContacts(context, false);
}

std::vector<TestResult> probeCollideSpheres(const ProbeContext& context) {
  return probeContacts(context, true);
}

}  // namespace clothref::grader
