// The rubric: the course's weights by default, JSON overrides, and how points split over tests.
#include "grader/grade/rubric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "clothref/io/error.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/probes/util.h"
#include "grader/grade/report/outputs.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

double total(const Rubric& rubric) {
  double sum = 0;
  for (const auto& [stub, points] : rubric.stub_points) sum += points;
  return sum;
}

TEST(Rubric, CourseWeightsAddUpToTheCodePart) {
  EXPECT_DOUBLE_EQ(total(defaultRubric(2022)), 80);
  EXPECT_DOUBLE_EQ(total(defaultRubric(2024)), 80);
  EXPECT_DOUBLE_EQ(defaultRubric(2022).stub_points.at("Cloth::computeSpringForce"), 20);
  EXPECT_DOUBLE_EQ(defaultRubric(2024).stub_points.at("Cloth::computeSpringForce"), 25);
  EXPECT_EQ(defaultRubric(2024).stub_points.count("Spheres::collide()"), 0u);
  EXPECT_TRUE(defaultRubric(2022).accepts("explicit-as-symplectic"));
}

TEST(Rubric, FileOverridesWeightsTolerancesAndVariants) {
  test::TempDir temp;
  std::ofstream(temp.file("rubric.json")) << R"({"stubs": {"RungeKuttaFourth::integrate": 30},
    "tests": {"RungeKuttaFourth::integrate: convergence order": 3},
    "tolerances": {"force_rel": 0.01}, "accepted_variants": {"explicit-as-symplectic": false}})";
  const Rubric rubric = loadRubric(temp.file("rubric.json"), defaultRubric(2022));
  EXPECT_DOUBLE_EQ(rubric.stub_points.at("RungeKuttaFourth::integrate"), 30);
  EXPECT_DOUBLE_EQ(rubric.tolerances.force_rel, 0.01);
  EXPECT_FALSE(rubric.accepts("explicit-as-symplectic"));
  EXPECT_TRUE(rubric.accepts("implicit-corrector-v-new"));
}

// Gradescope's visibility per stub or per test: a test's own entry wins, "visible" by default;
// an unknown stub or visibility is refused with the field named.
TEST(Rubric, VisibilityPerStubOrTestDefaultVisible) {
  const Rubric rubric = rubricFromJson(
      nlohmann::json::parse(R"({"visibility": {"RungeKuttaFourth::integrate": "after_due_date",
        "RungeKuttaFourth::integrate: convergence order": "hidden"}})"),
      "r.json", defaultRubric(2022));
  EXPECT_EQ(rubric.visibilityOf("RungeKuttaFourth::integrate: convergence order",
                                "RungeKuttaFourth::integrate"),
            "hidden");
  EXPECT_EQ(rubric.visibilityOf("RungeKuttaFourth::integrate: one step on a random state",
                                "RungeKuttaFourth::integrate"),
            "after_due_date");
  EXPECT_EQ(rubric.visibilityOf("Cloth::initializeSpring: connections at N = 25",
                                "Cloth::initializeSpring"),
            "visible");
  for (const char* bad : {R"({"visibility": {"Cloth::nope": "hidden"}})",
                          R"({"visibility": {"Cloth::initializeSpring": "secret"}})",
                          R"({"visibility": {"Cloth::initializeSpring": 1}})"}) {
    try {
      rubricFromJson(nlohmann::json::parse(bad), "r.json", defaultRubric(2022));
      ADD_FAILURE() << bad;
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()).rfind("r.json: /visibility/", 0), 0u) << error.what();
    }
  }
}

TEST(Rubric, BadFilesNameTheField) {
  test::TempDir temp;
  const auto expectError = [&](const std::string& text, const std::string& field) {
    std::ofstream(temp.file("rubric.json"), std::ios::trunc) << text;
    try {
      loadRubric(temp.file("rubric.json"), defaultRubric(2022));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
    }
  };
  expectError(R"({"stubs": {"Cloth::draw": 3}})", "/stubs/Cloth::draw: unknown stub");
  expectError(R"({"stubs": {"Cloth::initializeSpring": -1}})", "/stubs/Cloth::initializeSpring");
  expectError(R"({"tolerances": {"speed": 1}})", "/tolerances/speed");
  expectError(R"({"accepted_variants": {"anything": true}})", "/accepted_variants/anything");
  expectError(R"({"weights": {}})", "/weights: unknown field");
  expectError("{", "not valid JSON");
}

