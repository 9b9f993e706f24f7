// Reading a contact back in the course's terms (grader/grade/explain/contact_fit.h): contacts made
// here with the course's formula (clothref::formula::resolveContact, in float like a student's
// code) and with one quantity changed; every course contact reads as the course's, and each
// change is named with the value that fits.
#include "grader/grade/explain/contact_fit.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>

#include "clothref/formula/course_formulas.h"
#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

struct Pair {
  std::array<float, 4> xa, va, xb, vb;
  float inverse_mass_a, inverse_mass_b, reach;
};

// The probe's kinds of pair: approaching, separating, deep, a fixed particle (inverse mass 0),
// unequal masses.
std::vector<Pair> pairs() {
  return {{{0.1f, 0.42f, -0.05f, 1},
           {0.3f, -2, 0.1f, 0},
           {0, 0, 0, 1},
           {0.2f, 0.5f, -0.1f, 0},
           1 / 125.0f,
           1,
           0.5f},
          {{0.05f, 0.45f, 0, 1},
           {0, 1.5f, 0.2f, 0},
           {0, 0, 0, 1},
           {0, -0.3f, 0, 0},
           1 / 125.0f,
           1,
           0.5f},
          {{0.05f, 0.1f, 0.02f, 1},
           {0, -1, 0.5f, 0},
           {0, 0, 0, 1},
           {0, 0.2f, 0, 0},
           1 / 125.0f,
           1,
           0.5f},
          {{0, 0.45f, 0.05f, 1}, {0.2f, -1, 0, 0}, {0, 0, 0, 1}, {0, 0, 0, 0}, 1 / 125.0f, 0, 0.5f},
          {{0, 0, 0, 1},
           {2, 0, 0, 0},
           {1.45f, 0.1f, 0, 1},
           {0, 0, 0, 0},
           1 / 125.0f,
           1 / 1000.0f,
           1.5f}};
}

// A contact written as a student might change it: `edit` may touch the after-state.
using Contact = std::function<void(Pair&)>;

Contact course(float e, float correction) {
  return [=](Pair& p) {
    formula::resolveContact(p.xa.data(), p.va.data(), p.inverse_mass_a, p.xb.data(), p.vb.data(),
                            p.inverse_mass_b, p.reach, e, correction);
  };
}

std::vector<ContactReading> readAll(const Contact& contact) {
  std::vector<ContactReading> readings;
  for (Pair p : pairs()) {
    ContactCase c;
    for (int k = 0; k < 3; ++k)
      c.xa[k] = p.xa[k], c.va[k] = p.va[k], c.xb[k] = p.xb[k], c.vb[k] = p.vb[k];
    c.inverse_mass_a = p.inverse_mass_a;
    c.inverse_mass_b = p.inverse_mass_b;
    c.contact_distance = p.reach;
    contact(p);
    for (int k = 0; k < 3; ++k)
      c.xa_after[k] = p.xa[k], c.va_after[k] = p.va[k], c.xb_after[k] = p.xb[k],
      c.vb_after[k] = p.vb[k];
    readings.push_back(readContact(c));
  }
  return readings;
}

TEST(ContactFit, TheCoursesContactReadsAsTheCourses) {
  for (const float e : {0.0f, 0.8f}) {
    const auto readings = readAll(course(e, 0.15f));
    ASSERT_EQ(readings.size(), 5u);
    EXPECT_TRUE(readings[0].approaching);
    EXPECT_FALSE(readings[1].approaching);
    ASSERT_TRUE(readings[0].correction_a && readings[0].correction_b);
    EXPECT_NEAR(*readings[0].correction_a, 0.15, 1e-5);
    EXPECT_NEAR(*readings[0].correction_b, 0.15, 1e-5);
    ASSERT_TRUE(readings[0].restitution);
    EXPECT_NEAR(*readings[0].restitution, e, 1e-4);
    EXPECT_FALSE(readings[3].impulse_b);  // the fixed particle has no impulse to read
    EXPECT_TRUE(explainContacts(readings, e, 0.15).empty());
  }
}

