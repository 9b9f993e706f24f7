// Spheres::collide(Cloth*) and Spheres::collide(): crafted contacts (approaching, separating,
// several spheres, a sphere at an index other than 0, a fixed particle, deep penetration,
// touching exactly, unequal masses) compared with clothref's contact code, plus momentum.
// Three spheres are added once; unused ones and the rest of the cloth are parked far away, so
// each case touches only the bodies it names and the loop order cannot matter.
#include <algorithm>
#include <functional>
#include <iterator>
#include <set>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/cause_evidence.h"
#include "grader/grade/explain/contact_fit.h"
#include "grader/grade/explain/replay.h"
#include "grader/grade/mistakes/formula_variants.h"
#include "grader/grade/probes/collide_cases.h"
#include "grader/grade/probes/collide_replay.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
// A namespace of this file's own for the using-directive: a unity build shares one unnamed
// namespace among its files, where `contacts` would meet the other probes' names.
namespace collide_probe {
namespace {

using namespace contacts;

// The pairs of a case that touch before the call, each read back in the course's terms
// (contact_fit.h) from the student's result; a body in two contacts is left out (its change mixes
// both).
int readPairs(const Case& c, bool sphere_sphere, const Outcome& actual,
              std::vector<ContactReading>& readings) {
  const auto& sp = c.state.spheres.particles;
  const auto& cp = c.state.cloth.particles;
  struct Pair {
    int a, b;  // sphere index, and the other body's (a sphere or a particle)
  };
  std::vector<Pair> pairs;
  const auto reach = [&](int a, int b) {
    return sphere_sphere ? c.state.spheres.radius[a] + c.state.spheres.radius[b]
                         : c.state.spheres.radius[a];
  };
  const Particles<float>& others = sphere_sphere ? sp : cp;  // body b's kind
  for (int a : c.spheres)
    for (int b : sphere_sphere ? c.spheres : c.particles) {
      if (sphere_sphere && b <= a) continue;
      if ((sp.position.col(a) - others.position.col(b)).norm() <= reach(a, b))
        pairs.push_back({a, b});
    }
  const auto contacts = [&](int body, bool sphere) {
    int count = 0;
    for (const Pair& p : pairs)
      count += (sphere && p.a == body) || (sphere == sphere_sphere && p.b == body);
    return count;
  };
  const auto xyz = [](const Mat4X<float>& m, int i) {
    return std::array<double, 3>{m(0, i), m(1, i), m(2, i)};
  };
  for (const Pair& p : pairs) {
    if (contacts(p.a, true) != 1 || contacts(p.b, sphere_sphere) != 1) continue;
    const Mat4X<float>& bx = sphere_sphere ? actual.sphere_x : actual.cloth_x;
    const Mat4X<float>& bv = sphere_sphere ? actual.sphere_v : actual.cloth_v;
    ContactCase pair;
    pair.xa = xyz(sp.position, p.a);
    pair.va = xyz(sp.velocity, p.a);
    pair.xb = xyz(others.position, p.b);
    pair.vb = xyz(others.velocity, p.b);
    pair.xa_after = xyz(actual.sphere_x, p.a);
    pair.va_after = xyz(actual.sphere_v, p.a);
    pair.xb_after = xyz(bx, p.b);
    pair.vb_after = xyz(bv, p.b);
    pair.inverse_mass_a = sp.inverse_mass[p.a];
    pair.inverse_mass_b = others.inverse_mass[p.b];
    pair.contact_distance = reach(p.a, p.b);
    readings.push_back(readContact(pair));
  }
  return static_cast<int>(pairs.size());
}

std::vector<TestResult> probeContacts(const ProbeContext& context, bool sphere_sphere) {
  const std::vector<PlannedTest> checks = checkTable(sphere_sphere);
  // The course's values (the edition's scene): restitution of the pair's kind, the correction.
  const float e = static_cast<float>(sphere_sphere ? context.course.restitution_sphere
                                                   : context.course.restitution_cloth);
  const float correction = static_cast<float>(context.course.correction);
  const double rel = context.rubric.tolerances.collide_rel;
  std::vector<Case> cases =
      sphere_sphere ? sphereCases(context.course) : clothCases(context.course);
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
    request.floats[key::perCase(key::kClothAcc, n)] = util::flat(s.cloth.particles.acceleration);
    request.floats[key::perCase(key::kSphereAcc, n)] = util::flat(s.spheres.particles.acceleration);
    request.floats[key::perCase(key::kSphereMass, n)] = util::flat(s.spheres.particles.mass);
  }
  util::ProbeFailure failure;
  const auto answer = util::runGroup(context, context.probe, group_name, request, failure);
  const std::vector<ContactRow> signatures = contactRows(sphere_sphere);
  std::vector<TestResult> tests;
  std::string momentum_report;
  bool momentum_ok = true;
  bool momentum_non_finite = false;  // a failed case's momentum is NaN or infinite
  std::vector<std::string> ids;
  for (const ContactRow& signature : signatures) ids.push_back(signature.cause);
  CauseEvidence evidence = makeEvidence(cases.size(), ids);
  std::vector<ContactReading> readings;             // the touching pairs of every case
  std::vector<bool> touching(cases.size(), false);  // a failed case has a pair in contact
  // NaN or infinity out of the student's call, per case, and whether the case had a body at rest
  // (velocity exactly 0): NaN only where a body rests is a division by its speed.
  std::vector<bool> non_finite(cases.size(), false), at_rest(cases.size(), false);
  std::vector<Outcome> actuals;  // the student's outcome of each case (for the replays)
  // per case: the largest change of an acceleration by the call (m/s^2), 0 where none
  std::vector<double> acceleration_changes(cases.size(), 0);
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
      tests.push_back(
          util::failedTest(checks[c.check], failure.text, {util::likely(failure.causeId())}));
      continue;
    }
    const int n = static_cast<int>(k);
    const Outcome actual{util::matrix(answer->f(key::perCase(key::kClothPos, n)), kN * kN),
                         util::matrix(answer->f(key::perCase(key::kClothVel, n)), kN * kN),
                         util::matrix(answer->f(key::perCase(key::kSpherePos, n)), 3),
                         util::matrix(answer->f(key::perCase(key::kSphereVel, n)), 3),
                         util::matrix(answer->f(key::perCase(key::kClothAcc, n)), kN * kN),
                         util::matrix(answer->f(key::perCase(key::kSphereAcc, n)), 3)};
    actuals.push_back(actual);
    State reference = c.state;
    collideCourse(reference, sphere_sphere, e, correction);
    const Outcome expected = outcomeOf(reference);
    if (c.free_bodies && !conserves(c, actual)) {
      const Vec4<double> before = momentum(c.state, outcomeOf(c.state));
      const Vec4<double> after = momentum(c.state, actual);
      momentum_ok = false;
      momentum_non_finite = momentum_non_finite || !after.allFinite();
      momentum_report += util::compareVectors(
          checks[c.check].check + ": total momentum after your call (expected: as before it)",
          before, after, util::Tolerance{momentumTolerance(c), 0}, "kg m/s");
    }
    TestResult t = util::test(checks[c.check]);
    for (std::size_t m = 0; m < signatures.size(); ++m) {
      State variant = c.state;
      collideWithMistake(variant.spheres, variant.cloth, sphere_sphere, e, correction,
                         signatures[m]);
      const Outcome v = outcomeOf(variant);
      evidence.differs[k][m] = distance(v, expected) > rel;
      evidence.matches[k][m] = distance(actual, v) <= 10 * rel;
    }
    if (distance(actual, expected) <= rel) {
      evidence.passed[k] = true;
      readPairs(c, sphere_sphere, actual, readings);
      t.fraction = 1;
      t.output = "Positions, velocities and accelerations of every body match.";
      tests.push_back(t);
      continue;
    }
    t.output = "State tried (coefRestitution " + util::num(e) +
               ", radii 0.5, 0.5, 1.0, sphere masses " + util::num(context.course.sphere_density) +
               " r^3; all other bodies far away):\n\n";
    // Each body the case placed: a line of the text, and a body of the report's picture.
    const auto body = [&](const char* what, const char* short_name, int index,
                          const Mat4X<float>& x0, const Mat4X<float>& v0, float mass, float radius,
                          const Mat4X<float>& xe, const Mat4X<float>& ve, const Mat4X<float>& xa,
                          const Mat4X<float>& va, const Mat4X<float>& ae, const Mat4X<float>& aa) {
      t.output += "- " + std::string(what) + " " + std::to_string(index) + " (mass " +
                  util::num(mass) + "), before the call: x " + util::vec3(x0.col(index)) +
                  " m, v " + util::vec3(v0.col(index)) + " m/s\n" +
                  util::compareVectors("x after the call", xe.col(index), xa.col(index),
                                       util::Tolerance{rel, rel}, "m", "  ") +
                  util::compareVectors("v after the call", ve.col(index), va.col(index),
                                       util::Tolerance{rel, rel}, "m/s", "  ");
      // the acceleration only where the call changed it (the course's collide never does)
      if (!util::closeTo(ae.col(index), aa.col(index), rel))
        t.output += util::compareVectors(
            "a after the call (expected: as simulateOneStep() left it)", ae.col(index),
            aa.col(index), util::Tolerance{rel, rel}, "m/s^2", "  ");
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
           actual.sphere_x, actual.sphere_v, expected.sphere_a, actual.sphere_a);
    for (int q : c.particles)
      body("cloth particle", "particle", q, cloth.position, cloth.velocity, cloth.mass[q], 0,
           expected.cloth_x, expected.cloth_v, actual.cloth_x, actual.cloth_v, expected.cloth_a,
           actual.cloth_a);
    // Measured directly: NaN out of the call, or the fixed particle's velocity changed.
    non_finite[k] =
        !util::finite(util::flat(actual.sphere_v)) || !util::finite(util::flat(actual.cloth_v)) ||
        !util::finite(util::flat(actual.sphere_x)) || !util::finite(util::flat(actual.cloth_x));
    // The largest change the call made to an acceleration (the course's collide makes none).
    double acceleration_change = 0;
    for (const auto& [before, after] :
         {std::pair{&expected.cloth_a, &actual.cloth_a}, {&expected.sphere_a, &actual.sphere_a}})
      for (int i = 0; i < before->size() && i < after->size(); ++i)
        acceleration_change =
            std::max(acceleration_change, std::abs(double(after->data()[i] - before->data()[i])));
    if (non_finite[k])
      evidence.measured[k].push_back(cause::kNonFinite);
    else if (!util::closeTo(expected.cloth_a, actual.cloth_a, rel) ||
             !util::closeTo(expected.sphere_a, actual.sphere_a, rel))
      acceleration_changes[k] = acceleration_change,
      evidence.measured[k].push_back(cause::kCollideChangesAcceleration);
    else if (!sphere_sphere && c.check == kFixedParticle &&
             actual.cloth_v.col(0) != c.state.cloth.particles.velocity.col(0))
      evidence.measured[k].push_back(cause::kFixedParticleMassless);
    touching[k] = readPairs(c, sphere_sphere, actual, readings) > 0;
    tests.push_back(t);
  }
  // Every case with a body at rest went non-finite and no other case did: measured, not guessed.
  bool divides_by_speed = std::find(non_finite.begin(), non_finite.end(), true) != non_finite.end();
  for (std::size_t k = 0; k < cases.size(); ++k)
    if (non_finite[k] != at_rest[k]) divides_by_speed = false;
  // What the numbers say in the course's terms (contact_fit.h): the one quantity that differs,
  // shown on the cases with a touching pair.
  const std::vector<ContactFinding> findings =
      answer ? explainContacts(readings, e, correction) : std::vector<ContactFinding>{};
  for (const ContactFinding& f : findings)
    if (!f.cause.empty()) evidence.findings.push_back({f.cause, f.text});
  const auto finding = [&](const std::string& id) -> const ContactFinding* {
    for (const ContactFinding& f : findings)
      if (f.cause == id) return &f;
    return nullptr;
  };
  const std::set<std::string> likely = answer ? likelyCauses(evidence) : std::set<std::string>{};
  if (answer) nameCauses(evidence, likely, touching, tests);
  if (divides_by_speed)
    for (TestResult& t : tests)
      if (!t.passed() && t.names(cause::kNonFinite))
        t.causes.insert(t.causes.begin(), util::likely(cause::kDivisionBySpeed));
  // The likely causes that break momentum: a simulated mistake that does in some case, or an
  // impulse split read from the pairs.
  std::vector<std::string> breaks_momentum;
  for (std::size_t m = 0; m < signatures.size(); ++m) {
    const std::string id = signatures[m].cause;
    if (!likely.count(id) || std::count(breaks_momentum.begin(), breaks_momentum.end(), id))
      continue;
    for (const Case& c : cases) {
      State variant = c.state;
      collideWithMistake(variant.spheres, variant.cloth, sphere_sphere, e, correction,
                         signatures[m]);
      if (c.free_bodies && !conserves(c, outcomeOf(variant))) {
        breaks_momentum.push_back(id);
        break;
      }
    }
  }
  if (const ContactFinding* f = finding(cause::kWrongMassSplit);
      f && likely.count(f->cause) &&
      !std::count(breaks_momentum.begin(), breaks_momentum.end(), f->cause))
    breaks_momentum.push_back(f->cause);
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
        t.causes = {util::likely(cause::kDivisionBySpeed), util::likely(cause::kNonFinite)};
      else if (momentum_non_finite)
        t.causes = {util::likely(cause::kNonFinite)};
      else if (!breaks_momentum.empty())
        for (const std::string& id : breaks_momentum) {
          Cause& cause = t.addCause(id);
          if (const ContactFinding* f = finding(id)) cause.detail = "Measured: " + f->text + ".";
        }
      else
        t.causes = {util::guess(cause::kWrongMassSplit)};
    }
    tests.push_back(t);
  } else {
    tests.push_back(
        util::failedTest(checks.back(), failure.text, {util::likely(failure.causeId())}));
    return tests;
  }
  // Likely means proven: every model of a cause replayed on every case (explain/replay.h).
  const ContactModel course = courseContact(e, correction);
  std::vector<Candidate> candidates;
  for (const ContactRow& row : signatures)
    candidates.push_back({{row.cause}, withMistake(course, row)});
  for (const ContactFinding& f : findings) {
    ContactModel fitted = course;
    if (f.cause == cause::kRestitutionIgnored) {
      fitted.restitution = float(f.value);
      fitted.changes.push_back("with restitution " + util::num(f.value));
    } else if (f.cause == cause::kCorrectionFactor) {
      fitted.correction = float(f.value);
      fitted.changes.push_back("with a position correction of " + util::num(f.value) +
                               " x overlap");
    } else {
      continue;  // the others are the switches' models above
    }
    candidates.push_back({{f.cause}, fitted});
  }
  if (const std::optional<double> d = contactDistanceOffset(readings, correction)) {
    ContactModel reach = course;
    reach.reach_offset = float(*d);
    reach.changes.push_back("with a contact distance of " +
                            std::string(sphere_sphere ? "r_a + r_b" : "the radius") + " + " +
                            util::num(*d) + " m");
    candidates.push_back({{cause::kContactDistance}, reach});
  }
  ContactModel speed = course;
  speed.divides_by_speed = true;
  speed.changes.push_back("with each normal speed formed as |v| (v . n / |v|)");
  candidates.push_back({{cause::kDivisionBySpeed}, speed});
  proveContacts(candidates, cases, actuals, checks, sphere_sphere, rel, course, tests);
  // What the accelerations measured: read on the case, not a model.
  for (std::size_t k = 0; k < tests.size() && k < acceleration_changes.size(); ++k)
    for (Cause& c : tests[k].causes)
      if (c.id == cause::kCollideChangesAcceleration && acceleration_changes[k] > 0)
        c.detail = "Measured: your call changed an acceleration by up to " +
                   util::num(acceleration_changes[k]) +
                   " m/s^2; the course's collide leaves the accelerations as simulateOneStep() "
                   "made them.";
  requireProofs(tests, {cause::kNonFinite, cause::kCollideChangesAcceleration});
  for (TestResult& t : tests)
    if (!t.passed() &&
        std::none_of(t.causes.begin(), t.causes.end(), [](const Cause& c) { return c.likely; }) &&
        !t.names(cause::kUnknown))
      t.causes.insert(t.causes.begin(), util::guess(cause::kUnknown));
  return tests;
}

}  // namespace
}  // namespace collide_probe

std::vector<PlannedTest> collideChecks(bool sphere_sphere) {
  return contacts::checkTable(sphere_sphere);
}

std::vector<TestResult> probeCollideCloth(const ProbeContext& context) {
  return collide_probe::probeContacts(context, false);
}

std::vector<TestResult> probeCollideSpheres(const ProbeContext& context) {
  return collide_probe::probeContacts(context, true);
}

// The probes' rows of the probe table (probes.h), one per stub.
std::vector<ProbeGroup> probeRowsCollideCloth() {
  return {{probe::group::kCollideCloth,
           stubName(Stub::CollideCloth),
           collideChecks(false),
           probeCollideCloth,
           {probe::group::kCollideCloth}}};
}
std::vector<ProbeGroup> probeRowsCollideSpheres() {
  return {{probe::group::kCollideSpheres,
           stubName(Stub::CollideSpheres),
           collideChecks(true),
           probeCollideSpheres,
           {probe::group::kCollideSpheres}}};
}

}  // namespace clothref::grader