// The rubric reads through the library's one JSON reader, so its errors say what every format's
// do: "<file>: <JSON pointer>: <problem>", with line and column for a syntax error, the bad
// value quoted, and user text (keys) cut short.
TEST(Rubric, ErrorsGiveFilePointerLineAndColumnLikeEveryFormat) {
  test::TempDir temp;
  const std::string path = temp.file("rubric.json");
  const auto errorOf = [&](const std::string& text) -> std::string {
    std::ofstream(path, std::ios::trunc) << text;
    try {
      loadRubric(path, defaultRubric(2022));
    } catch (const InputError& error) {
      return error.what();
    }
    return "accepted: " + text;
  };
  EXPECT_EQ(
      errorOf("{\"stubs\": {\n  \"Cloth::initializeSpring\": 1e400}}")
          .rfind(path + ": /stubs/Cloth::initializeSpring: not valid JSON (line 2, column ", 0),
      0u);
  EXPECT_EQ(errorOf(R"({"stubs": {"Cloth::initializeSpring": "ten"}})"),
            path + R"(: /stubs/Cloth::initializeSpring: expected a number >= 0, got "ten")");
  EXPECT_EQ(errorOf(R"({"tolerances": []})"), path + ": /tolerances: expected an object, got []");
  EXPECT_EQ(errorOf("[1]"), path + ": /: expected an object, got [1]");
  EXPECT_EQ(errorOf(R"({"accepted_variants": {"explicit-as-symplectic": 1}})"),
            path + ": /accepted_variants/explicit-as-symplectic: expected true or false, got 1");
  const std::string error = errorOf(R"({"tests": {")" + std::string(100000, 'x') + R"(": -1}})");
  EXPECT_EQ(error.rfind(path + ": /tests/xxx", 0), 0u) << error.substr(0, 200);
  EXPECT_LT(error.size(), path.size() + 200) << error.substr(0, 200);
}

// The fuzz target's entry: a parsed document gives the same rubric as the file.
TEST(Rubric, FromJsonMatchesTheFile) {
  test::TempDir temp;
  const std::string text =
      R"({"stubs": {"ExplicitEuler::integrate": 7}, "tolerances": {"order": 0.5}})";
  std::ofstream(temp.file("rubric.json")) << text;
  const Rubric from_file = loadRubric(temp.file("rubric.json"), defaultRubric(2024));
  const Rubric from_json =
      rubricFromJson(nlohmann::json::parse(text), "rubric.json", defaultRubric(2024));
  EXPECT_EQ(from_json.stub_points, from_file.stub_points);
  EXPECT_DOUBLE_EQ(from_json.tolerances.order, 0.5);
  EXPECT_DOUBLE_EQ(from_json.stub_points.at("ExplicitEuler::integrate"), 7);
}

TEST(Rubric, PointsSplitByWeightAndPartialCredit) {
  GradeReport report;
  report.tests.push_back(makeTest("Cloth::initializeSpring", "a", 3));
  report.tests.push_back(makeTest("Cloth::initializeSpring", "b", 1));
  report.tests.push_back(makeTest("whole run", "info", 0));
  report.tests[0].fraction = 1;
  report.tests[1].fraction = 0.5;
  report.tests[2].informational = true;
  report.tests[2].fraction = 1;
  applyRubric(defaultRubric(2022), report);
  EXPECT_DOUBLE_EQ(report.tests[0].max_score, 11.25);
  EXPECT_DOUBLE_EQ(report.tests[1].score, 1.875);
  EXPECT_DOUBLE_EQ(report.tests[2].max_score, 0);
  EXPECT_DOUBLE_EQ(report.score, 13.125);
  EXPECT_DOUBLE_EQ(report.max_score, 15);
}

// Every test planned for an edition, all passed: the points add up to each stub's points and to 80
// exactly, also after results.json's rounding to three decimals (a reader sums those).
TEST(Rubric, TestPointsAddUpToTheStubsPointsExactly) {
  for (int edition : {2022, 2024}) {
    GradeReport report;
    for (const PlannedTest& planned : plannedTests(edition)) {
      report.tests.push_back(makeTest(planned.stub, planned.check, planned.weight));
      report.tests.back().fraction = 1;
    }
    const Rubric rubric = defaultRubric(edition);
    applyRubric(rubric, report);
    EXPECT_EQ(report.max_score, 80.0) << edition;
    EXPECT_EQ(report.score, 80.0) << edition;
    std::map<std::string, double> summed, summed_rounded;
    double total = 0;
    for (const TestResult& t : report.tests) {
      summed[t.stub] += t.max_score;
      summed_rounded[t.stub] += std::round(t.max_score * 1000) / 1000;
      total += t.max_score;
    }
    EXPECT_EQ(total, 80.0) << edition;
    ASSERT_EQ(report.stub_max.size(), rubric.stub_points.size()) << edition;
    for (const auto& [stub, points] : rubric.stub_points) {
      EXPECT_EQ(report.stub_max.at(stub), points) << edition << " " << stub;
      EXPECT_EQ(report.stub_score.at(stub), points) << edition << " " << stub;
      EXPECT_EQ(summed.at(stub), points) << edition << " " << stub;
      EXPECT_EQ(summed_rounded.at(stub), points) << edition << " " << stub;
    }
  }
}

