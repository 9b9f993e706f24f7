// Cloth::computeSpringForce: on OUR spring set (never the student's), on random perturbed and
// moving states, with existing accelerations (accumulation) and with fixed and heavy particles.
// Accelerations are compared with clothref's per particle, within force_rel times the sum of the
// magnitudes that meet at that particle (so reordered float sums pass, wrong physics does not).
#include <algorithm>
#include <optional>
#include <random>

#include "clothref/core/cloth.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/cause_evidence.h"
#include "grader/grade/explain/replay.h"
#include "grader/grade/explain/spring_fit.h"
#include "grader/grade/mistakes/formula_variants.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
namespace {

const std::string& kStub = stubName(Stub::ComputeSpringForce);
constexpr int kN = 25;

// Per particle: |a_init| + sum of |F| invM over its springs (double), the scale of the tolerance.
std::vector<double> scales(const Cloth<float>& cloth, const Mat4X<float>& acc0) {
  const auto& p = cloth.particles;
  std::vector<double> s(static_cast<std::size_t>(p.size()));
  for (int i = 0; i < p.size(); ++i) s[i] = acc0.col(i).cast<double>().norm();
  for (const auto& sp : cloth.springs) {
    const int i = int(sp.start), j = int(sp.end);
    const Eigen::Vector4d d = (p.position.col(i) - p.position.col(j)).cast<double>();
    const double length = d.norm();
    const Eigen::Vector4d dv = (p.velocity.col(i) - p.velocity.col(j)).cast<double>();
    const double f = std::abs(cloth.damper_coef * dv.dot(d) / length) +
                     std::abs(cloth.spring_coef * (length - sp.rest_length));
    s[i] += f * p.inverse_mass[i];
    s[j] += f * p.inverse_mass[j];
  }
  return s;
}

struct Mismatch {
  int count = 0;
  int worst = -1;
  double worst_ratio = 0;
};

Mismatch compare(const Mat4X<float>& actual, const Mat4X<float>& expected,
                 const std::vector<double>& scale, double rel) {
  Mismatch m;
  for (int i = 0; i < expected.cols(); ++i) {
    const double err = (actual.col(i).cast<double>() - expected.col(i).cast<double>()).norm();
    const double tol = rel * scale[i] + 1e-6;
    const double ratio = std::isfinite(err) ? err / tol : 1e300;
    if (ratio > 1) ++m.count;
    if (ratio > m.worst_ratio) m.worst_ratio = ratio, m.worst = i;
  }
  return m;
}

// Whether two answers agree at every particle within `rel` of its force scale (non-finite
// values must be non-finite in both).
bool sameAnswer(const Mat4X<float>& a, const Mat4X<float>& b, const std::vector<double>& scale,
                double rel) {
  for (int q = 0; q < a.cols(); ++q) {
    if (!a.col(q).allFinite() || !b.col(q).allFinite()) {
      if (a.col(q).allFinite() != b.col(q).allFinite()) return false;
    } else if ((a.col(q) - b.col(q)).cast<double>().norm() > rel * scale[q] + 1e-6) {
      return false;
    }
  }
  return true;
}

// Rows of forcesChecks(), the probe's check table: one case each.
enum ForceCheck { kRandom, kMoving, kAccumulates, kFixedAndHeavy };

struct Case {
  ForceCheck check;
  Cloth<float> cloth;
  Mat4X<float> acc0;
};

// A case and the student's answer as spring_fit reads them: the change to the accelerations.
SpringCase springCase(const Case& c, const Mat4X<float>& actual) {
  const auto& p = c.cloth.particles;
  SpringCase out;
  const auto xyz = [](const Mat4X<float>& m, int i) {
    return std::array<double, 3>{m(0, i), m(1, i), m(2, i)};
  };
  for (int i = 0; i < p.size(); ++i) {
    out.x.push_back(xyz(p.position, i));
    out.v.push_back(xyz(p.velocity, i));
    out.mass.push_back(p.mass[i]);
    const Mat4X<float> change = actual.col(i) - c.acc0.col(i);
    out.change.push_back(xyz(change, 0));
  }
  for (const auto& s : c.cloth.springs)
    out.springs.push_back({int(s.start), int(s.end), double(s.rest_length)});
  return out;
}

// A model of the student's computeSpringForce: one row's switches, the constants on `cloth`.
struct ForceCandidate {
  std::vector<std::string> ids;
  ForceRow mistake;
  float spring_coef, damper_coef;
  std::string text;
};

// The form a spring reading fitted, as the row whose model computes it (none: the course's).
ForceRow mistakeOfForm(SpringForm form) {
  switch (form) {
    case SpringForm::Course:
      return {};
    case SpringForm::DamperUnnormalised:
      return forceRow(cause::kDamperNotNormalised);
    case SpringForm::DamperUnnormalisedTwice:  // no model of its own: the candidate is skipped
      return {};
    case SpringForm::OneEndOnly:
      return forceRow(cause::kForceOneEndOnly, 0);  // the start particle only
    case SpringForm::EndOnly:
      return forceRow(cause::kForceOneEndOnly, 1);  // the end particle only
    case SpringForm::MassNotInverse:
      return forceRow(cause::kMassNotInverse);
  }
  return {};
}

}  // namespace

