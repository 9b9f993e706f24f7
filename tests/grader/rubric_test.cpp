// The rubric: the course's weights by default, JSON overrides, and how points split over tests.
#include "grader/grade/rubric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "clothref/io/error.h"
#include "grader/grade/probes/probes.h"
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

}  // namespace
}  // namespace clothref::grader