// A rubric's points that are no multiple of 1/8 still split exactly (in thousandths).
TEST(Rubric, OddPointsSplitIntoThousandthsThatAddUp) {
  GradeReport report;
  for (const char* check : {"a", "b", "c"})
    report.tests.push_back(makeTest("Cloth::initializeSpring", check, 1));
  for (TestResult& t : report.tests) t.fraction = 1;
  Rubric rubric = defaultRubric(2024);
  rubric.stub_points = {{"Cloth::initializeSpring", 3.3}};
  applyRubric(rubric, report);
  ASSERT_EQ(report.tests.size(), 3u);
  long thousandths = 0;
  for (const TestResult& t : report.tests) thousandths += std::lround(t.max_score * 1000);
  EXPECT_EQ(thousandths, 3300);
  EXPECT_EQ(std::round(report.stub_max.at("Cloth::initializeSpring") * 1000) / 1000, 3.3);
}

// ---- Points follow mistakes (per-mistake scoring)

const std::string kSpheres = "Spheres::collide()";

// The 2022 edition's planned checks of `stub`: the first `passing` pass, the others fail naming
// `causes` (id, likely); a likely cause comes with its proof (a replay), unless `proofs` is false.
GradeReport stubWithFailures(const std::string& stub, std::size_t passing,
                             const std::vector<std::pair<std::string, bool>>& causes,
                             bool proofs = true) {
  GradeReport report;
  for (const PlannedTest& planned : plannedTests(2022)) {
    if (planned.stub != stub) continue;
    TestResult test = makeTest(planned.stub, planned.check, planned.weight);
    test.fraction = report.tests.size() < passing ? 1 : 0;
    if (!test.passed()) {
      for (const auto& [id, likely] : causes) {
        if (likely && proofs)
          test.addCause(id, likely).proof = "Proven: the model of " + id + " gives your numbers.";
        else
          test.addCause(id, likely);
      }
    }
    report.tests.push_back(test);
  }
  return report;
}

Rubric perCheck(Rubric rubric) {
  rubric.scoring = Scoring::PerCheck;
  return rubric;
}

double testSum(const GradeReport& report, const std::string& stub) {
  double sum = 0;
  for (const TestResult& t : report.tests)
    if (t.stub == stub) sum += t.score;
  return sum;
}

std::string notes(const GradeReport& report) {
  std::string all;
  for (const TestResult& t : report.tests) all += t.rubric_note;
  return all;
}

// The issue's example: one wrong correction factor fails 7 of the 8 collision checks; the stub
// loses the cause's deduction once instead of 7/8 of its points, and its first failed check says
// so with the per-check score beside it.
TEST(PerMistake, OneLikelyCauseWithADeductionCostsItOnce) {
  const Rubric rubric = defaultRubric(2022);
  GradeReport report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  ASSERT_GT(report.tests.size(), 2u);
  GradeReport old = report;
  applyRubric(perCheck(rubric), old);
  applyRubric(rubric, report);
  const double max = rubric.stub_points.at(kSpheres);
  const double deduction = rubric.deductions.at(cause::kCorrectionFactor);
  EXPECT_GT(deduction, 0);
  EXPECT_EQ(report.stub_score.at(kSpheres), max * (1 - deduction));
  EXPECT_LT(old.stub_score.at(kSpheres), report.stub_score.at(kSpheres));
  EXPECT_EQ(testSum(report, kSpheres), report.stub_score.at(kSpheres));
  EXPECT_EQ(report.score, report.stub_score.at(kSpheres));
  EXPECT_TRUE(report.tests[0].rubric_note.empty());
  EXPECT_EQ(
      report.tests[1].rubric_note,
      "One mistake (`correction-factor`) explains every failed check of this stub: it loses " +
          points(deduction * 100) +
          " % of its points once (rubric: per-mistake; per-check scoring would give " +
          points(old.stub_score.at(kSpheres)) + " / " + points(max) + ").");
  for (std::size_t k = 2; k < report.tests.size(); ++k)
    EXPECT_TRUE(report.tests[k].rubric_note.empty()) << k;
  // scored again (a re-grade, a second writer): the same scores, the line once
  applyRubric(rubric, report);
  EXPECT_EQ(report.stub_score.at(kSpheres), max * (1 - deduction));
  EXPECT_EQ(notes(report), report.tests[1].rubric_note);
}

