// The student's report page (tools/grader/grade/report/html_report.cpp): escapes what a student
// controls, keeps every check, pictures the failed ones. In a real browser: tests/browser/.
#include "grader/grade/report/html_report.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "report_samples.h"

namespace clothref::grader {
namespace {

using test_samples::countOf;
using test_samples::sampleReport;

TEST(HtmlReport, StudentReportEscapesAndKeepsEveryCheck) {
  const std::string page = studentReportHtml(sampleReport(), nullptr);
  EXPECT_EQ(page.find("<img src=x"), std::string::npos);
  EXPECT_EQ(page.find("<script>alert(2)"), std::string::npos);
  EXPECT_EQ(page.find("<b>cloth.cpp"), std::string::npos);
  EXPECT_NE(page.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  EXPECT_NE(page.find("&lt;/pre&gt;&lt;script&gt;alert(2)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(page.find("\xEF\xBF\xBD"), std::string::npos);  // the bad byte, replaced
  EXPECT_EQ(page.find('\xFF'), std::string::npos);
  EXPECT_NE(page.find("connections at N = 25"), std::string::npos);
  EXPECT_NE(page.find("approaching pair"), std::string::npos);
  EXPECT_NE(page.find("<span class=\"gr-cause\">collision-normal-sign</span>"), std::string::npos);
  // the cause's why and example, escaped, the example as a code block
  EXPECT_NE(page.find("<p><strong>Why</strong>: &lt;why&gt; it points inwards</p>"),
            std::string::npos);
  EXPECT_NE(
      page.find("<pre><code>n = -n;  // mistake &lt;b&gt;\nn = xs - xc;  // fix\n</code></pre>"),
      std::string::npos);
  EXPECT_NE(page.find("<li>expected x (1, 2, 3) - actual x (1, 2, 4)</li>"), std::string::npos);
  // no whole run: no viewer and no script at all
  EXPECT_EQ(page.find("<script"), std::string::npos);
}

// A failed check with a sketch gets its picture, once; a page without the whole run has no script.
TEST(HtmlReport, AFailedCheckWithASketchGetsItsPicture) {
  const Sketch sketch = test_samples::sampleSketch(false);
  GradeReport report = sampleReport();
  ASSERT_FALSE(report.tests.empty());
  const std::string without = studentReportHtml(report, nullptr);
  EXPECT_EQ(without.find("gr-sketch"), std::string::npos);
  report.tests.back().sketch = sketch;
  const std::string with = studentReportHtml(report, nullptr);
  EXPECT_EQ(countOf(with, "<svg class=\"gr-sketch\""), 1u);
  EXPECT_EQ(with.find("<script"), std::string::npos);
}

// The pictures' ids are numbered per page: two failed checks' sketches share no id, and the same
// report gives the same page whatever was drawn before it (a batch in any order).
TEST(HtmlReport, SketchIdsAreNumberedPerPage) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0, 0}, {0, -1, 0}});
  sketch.bodies.push_back({"particle 3", {0, 0.02f, 0}, 0, {0, 1, 0}, {0, 0, 0}, {0, 1, 0}});
  GradeReport report = sampleReport();
  report.tests.back().sketch = sketch;
  TestResult second = report.tests.back();
  second.check = "separating pair";
  report.tests.push_back(second);
  const std::string page = studentReportHtml(report, nullptr);
  EXPECT_EQ(countOf(page, "<svg class=\"gr-sketch\""), 2u);
  std::set<std::string> ids;
  std::size_t defined = 0;
  for (std::size_t at = page.find(" id=\"gr-sketch-"); at != std::string::npos;
       at = page.find(" id=\"gr-sketch-", at + 1)) {
    ++defined;
    ids.insert(page.substr(at + 5, page.find('"', at + 5) - at - 5));
  }
  EXPECT_GE(defined, 10u);  // per sketch three arrow heads and two clip paths
  EXPECT_EQ(ids.size(), defined);
  // another report drawn in between changes nothing
  GradeReport other = sampleReport();
  other.tests.back().sketch = sketch;
  (void)studentReportHtml(other, nullptr);
  EXPECT_EQ(studentReportHtml(report, nullptr), page);
}

// The legend of the numbers is on the page once, rendered.
TEST(HtmlReport, ThePageSaysHowNumbersRead) {
  const std::string page = studentReportHtml(sampleReport(), nullptr);
  EXPECT_EQ(countOf(page, "6 significant digits"), 1u);
  EXPECT_NE(page.find("is <strong>bold</strong> in both"), std::string::npos);
}

}  // namespace
}  // namespace clothref::grader