TEST(ContactFit, ACorrectionFactorIsNamedWithItsValue) {
  const auto findings = explainContacts(readAll(course(0, 0.5f)), 0, 0.15);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].cause, cause::kCorrectionFactor);
  EXPECT_NEAR(findings[0].value, 0.5, 1e-4);
  EXPECT_EQ(findings[0].text,
            "velocities equal the course's; only positions differ: your position correction "
            "behaves as 0.5 x overlap; the course uses 0.15");
}

TEST(ContactFit, ARestitutionIsNamedWithItsValue) {
  const auto findings = explainContacts(readAll(course(0.5f, 0.15f)), 0.8, 0.15);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].cause, cause::kRestitutionIgnored);
  EXPECT_NEAR(findings[0].value, 0.5, 1e-3);
  EXPECT_NE(findings[0].text.find("restitution of 0.5; the course's is 0.8"), std::string::npos)
      << findings[0].text;
}

// A restitution of 0 read through float roundings is said as 0, not as -2e-9 (seen on the
// hand-written set: "a coefficient of restitution of -2.275e-09; the course's is 0.8").
TEST(ContactFit, ARestitutionOfZeroIsSaidAsZero) {
  const auto findings = explainContacts(readAll(course(0.0f, 0.15f)), 0.8, 0.15);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].cause, cause::kRestitutionIgnored);
  EXPECT_NE(findings[0].text.find("restitution of 0; the course's is 0.8"), std::string::npos)
      << findings[0].text;
}

TEST(ContactFit, OneBodyNoCorrectionAndTheNormalsSign) {
  const auto one = explainContacts(readAll([](Pair& p) {
                                     const auto xb = p.xb;
                                     course(0, 0.15f)(p);
                                     p.xb = xb;  // the particle is not pushed out
                                   }),
                                   0, 0.15);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].cause, cause::kCorrectionOneBody);
  EXPECT_NE(one[0].text.find("only the sphere is pushed out"), std::string::npos) << one[0].text;
  const auto none = explainContacts(readAll(course(0, 0.0f)), 0, 0.15);
  ASSERT_EQ(none.size(), 1u);
  EXPECT_EQ(none[0].cause, cause::kNoPositionCorrection);
  const auto reversed = explainContacts(readAll(course(0, -0.15f)), 0, 0.15);
  ASSERT_EQ(reversed.size(), 1u);
  EXPECT_EQ(reversed[0].cause, cause::kCollisionNormalSign);
}

// One body pushed out by another factor and the other not at all (blind4's yang: 0.1, the cloth
// only): two findings, each with the moved body's factor, so their models are replayed together.
TEST(ContactFit, OneBodyByAnotherFactorIsTwoFindings) {
  const auto findings = explainContacts(readAll([](Pair& p) {
                                          const auto xa = p.xa;
                                          course(0, 0.1f)(p);
                                          p.xa = xa;  // the sphere is not pushed out
                                        }),
                                        0, 0.15);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[0].cause, cause::kCorrectionOneBody);
  EXPECT_EQ(findings[1].cause, cause::kCorrectionFactor);
  EXPECT_NEAR(findings[1].value, 0.1, 1e-4);
  EXPECT_NE(findings[1].text.find("0.1 x overlap for the other body and 0 for the sphere"),
            std::string::npos)
      << findings[1].text;
}

// A student's contact with one impulse mistake (the course's form otherwise).
enum class Mistake { FullVelocity, NoApproachCheck, NotDivided, DividedByMasses };