// A guess alone, a cause without a deduction (a crash), a check with no cause: the stub is scored
// per check and nothing is said.
TEST(PerMistake, AnythingButProvenMistakesWithADeductionIsScoredPerCheck) {
  const Rubric rubric = defaultRubric(2022);
  const std::vector<std::vector<std::pair<std::string, bool>>> cases = {
      {{cause::kCorrectionFactor, false}},
      {{cause::kCrashed, true}},
      {{cause::kUnknown, false}},
      {}};
  for (const auto& causes : cases) {
    GradeReport report = stubWithFailures(kSpheres, 1, causes);
    GradeReport old = report;
    applyRubric(rubric, report);
    applyRubric(perCheck(rubric), old);
    EXPECT_EQ(report.stub_score.at(kSpheres), old.stub_score.at(kSpheres)) << causes.size();
    EXPECT_EQ(notes(report), "");
  }
  // A failed check naming only a guess beside checks naming a proven mistake: per check too.
  GradeReport report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  report.tests.back().causes = {Cause{cause::kRestitutionIgnored, false, {}, {}, {}, {}, {}, {}}};
  GradeReport old = report;
  applyRubric(rubric, report);
  applyRubric(perCheck(rubric), old);
  EXPECT_EQ(report.stub_score.at(kSpheres), old.stub_score.at(kSpheres));
  EXPECT_EQ(notes(report), "");
  // A guess beside the one likely cause does not count: the stub qualifies.
  report =
      stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}, {cause::kUnknown, false}});
  applyRubric(rubric, report);
  EXPECT_NE(notes(report), "");
  // NaN beside the mistake that makes it is its symptom, not a second mistake: the stub
  // qualifies (pan-big5's division by a zero speed); NaN alone has no deduction.
  report =
      stubWithFailures(kSpheres, 1, {{cause::kDivisionBySpeed, true}, {cause::kNonFinite, true}});
  applyRubric(rubric, report);
  EXPECT_NE(notes(report).find("(`division-by-speed`)"), std::string::npos) << notes(report);
  report = stubWithFailures(kSpheres, 1, {{cause::kNonFinite, true}});
  applyRubric(rubric, report);
  EXPECT_EQ(notes(report), "");
  // A stub without a failed check is untouched.
  report = stubWithFailures(kSpheres, 100, {{cause::kCorrectionFactor, true}});
  applyRubric(rubric, report);
  EXPECT_EQ(report.stub_score.at(kSpheres), rubric.stub_points.at(kSpheres));
  EXPECT_EQ(notes(report), "");
}

// Points follow proven mistakes only: a cause named as likely without its proof (a replay or a
// repair) never earns per-mistake points, whatever its deduction.
TEST(PerMistake, AnUnprovenLikelyCauseIsScoredPerCheck) {
  const Rubric rubric = defaultRubric(2022);
  GradeReport report =
      stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}}, /*proofs=*/false);
  ASSERT_TRUE(report.tests.back().causes.front().likely);
  ASSERT_FALSE(report.tests.back().causes.front().proven());
  GradeReport old = report;
  applyRubric(rubric, report);
  applyRubric(perCheck(rubric), old);
  EXPECT_EQ(report.stub_score.at(kSpheres), old.stub_score.at(kSpheres));
  EXPECT_EQ(notes(report), "");
  // The same with its proof: the deduction applies.
  report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  applyRubric(rubric, report);
  EXPECT_GT(report.stub_score.at(kSpheres), old.stub_score.at(kSpheres));
}

