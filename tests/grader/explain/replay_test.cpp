#include "grader/grade/explain/replay.h"

#include <gtest/gtest.h>

#include "grader/grade/cause_ids.h"
#include "grader/grade/rubric.h"

namespace clothref::grader {
namespace {

// A stub of three failed checks and one passed, the failed ones naming `id` as likely (the
// probe's first reading) and `unknown` as a guess.
std::vector<TestResult> threeFailed(const std::string& id) {
  std::vector<TestResult> tests;
  for (const char* check : {"approaching pair", "separating pair", "fixed particle", "momentum"}) {
    TestResult t = makeTest("Spheres::collide(Cloth*)", check, 1);
    t.fraction = tests.size() == 1 ? 1 : 0;
    if (!t.passed()) t.addCause(id, true);
    tests.push_back(t);
  }
  return tests;
}

Replay replayOf(const std::vector<std::vector<std::pair<std::string, bool>>>& checks) {
  Replay r;
  r.model = "the course's collide without the position correction";
  const char* names[] = {"approaching pair", "separating pair", "fixed particle", "momentum"};
  for (std::size_t k = 0; k < checks.size(); ++k) r.checks.push_back({names[k], checks[k]});
  return r;
}

TEST(Replay, EveryCheckReproducedIsProven) {
  const Replay r = replayOf({{{"positions", true}, {"velocities", true}},
                             {{"positions", true}, {"velocities", true}},
                             {{"positions", true}, {"velocities", true}},
                             {{"total momentum", true}}});
  EXPECT_TRUE(r.proven());
  EXPECT_EQ(r.line(),
            "Proven: the course's collide without the position correction gives your numbers on 4 "
            "of 4 checks.");
}

// Where the model and the student part is said: which quantities it gets right, on how many
// checks, the first of them named.
TEST(Replay, AModelThatPartsSaysWhere) {
  const Replay r = replayOf({{{"positions", true}, {"velocities", false}},
                             {{"positions", true}, {"velocities", true}},
                             {{"positions", true}, {"velocities", false}},
                             {{"total momentum", false}}});
  EXPECT_FALSE(r.proven());
  EXPECT_EQ(r.reproduced(), 1);
  EXPECT_EQ(r.line(),
            "Not proven: the course's collide without the position correction gives your numbers "
            "on 1 of 4 checks; on 2 (“approaching pair”, ...) it gives your positions but not "
            "your velocities; on 1 (“momentum”) it gives none of your total momentum.");
  EXPECT_FALSE(Replay{}.proven());  // no check: nothing proven
}

// The example: a cause the code contradicts (the stub skips every pair, so its
// velocities differ too) fails its replay and is not named as likely; its line says where.
TEST(Replay, APlausibleButWrongCauseIsAGuessWithItsLine) {
  std::vector<TestResult> tests = threeFailed(cause::kNoPositionCorrection);
  const Replay r = replayOf({{{"positions", true}, {"velocities", false}},
                             {{"positions", true}, {"velocities", true}},
                             {{"positions", true}, {"velocities", false}},
                             {{"total momentum", true}}});
  applyReplay(r, {cause::kNoPositionCorrection}, tests);
  for (const TestResult& t : tests) {
    if (t.passed()) continue;
    ASSERT_EQ(t.causes.size(), 1u) << t.check;
    EXPECT_FALSE(t.causes[0].likely) << t.check;
    EXPECT_FALSE(t.causes[0].proven()) << t.check;
    EXPECT_EQ(t.causes[0].proof, r.line());
  }
  // ... so per-mistake scoring never applies to it.
  GradeReport report;
  report.tests = tests;
  GradeReport per_check = report;
  Rubric rubric = defaultRubric(2022);
  applyRubric(rubric, report);
  rubric.scoring = Scoring::PerCheck;
  applyRubric(rubric, per_check);
  EXPECT_EQ(report.score, per_check.score);
}

// A proven model names its causes likely on every failed check of the stub, with the proof.
TEST(Replay, AProvenModelNamesItsCausesOnEveryFailedCheck) {
  std::vector<TestResult> tests = threeFailed(cause::kUnknown);
  tests[0].causes[0].likely = false;
  const Replay r = replayOf({{{"positions", true}},
                             {{"positions", true}},
                             {{"positions", true}},
                             {{"total momentum", true}}});
  applyReplay(r, {cause::kFirstSphereOnly, cause::kRestitutionIgnored}, tests);
  for (const TestResult& t : tests) {
    if (t.passed()) {
      EXPECT_TRUE(t.causes.empty());
      continue;
    }
    for (const char* id : {cause::kFirstSphereOnly, cause::kRestitutionIgnored}) {
      ASSERT_TRUE(t.names(id)) << t.check << " " << id;
      for (const Cause& c : t.causes)
        if (c.id == id) {
          EXPECT_TRUE(c.proven());
          EXPECT_EQ(c.proof, r.line());
        }
    }
  }
  // A later failed replay of the same cause does not undo the proof.
  const Replay worse = replayOf({{{"positions", false}}});
  applyReplay(worse, {cause::kFirstSphereOnly}, tests);
  ASSERT_FALSE(tests.empty());
  for (const Cause& c : tests[0].causes) {
    if (c.id == cause::kFirstSphereOnly) {
      EXPECT_TRUE(c.proven());
    }
  }
}

// What no replay proved becomes a guess, except what is read directly (NaN); likely causes first.
TEST(Replay, RequireProofsKeepsOnlyProvenAndObserved) {
  TestResult t = makeTest("Spheres::collide(Cloth*)", "approaching pair", 1);
  t.addCause(cause::kUnknown, false);
  t.addCause(cause::kCorrectionFactor, true);
  t.addCause(cause::kNonFinite, true);
  t.addCause(cause::kWrongMassSplit, true).proof = "Proven: a split.";
  std::vector<TestResult> tests = {t};
  requireProofs(tests, {cause::kNonFinite});
  ASSERT_EQ(tests[0].causes.size(), 4u);
  EXPECT_EQ(tests[0].causes[0].id, cause::kNonFinite);
  EXPECT_TRUE(tests[0].causes[0].likely);
  EXPECT_EQ(tests[0].causes[1].id, cause::kWrongMassSplit);
  EXPECT_TRUE(tests[0].causes[1].proven());
  EXPECT_EQ(tests[0].causes[2].id, cause::kUnknown);
  EXPECT_EQ(tests[0].causes[3].id, cause::kCorrectionFactor);
  EXPECT_FALSE(tests[0].causes[3].likely);
}

}  // namespace
}  // namespace clothref::grader