Contact student(Mistake mistake, float e = 0) {
  return [=](Pair& p) {
    float n[4], relative[4];
    for (int k = 0; k < 4; ++k) n[k] = p.xa[k] - p.xb[k];
    const float length = std::sqrt(formula::dot4(n, n));
    const float penetration = p.reach - length;
    if (penetration < 0) return;
    for (int k = 0; k < 4; ++k) n[k] /= length;
    for (int k = 0; k < 4; ++k) relative[k] = p.va[k] - p.vb[k];
    const float approach = formula::dot4(relative, n);
    const float masses = 1 / p.inverse_mass_a + (p.inverse_mass_b > 0 ? 1 / p.inverse_mass_b : 0);
    const float denominator = mistake == Mistake::NotDivided ? 1.0f
                              : mistake == Mistake::DividedByMasses
                                  ? masses
                                  : p.inverse_mass_a + p.inverse_mass_b;
    if (approach < 0 || mistake == Mistake::NoApproachCheck)
      for (int k = 0; k < 4; ++k) {
        const float u = mistake == Mistake::FullVelocity ? relative[k] : n[k] * approach;
        const float impulse = -(1 + e) * u / denominator;
        p.va[k] += impulse * p.inverse_mass_a;
        p.vb[k] -= impulse * p.inverse_mass_b;
      }
    for (int k = 0; k < 4; ++k) {
      const float shift = (penetration * n[k]) * 0.15f;
      p.xa[k] += shift;
      p.xb[k] -= shift;
    }
  };
}

TEST(ContactFit, ImpulseMistakesAreNamedNotTakenForConstants) {
  const auto full = explainContacts(readAll(student(Mistake::FullVelocity)), 0, 0.15);
  ASSERT_EQ(full.size(), 1u);
  EXPECT_EQ(full[0].cause, cause::kRestitutionFullVelocity);
  const auto always = explainContacts(readAll(student(Mistake::NoApproachCheck)), 0, 0.15);
  ASSERT_FALSE(always.empty());
  EXPECT_EQ(always[0].cause, cause::kNoApproachCheck);
  for (const Mistake split : {Mistake::NotDivided, Mistake::DividedByMasses}) {
    const auto findings = explainContacts(readAll(student(split)), 0, 0.15);
    ASSERT_EQ(findings.size(), 1u);
    EXPECT_EQ(findings[0].cause, cause::kWrongMassSplit);
    EXPECT_NE(findings[0].text.find(split == Mistake::NotDivided ? "not divided by"
                                                                 : "divided by m_a + m_b"),
              std::string::npos)
        << findings[0].text;
  }
}

// No approach test beside a restitution of 0.5 (blind4's wu-big5): both found, the restitution
// read on the pairs as on approaching ones, so the two models are replayed together.
TEST(ContactFit, NoApproachTestBesideAnotherRestitutionIsTwoFindings) {
  const auto findings = explainContacts(readAll(student(Mistake::NoApproachCheck, 0.5f)), 0, 0.15);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[0].cause, cause::kNoApproachCheck);
  EXPECT_EQ(findings[1].cause, cause::kRestitutionIgnored);
  EXPECT_NEAR(findings[1].value, 0.5, 1e-3);
}

// A contact distance of r + 0.1 (the course's reach and penetration 0.1 larger): read back from
// every pair's correction; the course's own contact has no offset.
TEST(ContactFit, AContactDistanceIsReadFromTheCorrections) {
  const Contact wider = [](Pair& p) {
    formula::resolveContact(p.xa.data(), p.va.data(), p.inverse_mass_a, p.xb.data(), p.vb.data(),
                            p.inverse_mass_b, p.reach + 0.1f, 0.0f, 0.15f);
  };
  const std::optional<double> d = contactDistanceOffset(readAll(wider), 0.15);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(*d, 0.1, 1e-4);
  EXPECT_FALSE(contactDistanceOffset(readAll(course(0.0f, 0.15f)), 0.15).has_value());
  // another correction factor is no offset: the readings disagree on one
  EXPECT_FALSE(contactDistanceOffset(readAll(course(0.0f, 0.5f)), 0.15).has_value());
}

}  // namespace
}  // namespace clothref::grader