// Two proven mistakes in one stub (each failed check names one of them, or both): their
// deductions add up, at most the stub's points, and the line names both.
TEST(PerMistake, ProvenMistakesDeductionsAddUp) {
  const Rubric rubric = defaultRubric(2022);
  GradeReport report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  ASSERT_GT(report.tests.size(), 3u);
  report.tests[2].causes.clear();
  report.tests[2].addCause(cause::kWrongMassSplit).proof = "Proven: a split.";
  GradeReport old = report;
  applyRubric(rubric, report);
  applyRubric(perCheck(rubric), old);
  const double max = rubric.stub_points.at(kSpheres);
  const double both =
      rubric.deductions.at(cause::kCorrectionFactor) + rubric.deductions.at(cause::kWrongMassSplit);
  ASSERT_LT(both, 1);
  EXPECT_EQ(report.stub_score.at(kSpheres),
            std::max(old.stub_score.at(kSpheres), std::round(max * (1 - both) * 8) / 8));
  EXPECT_EQ(testSum(report, kSpheres), report.stub_score.at(kSpheres));
  EXPECT_EQ(report.tests[1].rubric_note,
            "2 proven mistakes (`correction-factor`, `wrong-mass-split`) explain every failed "
            "check of this stub: together they lose " +
                points(rubric.deductions.at(cause::kCorrectionFactor) * 100) + " + " +
                points(rubric.deductions.at(cause::kWrongMassSplit) * 100) + " = " +
                points(both * 100) +
                " % of its points once (rubric: per-mistake; per-check scoring would give " +
                points(old.stub_score.at(kSpheres)) + " / " + points(max) + ").");
  // Deductions that add up to more than the stub: nothing given back beyond per check.
  Rubric heavy = rubric;
  heavy.deductions[cause::kCorrectionFactor] = 0.7;
  heavy.deductions[cause::kWrongMassSplit] = 0.6;
  GradeReport capped = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  capped.tests[2].causes.clear();
  capped.tests[2].addCause(cause::kWrongMassSplit).proof = "Proven: a split.";
  GradeReport capped_old = capped;
  applyRubric(heavy, capped);
  applyRubric(perCheck(heavy), capped_old);
  EXPECT_EQ(capped.stub_score.at(kSpheres), capped_old.stub_score.at(kSpheres));
  EXPECT_EQ(notes(capped), "");
}

// NaN and garbage never earn a mistake's points (issue 36): a cause that cannot make non-finite
// numbers is no longer likely on a check whose answers are non-finite, so a NaN stub is scored
// per check. Before, a NaN computeSpringForce named `fixed-particle-moves` and kept 75 %, and a
// NaN RK4 named `no-reevaluation`.
TEST(PerMistake, NonFiniteAnswersEarnNoMistakesPoints) {
  const Rubric rubric = defaultRubric(2022);
  const Catalogue catalogue =
      loadCatalogue(std::string(CLOTHREF_SOURCE_DIR) + "/tools/grader/diagnoses.json");
  std::set<std::string> can_be;
  for (const auto& [id, entry] : catalogue.entries)
    if (entry.non_finite) can_be.insert(id);
  ASSERT_TRUE(can_be.count(cause::kDivisionBySpeed));
  ASSERT_FALSE(can_be.count(cause::kNoReevaluation));
  const std::string rk4 = "RungeKuttaFourth::integrate";
  // The probe answered NaN and names no cause per check: each failed check is taken as
  // non-finite, the stage fit's finding becomes a guess, and the stub is scored per check.
  // Its stage fit's finding has no proof: no model of it gives NaN on the probe's finite states.
  GradeReport report = stubWithFailures(rk4, 0, {{cause::kNoReevaluation, true}}, /*proofs=*/false);
  ASSERT_GT(report.tests.size(), 1u);
  GradeReport old = report;
  applyRubric(perCheck(rubric), old);
  markNonFinite({rk4}, can_be, report.tests);
  applyRubric(rubric, report);
  EXPECT_EQ(report.stub_score.at(rk4), old.stub_score.at(rk4));
  EXPECT_EQ(notes(report), "");
  for (const TestResult& t : report.tests) {
    ASSERT_FALSE(t.causes.empty());
    EXPECT_EQ(t.causes.front().id, cause::kNonFinite);
    EXPECT_TRUE(t.causes.front().likely);
    for (const Cause& cause : t.causes) EXPECT_EQ(cause.likely, cause.id == cause::kNonFinite);
  }
  // Not its stub, and finite: untouched, one mistake.
  report = stubWithFailures(rk4, 0, {{cause::kNoReevaluation, true}});
  markNonFinite({kSpheres}, can_be, report.tests);
  applyRubric(rubric, report);
  EXPECT_NE(notes(report).find("(`no-reevaluation`)"), std::string::npos) << notes(report);
  // A cause that makes NaN itself keeps its place: NaN is its symptom (pan-big5).
  report =
      stubWithFailures(kSpheres, 1, {{cause::kDivisionBySpeed, true}, {cause::kNonFinite, true}});
  markNonFinite({kSpheres}, can_be, report.tests);
  applyRubric(rubric, report);
  EXPECT_NE(notes(report).find("(`division-by-speed`)"), std::string::npos) << notes(report);
  // A probe that names non-finite on its own checks says which: the others keep their causes.
  // (The correction factor's model gives no NaN: on the NaN check it has no proof.)
  report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  report.tests.back().addCause(cause::kNonFinite);
  report.tests.back().causes.front().proof.clear();
  markNonFinite({kSpheres}, can_be, report.tests);
  EXPECT_TRUE(report.tests[1].causes.front().likely);
  EXPECT_EQ(report.tests[1].causes.front().id, cause::kCorrectionFactor);
  EXPECT_FALSE(report.tests.back().causes.front().id == cause::kCorrectionFactor &&
               report.tests.back().causes.front().likely);
  applyRubric(rubric, report);
  EXPECT_EQ(notes(report), "");
  // A cause proven on these numbers (its replay gave the NaN too) keeps its place (issue 38).
  report = stubWithFailures(rk4, 0, {{cause::kNoReevaluation, true}});
  markNonFinite({rk4}, can_be, report.tests);
  applyRubric(rubric, report);
  EXPECT_NE(notes(report).find("(`no-reevaluation`)"), std::string::npos) << notes(report);
}

