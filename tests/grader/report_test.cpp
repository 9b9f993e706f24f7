// The writers: Gradescope's results.json fields, JUnit XML that stays well-formed.
#include "grader/grade/report.h"

#include <gtest/gtest.h>

namespace clothref::grader {
namespace {

GradeReport sampleReport() {
  GradeReport report;
  report.submission = "sub";
  report.edition = 2022;
  TestResult passed = makeTest("RungeKuttaFourth::integrate", "convergence order", 1);
  passed.fraction = 1;
  passed.max_score = passed.score = 3;
  TestResult failed = makeTest("Spheres::collide(Cloth*)", "approaching pair", 1);
  failed.max_score = 2;
  failed.output = "expected <1> & got \"2\"\x01";
  failed.diagnoses = {"no-approach-check"};
  report.tests = {passed, failed};
  report.score = 3;
  report.max_score = 5;
  return report;
}

TEST(ResultsJson, GradescopeFields) {
  const auto json = resultsJson(sampleReport());
  EXPECT_EQ(json["score"], 3.0);
  ASSERT_EQ(json["tests"].size(), 2u);
  const auto& test = json["tests"][1];
  EXPECT_EQ(test["name"], "Spheres::collide(Cloth*): approaching pair");
  EXPECT_EQ(test["status"], "failed");
  EXPECT_EQ(test["max_score"], 2.0);
  EXPECT_EQ(test["output_format"], "md");
  EXPECT_EQ(test["visibility"], "visible");
  EXPECT_EQ(test["tags"],
            nlohmann::ordered_json({"Spheres::collide(Cloth*)", "no-approach-check"}));
  EXPECT_EQ(json["tests"][0]["status"], "passed");
}

TEST(JunitXml, EscapesFeedback) {
  const std::string xml = junitXml(sampleReport());
  EXPECT_NE(xml.find("failures=\"1\""), std::string::npos);
  EXPECT_NE(xml.find("expected &lt;1&gt; &amp; got &quot;2&quot; "), std::string::npos) << xml;
  EXPECT_EQ(xml.find('\x01'), std::string::npos);
  EXPECT_NE(xml.find("classname=\"RungeKuttaFourth::integrate\" name=\"convergence order\""),
            std::string::npos);
}

TEST(MarkdownReport, FailedChecksComeWithTheirFeedback) {
  const std::string md = markdownReport(sampleReport());
  EXPECT_NE(md.find("### Spheres::collide(Cloth*): approaching pair (0 / 2)"), std::string::npos)
      << md;
  EXPECT_NE(md.find("- RungeKuttaFourth::integrate: convergence order (3 / 3)"), std::string::npos)
      << md;
}

TEST(AllWriters, StateTheVerdictAndTheIsolation) {
  GradeReport report = sampleReport();
  report.verdict = "timed-out";
  report.isolation = "rlimits, uid 65534 <x>";
  const auto json = resultsJson(report);
  EXPECT_EQ(json["extra_data"]["verdict"], "timed-out");
  EXPECT_EQ(json["extra_data"]["isolation"], "rlimits, uid 65534 <x>");
  EXPECT_NE(json["output"].get<std::string>().find("Verdict: timed-out"), std::string::npos);
  const std::string xml = junitXml(report);
  EXPECT_NE(xml.find("<property name=\"verdict\" value=\"timed-out\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<property name=\"isolation\" value=\"rlimits, uid 65534 &lt;x&gt;\"/>"),
            std::string::npos);
  const std::string markdown = markdownReport(report);
  EXPECT_NE(markdown.find("Verdict: **timed-out**"), std::string::npos);
  EXPECT_NE(markdown.find("Student code ran with: rlimits, uid 65534 <x>."), std::string::npos);
}

}  // namespace
}  // namespace clothref::grader
