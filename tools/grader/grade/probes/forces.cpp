// Cloth::computeSpringForce: on OUR spring set (never the student's), on random perturbed and
// moving states, with existing accelerations (accumulation) and with fixed and heavy particles.
// Accelerations are compared with clothref's per particle, within force_rel times the sum of the
// magnitudes that meet at that particle (so reordered float sums pass, wrong physics does not).
#include <random>

#include "clothref/core/cloth.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
namespace {

const std::string& kStub = stubName(Stub::ComputeSpringForce);
constexpr int kN = 25;

// Course-form force with one known mistake switched on (for the numeric signatures).
enum class ForceMistake {
  None,
  Assign,
  SpringSign,
  DamperSign,
  NoDamper,
  DamperUnnormalised,
  OneEnd,
  MassNotInverse,
  DivideByMass
};

Mat4X<float> forces(const Cloth<float>& cloth, const Mat4X<float>& acc0, ForceMistake mistake) {
  const auto& p = cloth.particles;
  Mat4X<float> a = acc0;
  const float ks = cloth.spring_coef, kd = cloth.damper_coef;
  for (const auto& s : cloth.springs) {
    const int i = int(s.start), j = int(s.end);
    Vec4<float> raw = p.position.col(i) - p.position.col(j);
    const float length = raw.norm();
    Vec4<float> d = raw / length;
    const Vec4<float> dv = p.velocity.col(i) - p.velocity.col(j);
    float damper = kd * dv.dot(mistake == ForceMistake::DamperUnnormalised ? raw : d);
    float spring = ks * (length - s.rest_length);
    if (mistake == ForceMistake::SpringSign) spring = -spring;
    if (mistake == ForceMistake::DamperSign) damper = -damper;
    if (mistake == ForceMistake::NoDamper) damper = 0;
    const Vec4<float> f = d * (damper + spring);
    float wi = p.inverse_mass[i], wj = p.inverse_mass[j];
    if (mistake == ForceMistake::MassNotInverse) wi = p.mass[i], wj = p.mass[j];
    if (mistake == ForceMistake::DivideByMass) wi = 1.0f / p.mass[i], wj = 1.0f / p.mass[j];
    if (mistake == ForceMistake::Assign) {
      a.col(i) = -f * wi;
      a.col(j) = f * wj;
    } else {
      a.col(i) -= f * wi;
      if (mistake != ForceMistake::OneEnd) a.col(j) += f * wj;
    }
  }
  return a;
}

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

// Rows of forcesChecks(), the probe's check table: one case each.
enum ForceCheck { kRandom, kMoving, kAccumulates, kFixedAndHeavy };

struct Case {
  ForceCheck check;
  Cloth<float> cloth;
  Mat4X<float> acc0;
};

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
  base.particles = initializeVertex<float>(kN, 2.0f, context.edition == 2024 ? 1.0f : 0.0f, 1.0f);
  for (int corner : {0, kN - 1, kN * (kN - 1), kN * kN - 1}) setMass(base.particles, corner, 0.0f);
  initializeSpring(base, kN);
  base.spring_coef = context.edition == 2024 ? 20000.0f : 25000.0f;
  base.damper_coef = 750.0f;
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
      if (c.cloth.particles.mass[i] != 0) c.acc0.col(i) = Vec4<float>(0, -9.8f, 0, 0);
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
      if (c.cloth.particles.mass[i] != 0) c.acc0.col(i) = Vec4<float>(0, -9.8f, 0, 0);
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
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    if (!answer) {
      tests.push_back(util::failedTest(checks[c.check], failure.text, {util::guess(failure.causeId())}));
      continue;
    }
    TestResult t = util::test(checks[c.check]);
    const Mat4X<float> actual =
        util::matrix(answer->f(key::perCase(key::kClothAcc, static_cast<int>(k))), kN * kN);
    const Mat4X<float> expected = forces(c.cloth, c.acc0, ForceMistake::None);
    const auto scale = scales(c.cloth, c.acc0);
    const Mismatch m = compare(actual, expected, scale, rel);
    if (m.count == 0) {
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
    const std::pair<ForceMistake, const char*> signatures[] = {
        {ForceMistake::Assign, "assign-not-accumulate"},
        {ForceMistake::SpringSign, "spring-force-sign"},
        {ForceMistake::DamperSign, "damper-sign"},
        {ForceMistake::NoDamper, "missing-damper"},
        {ForceMistake::DamperUnnormalised, "damper-not-normalised"},
        {ForceMistake::OneEnd, "force-one-end-only"},
        {ForceMistake::MassNotInverse, "mass-not-inverse"},
        {ForceMistake::DivideByMass, "fixed-particle-moves"}};
    for (const auto& [mistake, id] : signatures) {
      const Mat4X<float> variant = forces(c.cloth, c.acc0, mistake);
      if ((variant - expected).cwiseAbs().maxCoeff() == 0.0f) continue;  // indistinguishable here
      bool same = true;
      for (int q = 0; q < kN * kN && same; ++q) {
        const auto& vc = variant.col(q);
        const auto& ac = actual.col(q);
        if (!vc.allFinite() || !ac.allFinite())
          same = vc.allFinite() == ac.allFinite();
        else
          same = (vc - ac).cast<double>().norm() <= 10 * (rel * scale[q] + 1e-6);
      }
      if (same) t.addCause(id);
    }
    if (t.causes.empty()) {
      bool fixed_moved = false;
      for (int q = 0; q < kN * kN; ++q)
        if (p.mass[q] == 0 && actual.col(q) != c.acc0.col(q)) fixed_moved = true;
      if (fixed_moved)
        t.addCause("fixed-particle-moves");
      else if (!util::finite(util::flat(actual)))
        t.addCause("non-finite");
    }
    if (t.causes.empty()) t.addCause("unknown", false);
    tests.push_back(t);
  }
  return tests;
}

}  // namespace clothref::grader