// "scoring": "per-check" in a rubric file gives today's scores exactly: each test earns its
// points times its fraction, in whole units, and nothing is said.
TEST(PerMistake, PerCheckRubricFileGivesTodaysScores) {
  test::TempDir temp;
  std::ofstream(temp.file("rubric.json")) << R"({"scoring": "per-check"})";
  const Rubric rubric = loadRubric(temp.file("rubric.json"), defaultRubric(2022));
  EXPECT_EQ(rubric.scoring, Scoring::PerCheck);
  GradeReport report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  report.tests[2].fraction = 0.5;
  applyRubric(rubric, report);
  double sum = 0;
  for (const TestResult& t : report.tests) {
    EXPECT_EQ(t.score, std::round(t.max_score * t.fraction * 8) / 8) << t.check;
    sum += t.score;
  }
  EXPECT_EQ(report.stub_score.at(kSpheres), sum);
  EXPECT_LT(sum,
            rubric.stub_points.at(kSpheres) * (1 - rubric.deductions.at(cause::kCorrectionFactor)));
  EXPECT_EQ(notes(report), "");
}

// The rule only ever raises: over random stubs (random fractions, causes, deductions and
// points), no stub and no test earns less than per check, the tests add up to the stub and the
// stubs to the total, and a stub that qualifies earns max(per check, points x (1 - deduction)).
TEST(PerMistake, NeverLowersAScoreAndTheScoresAddUp) {
  std::mt19937 rng(33);
  const std::vector<std::string> ids = {cause::kCorrectionFactor, cause::kRestitutionIgnored,
                                        cause::kCrashed};
  int raised = 0;
  for (int round = 0; round < 400; ++round) {
    Rubric rubric = defaultRubric(2022);
    rubric.deductions[cause::kCorrectionFactor] = std::uniform_real_distribution<>(0, 1)(rng);
    if (round % 3 == 0) rubric.stub_points[kSpheres] = 3.3;  // thousandths
    GradeReport report;
    for (const PlannedTest& planned : plannedTests(2022)) {
      report.tests.push_back(makeTest(planned.stub, planned.check, planned.weight));
      TestResult& t = report.tests.back();
      const int kind = std::uniform_int_distribution<>(0, 5)(rng);
      t.fraction = kind < 3 ? 1.0 : kind == 3 ? std::uniform_real_distribution<>(0, 1)(rng) : 0;
      if (t.passed()) continue;
      Cause& cause = t.addCause(
          ids[std::uniform_int_distribution<>(0, round % 4 == 0 ? 2 : 0)(rng)], rng() % 8 != 0);
      if (rng() % 6 != 0) cause.proof = "Proven: a replay.";
    }
    GradeReport old = report;
    applyRubric(rubric, report);
    applyRubric(perCheck(rubric), old);
    ASSERT_EQ(report.tests.size(), old.tests.size());
    for (std::size_t k = 0; k < report.tests.size(); ++k) {
      EXPECT_GE(report.tests[k].score, old.tests[k].score) << round << " " << k;
      EXPECT_LE(report.tests[k].score, report.tests[k].max_score) << round << " " << k;
    }
    double total = 0;
    for (const auto& [stub, score] : report.stub_score) {
      EXPECT_GE(score, old.stub_score.at(stub)) << round << " " << stub;
      long units = 0;  // thousandths: exact for both point units
      for (const TestResult& t : report.tests)
        if (t.stub == stub) units += std::lround(t.score * 1000);
      EXPECT_EQ(units, std::lround(score * 1000)) << round << " " << stub;
      total += score;
      // The rule as the docs state it, worked out here: each failed check has one cause; every
      // failed check must name a proven one with a deduction, and their deductions add up.
      std::set<std::string> mistakes;
      bool covered = true, failed = false;
      for (const TestResult& t : report.tests) {
        if (t.stub != stub || t.passed()) continue;
        failed = true;
        const Cause& cause = t.causes.front();
        covered = covered && cause.proven() && rubric.deductions.count(cause.id);
        mistakes.insert(cause.id);
      }
      const bool qualifies = failed && covered;
      double deduction = 0;
      if (qualifies)
        for (const std::string& id : mistakes) deduction += rubric.deductions.at(id);
      const double target =
          qualifies ? report.stub_max.at(stub) * (1 - std::min(1.0, deduction)) : 0;
      const bool said = [&] {
        for (const TestResult& t : report.tests)
          if (t.stub == stub && !t.rubric_note.empty()) return true;
        return false;
      }();
      if (qualifies && target - old.stub_score.at(stub) > 0.0625) {
        ++raised;
        EXPECT_TRUE(said) << round << " " << stub;
        EXPECT_LE(std::abs(score - target), 0.0625) << round << " " << stub;
      } else if (!qualifies) {
        EXPECT_FALSE(said) << round << " " << stub;
        EXPECT_EQ(score, old.stub_score.at(stub)) << round << " " << stub;
      }
      if (said) {
        EXPECT_GT(score, old.stub_score.at(stub)) << round << " " << stub;
      } else {
        EXPECT_EQ(score, old.stub_score.at(stub)) << round << " " << stub;
      }
    }
    EXPECT_DOUBLE_EQ(report.score, total) << round;
  }
  EXPECT_GT(raised, 20);  // the random stubs do exercise the rule
}