std::vector<PlannedTest> forcesChecks() {
  return {{kStub, "random perturbed state", 1},
          {kStub, "moving state (damper)", 1},
          {kStub, "accumulates into existing accelerations", 1},
          {kStub, "fixed and heavy particles", 1}};
}

std::vector<TestResult> probeForces(const ProbeContext& context) {
  const double rel = context.rubric.tolerances.force_rel;
  Cloth<float> base;
  // The course's cloth and constants (the edition's scene).
  const Edition& course = context.course;
  base.particles = initializeVertex<float>(kN, static_cast<float>(course.cloth_half_extent),
                                           static_cast<float>(course.cloth_height),
                                           static_cast<float>(course.particle_mass));
  for (int corner : {0, kN - 1, kN * (kN - 1), kN * kN - 1}) setMass(base.particles, corner, 0.0f);
  initializeSpring(base, kN);
  base.spring_coef = static_cast<float>(course.spring_coef);
  base.damper_coef = static_cast<float>(course.damper_coef);
  const Vec4<float> gravity(static_cast<float>(course.gravity[0]),
                            static_cast<float>(course.gravity[1]),
                            static_cast<float>(course.gravity[2]), 0.0f);
  std::mt19937 rng(static_cast<unsigned>(context.seed));
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const auto noise = [&](Mat4X<float>& m, float amount, bool keep_w) {
    for (int c = 0; c < m.cols(); ++c)
      for (int r = 0; r < 3; ++r) m(r, c) += amount * u(rng);
    if (!keep_w) m.row(3).setZero();
  };
  std::vector<Case> cases;
  {  // perturbed positions, at rest, nothing accumulated yet
    Case c{kRandom, base, Mat4X<float>::Zero(4, kN * kN)};
    noise(c.cloth.particles.position, 0.03f, true);
    cases.push_back(c);
  }
  {  // stretched and moving: the damper matters
    Case c{kMoving, base, Mat4X<float>::Zero(4, kN * kN)};
    c.cloth.particles.position.topRows(3) *= 1.05f;
    noise(c.cloth.particles.position, 0.02f, true);
    noise(c.cloth.particles.velocity, 1.0f, false);
    cases.push_back(c);
  }
  {  // gravity and drag already in the accelerations: the springs must add to them
    Case c{kAccumulates, base, Mat4X<float>::Zero(4, kN * kN)};
    noise(c.cloth.particles.position, 0.03f, true);
    noise(c.cloth.particles.velocity, 0.5f, false);
    for (int i = 0; i < kN * kN; ++i)
      if (c.cloth.particles.mass[i] != 0) c.acc0.col(i) = gravity;
    noise(c.acc0, 2.0f, false);
    for (int i = 0; i < kN * kN; ++i)
      if (c.cloth.particles.mass[i] == 0) c.acc0.col(i).setZero();
    cases.push_back(c);
  }
  {  // some interior particles fixed (mass 0), others heavy or light
    Case c{kFixedAndHeavy, base, Mat4X<float>::Zero(4, kN * kN)};
    noise(c.cloth.particles.position, 0.03f, true);
    noise(c.cloth.particles.velocity, 0.5f, false);
    std::uniform_int_distribution<int> pick(0, 9);
    for (int i = 0; i < kN * kN; ++i) {
      const int k = pick(rng);
      if (c.cloth.particles.mass[i] == 0) continue;
      setMass(c.cloth.particles, i, k == 0 ? 0.0f : k < 3 ? 2.5f : k < 5 ? 0.5f : 1.0f);
      if (c.cloth.particles.mass[i] != 0) c.acc0.col(i) = gravity;
    }
    cases.push_back(c);
  }

  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kForces;
  request.ints[key::kCases] = {static_cast<std::int64_t>(cases.size())};
  request.floats[key::kSpringCoef] = {base.spring_coef};
  request.floats[key::kDamperCoef] = {base.damper_coef};
  for (const auto& s : base.springs) {
    request.ints[key::kSpringStart].push_back(s.start);
    request.ints[key::kSpringEnd].push_back(s.end);
    request.ints[key::kSpringType].push_back(static_cast<std::int64_t>(s.type));
    request.floats[key::kSpringRest].push_back(s.rest_length);
  }
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& p = cases[k].cloth.particles;
    const int n = static_cast<int>(k);
    request.floats[key::perCase(key::kClothPos, n)] = util::flat(p.position);
    request.floats[key::perCase(key::kClothVel, n)] = util::flat(p.velocity);
    request.floats[key::perCase(key::kClothAcc, n)] = util::flat(cases[k].acc0);
    request.floats[key::perCase(key::kClothMass, n)] = util::flat(p.mass);
  }
  util::ProbeFailure failure;
  const auto answer = util::runGroup(context, context.probe, group::kForces, request, failure);
  const std::vector<PlannedTest> checks = forcesChecks();
  std::vector<TestResult> tests;
  if (!answer) {
    for (const Case& c : cases)
      tests.push_back(
          util::failedTest(checks[c.check], failure.text, {util::likely(failure.causeId())}));
    return tests;
  }
  std::vector<ForceRow> signatures;  // the rows simulated on every case
  for (const ForceRow& row : forceRows())
    if (row.probed) signatures.push_back(row);
  std::vector<std::string> ids;
  for (const ForceRow& signature : signatures) ids.push_back(signature.cause);
  CauseEvidence evidence = makeEvidence(cases.size(), ids);
  std::vector<SpringReading> readings;  // each case read as the course's force, constants free
  std::vector<Mat4X<float>> actuals;    // the student's accelerations of each case
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    TestResult t = util::test(checks[c.check]);
    const Mat4X<float> actual =
        util::matrix(answer->f(key::perCase(key::kClothAcc, static_cast<int>(k))), kN * kN);
    actuals.push_back(actual);
    Cloth<float> reference = c.cloth;  // the library's stub gives the expected answer
    reference.particles.acceleration = c.acc0;
    computeSpringForce(reference);
    const Mat4X<float>& expected = reference.particles.acceleration;
    const auto scale = scales(c.cloth, c.acc0);
    readings.push_back(readSprings(springCase(c, actual), rel));
    for (std::size_t m = 0; m < ids.size(); ++m) {
      const Mat4X<float> variant = springAccelerations(c.cloth, c.acc0, signatures[m], gravity);
      evidence.differs[k][m] = !sameAnswer(variant, expected, scale, rel);
      evidence.matches[k][m] = sameAnswer(variant, actual, scale, 10 * rel);
    }
    const Mismatch m = compare(actual, expected, scale, rel);
    if (m.count == 0) {
      evidence.passed[k] = true;
      t.fraction = 1;
      t.output = "All " + std::to_string(kN * kN) + " accelerations match (within " +
                 util::num(rel) + " of the force scale at each particle).";
      tests.push_back(t);
      continue;
    }
    const int i = m.worst;
    const auto& p = c.cloth.particles;
    t.output =
        "State: the 25 x 25 course cloth with our springs (k_s = " + util::num(base.spring_coef) +
        ", k_d = " + util::num(base.damper_coef) + "), " + checks[c.check].check + ". " +
        std::to_string(m.count) + " of " + std::to_string(kN * kN) +
        " particles differ. Worst, particle " + std::to_string(i) + " (row " +
        std::to_string(i / kN) + ", col " + std::to_string(i % kN) + "):\n\n" + "- position " +
        util::vec3(p.position.col(i)) + ", velocity " + util::vec3(p.velocity.col(i)) + ", mass " +
        util::num(p.mass[i]) + "\n" + "- acceleration before the call " +
        util::vec3(c.acc0.col(i)) + "\n" +
        util::compareVectors("acceleration after the call", expected.col(i), actual.col(i),
                             util::Tolerance{rel * scale[i] + 1e-6, 0}, "m/s\u00B2");
    // Measured: a fixed particle's acceleration changed. It explains the check (likely) only where
    // every other particle is right; beside other differences (NaN, garbage, a second mistake)
    // it is shown as a guess, and earns no mistake's points.
    bool others_right = true;
    for (int q = 0; q < kN * kN; ++q)
      if (p.mass[q] != 0) {
        const double err = (actual.col(q).cast<double>() - expected.col(q).cast<double>()).norm();
        others_right = others_right && std::isfinite(err) && err <= rel * scale[q] + 1e-6;
      }
    for (int q = 0; q < kN * kN; ++q)
      if (p.mass[q] == 0 && actual.col(q) != c.acc0.col(q)) {
        t.addCause(cause::kFixedParticleMoves, others_right);
        break;
      }
    tests.push_back(t);
  }
  const std::vector<SpringFinding> findings =
      explainSprings(readings, base.spring_coef, base.damper_coef);
  for (const SpringFinding& f : findings) evidence.findings.push_back({f.cause, f.text});
  nameCauses(evidence, likelyCauses(evidence), std::vector<bool>(cases.size(), true), tests);

  // Likely means proven: each row's model replayed on every case (explain/replay.h).
  std::vector<ForceCandidate> candidates;
  for (const ForceRow& row : forceRows())
    candidates.push_back(
        {{row.cause}, row, base.spring_coef, base.damper_coef, forceModelText(row)});
  // The constants and the form the readings agree on, as one model of every finding.
  const auto common = [&](auto get) -> std::optional<double> {
    std::optional<double> value;
    for (const SpringReading& r : readings) {
      if (!r.fits) return std::nullopt;
      const double v = get(r);
      if (std::isnan(v)) continue;
      if (value && std::abs(*value - v) > 1e-3 * std::max(1.0, std::abs(v))) return std::nullopt;
      if (!value) value = v;
    }
    return value;
  };
  const std::optional<double> ks = common([](const SpringReading& r) { return r.spring_coef; });
  const std::optional<double> kd = common([](const SpringReading& r) { return r.damper_coef; });
  const std::optional<double> form =
      common([](const SpringReading& r) { return double(int(r.form)); });
  if (!findings.empty() && form && SpringForm(int(*form)) != SpringForm::DamperUnnormalisedTwice) {
    ForceCandidate fitted{{},
                          mistakeOfForm(SpringForm(int(*form))),
                          float(ks.value_or(base.spring_coef)),
                          float(kd.value_or(base.damper_coef)),
                          {}};
    for (const SpringFinding& f : findings) fitted.ids.push_back(f.cause);
    fitted.text = forceModelText(fitted.mistake) + " with k_s = " + util::num(fitted.spring_coef) +
                  " N/m and k_d = " + util::num(fitted.damper_coef) + " N s/m";
    candidates.push_back(fitted);
  }
  // The models of the causes named likely first; the first that proves is named, another that
  // proves too is an alternative reading (explain/replay.h).
  const auto named = [&](const std::string& id) {
    for (const TestResult& t : tests)
      for (const Cause& c : t.causes)
        if (c.id == id && c.likely) return true;
    return false;
  };
  std::stable_partition(candidates.begin(), candidates.end(), [&](const ForceCandidate& c) {
    return std::any_of(c.ids.begin(), c.ids.end(), named);
  });
  std::vector<Replay> replays;
  std::vector<std::string> winner;
  for (const ForceCandidate& m : candidates) {
    Replay replay;
    replay.model = m.text;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      Cloth<float> cloth = cases[k].cloth;
      cloth.spring_coef = m.spring_coef;
      cloth.damper_coef = m.damper_coef;
      const Mat4X<float> model = springAccelerations(cloth, cases[k].acc0, m.mistake, gravity);
      replay.checks.push_back(
          {checks[cases[k].check].check,
           {{"accelerations",
             sameAnswer(model, actuals[k], scales(cases[k].cloth, cases[k].acc0), rel)}}});
    }
    const bool failed =
        std::any_of(tests.begin(), tests.end(), [](const TestResult& t) { return !t.passed(); });
    if (replay.proven() && failed && winner.empty()) {
      applyReplay(replay, m.ids, tests);
      winner = m.ids;
    } else if (replay.proven() && failed && m.ids != winner) {
      alternative(replay, m.ids, winner.front(), tests);
    }
    replays.push_back(replay);
  }
  // A likely cause no model proves: a guess, with where its best model parts from the numbers.
  for (std::size_t m = 0; m < candidates.size(); ++m) {
    std::size_t best = m;
    for (std::size_t q = 0; q < candidates.size(); ++q)
      if (candidates[q].ids == candidates[m].ids &&
          replays[q].reproduced() > replays[best].reproduced())
        best = q;
    if (best == m && !replays[m].proven()) applyReplay(replays[m], candidates[m].ids, tests);
  }
  requireProofs(tests, {cause::kNonFinite, cause::kFixedParticleMoves});
  for (TestResult& t : tests)
    if (!t.passed() &&
        std::none_of(t.causes.begin(), t.causes.end(), [](const Cause& c) { return c.likely; }) &&
        !t.names(cause::kUnknown))
      t.causes.insert(t.causes.begin(), util::guess(cause::kUnknown));
  return tests;
}

// The probe's row of the probe table (probes.h): one child on the course's cloth.
std::vector<ProbeGroup> probeRowsForces() {
  return {{probe::group::kForces, kStub, forcesChecks(), probeForces, {probe::group::kForces}}};
}

}  // namespace clothref::grader
