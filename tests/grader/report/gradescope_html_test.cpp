// What results.json gives Gradescope as HTML (tools/grader/grade/report/gradescope_html.cpp): the
// summary, and each failed check with a picture as static HTML, the picture inline and every text
// a submission controls escaped beside it. Rendered as Gradescope renders it, in a browser:
// tests/browser/report_page_test.py.
#include "grader/grade/report/gradescope_html.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "clothref/record/record.h"
#include "clothref/scene/scene.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/report/whole_run_svg.h"
#include "report_samples.h"

namespace clothref::grader {
namespace {

using test_samples::countOf;
using test_samples::sampleReport;

// Every element is one of the inert ones a page of text and a drawing needs, no attribute is an
// event handler, no URL leaves the picture (only "url(#id)"): nothing runs, nothing is loaded.
// Text a submission controls is escaped, so every '<' left opens markup of ours.
void expectInert(const std::string& html) {
  static const std::set<std::string> allowed = {
      "p",        "div",  "ul",     "li",   "br",       "em",   "strong", "code", "pre",
      "table",    "tr",   "th",     "td",   "svg",      "defs", "marker", "path", "g",
      "clipPath", "rect", "circle", "line", "polyline", "text", "tspan"};
  static const std::regex tag(R"(<([a-zA-Z]+)([^>]*)>)");
  static const std::regex attribute(R"re(([a-zA-Z:-]+)="([^"]*)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), tag); it != std::sregex_iterator();
       ++it) {
    EXPECT_TRUE(allowed.count((*it)[1].str())) << (*it)[0];
    const std::string attributes = (*it)[2].str();
    for (auto a = std::sregex_iterator(attributes.begin(), attributes.end(), attribute);
         a != std::sregex_iterator(); ++a) {
      const std::string name = (*a)[1].str(), value = (*a)[2].str();
      EXPECT_NE(name.rfind("on", 0), 0u) << (*it)[0];
      EXPECT_TRUE(name != "href" && name != "src" && name.find("href") == std::string::npos)
          << (*it)[0];
      if (value.find("url(") != std::string::npos) {
        EXPECT_NE(value.find("url(#"), std::string::npos) << (*it)[0];
      }
    }
  }
  EXPECT_EQ(std::count(html.begin(), html.end(), '<'), std::count(html.begin(), html.end(), '>'))
      << html;
}

TEST(GradescopeHtml, SummaryIsStaticHtml) {
  nlohmann::ordered_json results = {{"score", 6},
                                    {"output", "Edition 2022. **Verdict** <graded>."},
                                    {"output_format", "md"},
                                    {"tests", {{{"name", "x"}, {"output_format", "md"}}}}};
  const auto html = withHtmlSummary(results, sampleReport());
  EXPECT_EQ(html["output_format"], "html");
  EXPECT_EQ(html["tests"][0]["output_format"], "md");  // not one test per check: left alone
  const std::string output = html["output"].get<std::string>();
  // one line per stub that lost points: points, checks passed, what is wrong; never a line per
  // failed check; the stubs whose every check passed on one line
  EXPECT_NE(output.find("<tr><td>Spheres::collide(Cloth*)</td><td>0 / 1.25</td><td>0 of 1</td>"
                        "<td><em>collision-normal-sign</em></td></tr>"),
            std::string::npos)
      << output;
  EXPECT_EQ(output.find("approaching pair"), std::string::npos) << output;
  EXPECT_NE(output.find("<p>Every check passed: Cloth::initializeSpring 6 / 6.</p>"),
            std::string::npos)
      << output;
  EXPECT_EQ(countOf(output, "<tr>"), 2u) << output;  // the head and the one stub that lost points
  EXPECT_EQ(output.find("<li>"), output.find("<li>cloth.cpp")) << output;  // the files only
  EXPECT_NE(output.find("<strong>Verdict</strong> &lt;graded&gt;."), std::string::npos);
  expectInert(output);
}

// In the summary, a stub's likely causes come first, its guesses after them, marked "?".
TEST(GradescopeHtml, SummaryKeepsLikelyCausesAndGuessesApart) {
  GradeReport report = sampleReport();
  report.tests[1].causes.insert(report.tests[1].causes.begin(),
                                Cause{cause::kUnknown, false, {}, {}, {}, {}, {}, {}});
  const std::string output = withHtmlSummary(resultsJson(report), report)["output"];
  EXPECT_NE(output.find("<td><em>collision-normal-sign</em>, <em>unknown</em>?</td>"),
            std::string::npos)
      << output;
}

Sketch collisionSketch() {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0.2f, 0}, {0, -1, 0}});
  sketch.bodies.push_back({"particle 3", {0, 0.02f, 0}, 0, {0, 1, 0}, {0, -0.5f, 0}, {0, 1, 0}});
  return sketch;
}

// A failed check with a picture is HTML in results.json: the picture inline, then its output and
// causes with every text escaped; a check without one keeps its Markdown. Two pictures never share
// an id, and the same report gives the same bytes.
TEST(GradescopeHtml, AFailedCheckWithAPictureIsHtmlWithThePictureInline) {
  GradeReport report = sampleReport();
  report.tests[1].sketch = collisionSketch();
  TestResult second = report.tests[1];
  second.check = "separating pair";
  second.output = "yours `</svg><script>alert(5)</script>`";
  report.tests.push_back(second);
  const auto results = withHtmlSummary(resultsJson(report), report);
  EXPECT_EQ(results["tests"][0]["output_format"], "md");  // passed: no picture
  for (int k : {1, 2}) {
    SCOPED_TRACE(k);
    EXPECT_EQ(results["tests"][k]["output_format"], "html");
    const std::string html = results["tests"][k]["output"];
    EXPECT_EQ(html.rfind("<div class=\"gr-picture\"><svg class=\"gr-sketch\"", 0), 0u) << html;
    EXPECT_EQ(countOf(html, "<svg "), 1u);
    EXPECT_EQ(countOf(html, "id=\"gr-test-" + std::to_string(k) + "-"), countOf(html, " id=\""));
    EXPECT_NE(html.find("<strong>Likely cause</strong> (<code>collision-normal-sign</code>)"),
              std::string::npos);
    expectInert(html);
  }
  EXPECT_NE(std::string(results["tests"][1]["output"])
                .find("&lt;/pre&gt;&lt;script&gt;alert(2)&lt;/script&gt;"),
            std::string::npos);
  EXPECT_NE(std::string(results["tests"][2]["output"])
                .find("<code>&lt;/svg&gt;&lt;script&gt;alert(5)&lt;/script&gt;</code>"),
            std::string::npos);
  EXPECT_EQ(withHtmlSummary(resultsJson(report), report).dump(), results.dump());
}

// The whole run, when it differs: a static picture of both runs from its two traces (here the
// course scene by explicit and by symplectic Euler, which part within a few steps).
TEST(GradescopeHtml, AWholeRunThatDiffersIsPictured) {
  const Scene* scene = findBuiltinScene("course2022");
  ASSERT_NE(scene, nullptr);
  TraceSettings settings;
  settings.dt = scene->dt;
  settings.steps = 40;
  settings.stride = 20;
  auto traces = std::make_shared<TestResult::Traces>();
  std::ostringstream reference, student;
  writeTrace(*scene, settings, reference);
  settings.method = Method::Symplectic;
  writeTrace(*scene, settings, student);
  traces->reference = reference.str();
  traces->student = student.str();
  TestResult run = makeTest("Cloth + Spheres + ExplicitEuler (whole run)", "course scene", 0);
  run.informational = true;
  run.traces = traces;
  const std::string svg = testPicture(run, 4);
  ASSERT_EQ(svg.rfind("<svg class=\"gr-sketch gr-whole-run\"", 0), 0u) << svg;
  EXPECT_EQ(countOf(svg, "<polyline "), 1u);
  EXPECT_GE(countOf(svg, "<circle "), 3u);  // a point per recorded step at least
  EXPECT_NE(svg.find("front view at step 40"), std::string::npos) << svg;
  EXPECT_EQ(countOf(svg, "id=\"gr-test-4-"), countOf(svg, " id=\""));
  expectInert(svg);
  // identical: nothing to picture; a trace cut short: no picture, the text says why
  run.fraction = 1;
  EXPECT_EQ(testPicture(run, 4), "");
  run.fraction = 0;
  traces->student = traces->student.substr(0, traces->student.size() / 2);
  EXPECT_EQ(wholeRunSvg(*traces, "w"), "");
}

// A rubric that shows a stub's tests later (or never) hides that stub everywhere a student looks
// before its release: the summary (Markdown and HTML) names neither its points nor its checks
// passed nor its causes, and says no total or verdict (both count it); a visible check of a stub
// whose other checks are shown later does not carry the per-mistake line (it tells how every
// check of the stub went). The hidden checks keep their own text, shown with them.
TEST(GradescopeHtml, AHiddenStubAppearsNowhereAStudentSeesBeforeItsRelease) {
  for (const std::string visibility : {"hidden", "after_due_date", "after_published"}) {
    SCOPED_TRACE(visibility);
    GradeReport report = sampleReport();
    report.tests[1].visibility = visibility;  // Spheres::collide(Cloth*): all its checks
    report.tests[1].sketch = collisionSketch();
    // Cloth::computeSpringForce: one check visible (with the per-mistake line), one shown later
    TestResult shown = makeTest("Cloth::computeSpringForce", "random perturbed state", 1);
    shown.max_score = 10;
    shown.score = 6;
    shown.output = "acceleration after the call differs";
    shown.rubric_note = "One mistake (`damper-sign`) explains every failed check of this stub.";
    TestResult later = makeTest("Cloth::computeSpringForce", "moving state (damper)", 1);
    later.max_score = 10;
    later.output = "the damper term differs";
    later.visibility = visibility;
    report.tests.push_back(shown);
    report.tests.push_back(later);
    report.stub_score["Cloth::computeSpringForce"] = 6;
    report.stub_max["Cloth::computeSpringForce"] = 20;
    report.score = 12;
    report.max_score = 27.25;
    const nlohmann::ordered_json md = resultsJson(report);
    const nlohmann::ordered_json html = withHtmlSummary(md, report);
    for (const std::string& summary :
         {md["output"].get<std::string>(), html["output"].get<std::string>()}) {
      for (const char* hidden :
           {"Spheres::collide(Cloth*)", "Cloth::computeSpringForce", "1.25", "0 of 1", "6 / 20",
            "0 of 2", cause::kCollisionNormalSign, "12 / 27.25", "27.25", "graded"})
        EXPECT_EQ(summary.find(hidden), std::string::npos) << hidden << " in\n" << summary;
      EXPECT_NE(summary.find("shown later"), std::string::npos) << summary;
    }
    // the visible stub keeps its line
    EXPECT_NE(html["output"].get<std::string>().find(
                  "<p>Every check passed: Cloth::initializeSpring 6 / 6.</p>"),
              std::string::npos)
        << html["output"];
    ASSERT_EQ(html["tests"].size(), 4u);
    for (const auto& results : {md, html}) {
      const std::string visible = results["tests"][2]["output"].get<std::string>();
      EXPECT_EQ(results["tests"][2]["visibility"], "visible");
      EXPECT_EQ(visible.find("One mistake"), std::string::npos) << visible;
      EXPECT_NE(visible.find("acceleration after the call differs"), std::string::npos);
      EXPECT_EQ(results["tests"][3]["visibility"], visibility);
      EXPECT_NE(results["tests"][3]["output"].get<std::string>().find("the damper term differs"),
                std::string::npos);
      // the hidden stub's picture and causes are in its own check only, hidden with it
      EXPECT_EQ(results["tests"][1]["visibility"], visibility);
    }
    EXPECT_NE(html["tests"][1]["output"].get<std::string>().find("<svg"), std::string::npos);
    // every check visible again: the summary says the total, the verdict and every stub
    for (TestResult& t : report.tests) t.visibility = "visible";
    const std::string all = withHtmlSummary(resultsJson(report), report)["output"];
    EXPECT_NE(all.find("12 / 27.25"), std::string::npos) << all;
    EXPECT_NE(all.find("<td>Spheres::collide(Cloth*)</td><td>0 / 1.25</td><td>0 of 1</td>"),
              std::string::npos)
        << all;
    EXPECT_NE(all.find("graded"), std::string::npos) << all;
  }
}

}  // namespace
}  // namespace clothref::grader