// The line is part of the test's text, so every output shows it: results.json, JUnit, Markdown.
TEST(PerMistake, EveryOutputShowsTheLine) {
  GradeReport report = stubWithFailures(kSpheres, 1, {{cause::kCorrectionFactor, true}});
  applyRubric(defaultRubric(2022), report);
  const std::string line = report.tests[1].rubric_note;
  ASSERT_FALSE(line.empty());
  const auto results = resultsJson(report);
  EXPECT_EQ(results["tests"][1]["output"].get<std::string>().rfind(line, 0), 0u);
  EXPECT_EQ(results["tests"][1]["score"].get<double>(), roundedPoints(report.tests[1].score));
  EXPECT_EQ(results["score"].get<double>(), roundedPoints(report.score));
  const std::string markdown = markdownReport(report);
  EXPECT_NE(markdown.find(line), std::string::npos);
  EXPECT_EQ(markdown.find(line), markdown.rfind(line));  // once
  EXPECT_NE(junitXml(report).find("One mistake (`correction-factor`)"), std::string::npos);
}

TEST(PerMistake, RubricSetsScoringAndDeductions) {
  const Rubric rubric = rubricFromJson(nlohmann::json::parse(R"({"scoring": "per-mistake",
        "deductions": {"correction-factor": 0.5, "missing-damper": 0, "rk4-wrong-weights": null,
                       "crashed": null}})"),
                                       "r.json", perCheck(defaultRubric(2022)));
  EXPECT_EQ(rubric.scoring, Scoring::PerMistake);
  EXPECT_EQ(rubric.deductions.at(cause::kCorrectionFactor), 0.5);
  EXPECT_EQ(rubric.deductions.at(cause::kMissingDamper), 0.0);
  EXPECT_EQ(rubric.deductions.count(cause::kRk4WrongWeights), 0u);  // null: scored per check
  EXPECT_EQ(rubric.deductions.at(cause::kRestitutionIgnored),
            defaultRubric(2022).deductions.at(cause::kRestitutionIgnored));
}

// A scoring word, cause id or deduction the rubric does not know is refused, one line naming
// the field.
TEST(PerMistake, BadScoringOrDeductionsNameTheField) {
  const auto errorOf = [](const std::string& text) -> std::string {
    try {
      rubricFromJson(nlohmann::json::parse(text), "r.json", defaultRubric(2022));
    } catch (const InputError& error) {
      return error.what();
    }
    return "accepted: " + text;
  };
  const std::map<std::string, std::string> bad = {
      {R"({"scoring": "per-stub"})", "r.json: /scoring: expected \"per-mistake\" or"},
      {R"({"scoring": 1})", "r.json: /scoring: expected"},
      {R"({"deductions": {"wrong-constant": 0.2}})",
       "r.json: /deductions/wrong-constant: unknown cause"},
      {R"({"deductions": {"correction-factor": 1.5}})",
       "r.json: /deductions/correction-factor: expected a share"},
      {R"({"deductions": {"correction-factor": -0.1}})",
       "r.json: /deductions/correction-factor: expected a share"},
      {R"({"deductions": {"correction-factor": "25 %"}})",
       "r.json: /deductions/correction-factor: expected a share"},
      {R"({"deductions": {"crashed": 0.5}})",
       "r.json: /deductions/crashed: never scored per mistake"},
      {R"({"deductions": []})", "r.json: /deductions: expected an object"}};
  for (const auto& [text, start] : bad) {
    const std::string error = errorOf(text);
    EXPECT_EQ(error.rfind(start, 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

// Every catalogue id has a default (a deduction, or "never"), every default is in 0..1 and costs
// less than the whole stub, and the causes the issue names never trigger the rule.
TEST(PerMistake, EveryCatalogueCauseHasADefault) {
  const Catalogue catalogue =
      loadCatalogue(std::string(CLOTHREF_SOURCE_DIR) + "/tools/grader/diagnoses.json");
  std::set<std::string> table;
  for (const CauseDeduction& cause : causeDeductions()) {
    EXPECT_TRUE(table.insert(cause.id).second) << cause.id << " twice";
    EXPECT_TRUE(cause.deduction < 0 || (cause.deduction > 0 && cause.deduction < 1)) << cause.id;
  }
  for (const auto& [id, entry] : catalogue.entries) EXPECT_TRUE(table.count(id)) << id;
  EXPECT_EQ(table.size(), catalogue.entries.size());
  // The default rubric holds the catalogue's deduction of every entry, none for the kind "never".
  const Rubric rubric = defaultRubric(2024);
  for (const cause::Entry& entry : cause::entries()) {
    const bool never = std::string(entry.kind) == "never";
    EXPECT_EQ(never, entry.deduction < 0) << entry.id;
    ASSERT_EQ(rubric.deductions.count(entry.id), never ? 0u : 1u) << entry.id;
    if (!never) {
      EXPECT_EQ(rubric.deductions.at(entry.id), entry.deduction) << entry.id;
    }
  }
  // A guess never has one. Nor has the cause of a way a probe can fail to answer (a crash, a
  // timeout, ours), but for one that only a repair of the student's lines can prove
  // (undefined-behaviour): how a run ended is named without a proof, so it never costs a
  // deduction by itself (per-mistake scoring takes proven causes only).
  for (const auto& [id, entry] : catalogue.entries)
    if (entry.recognised_by == "guess") {
      EXPECT_EQ(rubric.deductions.count(id), 0u) << id;
    }
  for (const VerdictInfo& info : verdictTable()) {
    const std::string id = util::ProbeFailure{info.verdict, {}}.causeId();
    EXPECT_TRUE(catalogue.entries.count(id)) << id;
    const auto all = cause::entries();  // an array by value: one copy for both ends
    const auto entry =
        std::find_if(all.begin(), all.end(), [&](const cause::Entry& e) { return e.id == id; });
    ASSERT_NE(entry, all.end()) << id;
    if (std::string(entry->proof) != "repair") {
      EXPECT_EQ(rubric.deductions.count(id), 0u) << id;
    }
  }
}

// docs/grading-reference.md's table of deductions states every default of the table.
TEST(PerMistake, TheDocsStateEveryDefault) {
  std::ifstream in(std::string(CLOTHREF_SOURCE_DIR) + "/docs/grading-reference.md");
  std::stringstream docs;
  docs << in.rdbuf();
  for (const CauseDeduction& cause : causeDeductions()) {
    const std::string row = "| `" + std::string(cause.id) + "` | " + cause.kind + " | " +
                            (cause.deduction < 0 ? "—" : points(cause.deduction * 100) + " %") +
                            " |";
    EXPECT_NE(docs.str().find(row), std::string::npos) << row;
  }
}

}  // namespace
}  // namespace clothref::grader
