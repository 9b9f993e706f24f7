// The grader's pages (tools/grader/grade/report/html_report.cpp): the student's report, the
// Gradescope summary and the class overview escape what a student controls, keep every check, and
// are built from the batch's files alone. In a real browser: tests/browser/.
#include "grader/grade/report/html_report.h"

#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

GradeReport sampleReport() {
  GradeReport report;
  report.submission = "subs/<img src=x onerror=alert(1)>";
  report.edition = 2022;
  report.edition_source = "detected";
  report.files = {{"cloth.cpp", "src/<b>cloth.cpp", true, Verdict::Graded, "", 0, ""},
                  {"sphere.cpp", "", false, Verdict::MissingFile, "missing", 0, ""}};
  report.notes = {"non-UTF-8 bytes \xFF in integrator.cpp"};
  TestResult pass = makeTest("Cloth::initializeSpring", "connections at N = 25", 1);
  pass.fraction = 1;
  pass.score = pass.max_score = 6;
  TestResult fail = makeTest("Spheres::collide(Cloth*)", "approaching pair", 1);
  fail.max_score = 1.25;
  fail.output =
      "State tried:\n\n- sphere 0: x (0.1, 0.42, -0.05)\n  - expected x (1, 2, 3) - actual "
      "x (1, 2, 4)\n\n```\n</pre><script>alert(2)</script>\n```\n\n**Likely cause** "
      "(`collision-normal-sign`): <the normal>";
  fail.causes = {Cause{"collision-normal-sign",
                       true,
                       {},
                       {},
                       "<the normal>",
                       "<why> it points inwards",
                       "n = -n;  // mistake <b>\nn = xs - xc;  // fix"}};
  report.tests = {pass, fail};
  report.stub_score = {{"Cloth::initializeSpring", 6}, {"Spheres::collide(Cloth*)", 0}};
  report.stub_max = {{"Cloth::initializeSpring", 6}, {"Spheres::collide(Cloth*)", 1.25}};
  report.score = 6;
  report.max_score = 7.25;
  return report;
}

TEST(HtmlReport, MarkdownBecomesEscapedHtml) {
  const std::string html =
      markdownToHtml("text with `code` and **bold** <i>\n\n- one\n  - two\n\n```\na < b\n```\n");
  EXPECT_EQ(html,
            "<p>text with <code>code</code> and <strong>bold</strong> &lt;i&gt;</p>\n"
            "<ul>\n<li>one</li>\n<li>two</li>\n</ul>\n<pre><code>a &lt; b\n</code></pre>\n");
}

// The summary's file table (report.cpp's filesSection) must not reach Gradescope as raw pipes.
TEST(HtmlReport, MarkdownTablesBecomeHtmlTables) {
  const std::string html = markdownToHtml(
      "before\n| file | used |\n|---|---|\n| cloth.cpp | `a<b` |\n| x.cpp |  |\nafter\n");
  EXPECT_EQ(html,
            "<p>before</p>\n<table>\n<tr><th>file</th><th>used</th></tr>\n"
            "<tr><td>cloth.cpp</td><td><code>a&lt;b</code></td></tr>\n"
            "<tr><td>x.cpp</td><td></td></tr>\n</table>\n<p>after</p>\n");
}

std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A failed collision check's state, in two panels (the whole scene, and the contact up close): in
// each one circle per sphere, a dot per particle, three arrows per body, nothing but static SVG;
// a check without a sketch gets no picture.
TEST(HtmlReport, AFailedCollisionCheckGetsASmallPictureOfTheStateTried) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0",
                           {0.1f, 0.42f, -0.05f},
                           0.5f,
                           {0.3f, -2, 0.1f},
                           {0.3f, -1.98f, 0.1f},
                           {0.3f, -2, 0.1f}});
  sketch.bodies.push_back({"particle 312",
                           {0, 0, 0},
                           0,
                           {0.2f, 0.5f, -0.1f},
                           {-0.35f, -1.8f, 0.17f},
                           {0.2f, 0.5f, -0.1f}});
  const std::string svg = stateSketchSvg(sketch);
  ASSERT_EQ(svg.rfind("<svg ", 0), 0u) << svg;
  EXPECT_EQ(countOf(svg, "<circle "), 4u);
  EXPECT_EQ(countOf(svg, "r=\"3.5\""), 2u);  // the particle's dot
  EXPECT_EQ(countOf(svg, "<line "), 12u);
  EXPECT_EQ(countOf(svg, "marker-end=\"url(#gr-yours)\""), 4u);
  EXPECT_NE(svg.find(">particle 312</text>"), std::string::npos);
  EXPECT_NE(svg.find("around the contact"), std::string::npos);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  // a non-finite velocity loses its arrow, never the picture; a non-finite position, the picture
  sketch.bodies[1].v_actual = {std::nanf(""), 0, 0};
  const std::string without_arrow = stateSketchSvg(sketch);
  EXPECT_EQ(countOf(without_arrow, "<line "), 10u);
  EXPECT_EQ(without_arrow.find("nan"), std::string::npos);
  sketch.bodies[1].x = {std::nanf(""), 0, 0};
  EXPECT_EQ(stateSketchSvg(sketch), "");
  EXPECT_EQ(stateSketchSvg(Sketch{}), "");

  GradeReport report = sampleReport();
  ASSERT_FALSE(report.tests.empty());
  const std::string without = studentReportHtml(report, nullptr);
  EXPECT_EQ(without.find("gr-sketch"), std::string::npos);
  sketch.bodies.pop_back();
  report.tests.back().sketch = sketch;
  const std::string with = studentReportHtml(report, nullptr);
  EXPECT_EQ(countOf(with, "<svg class=\"gr-sketch\""), 1u);
  EXPECT_EQ(with.find("<script"), std::string::npos);
}

// Labels never cover each other: a particle on a sphere's surface, a second sphere touching the
// first, and a second particle beside the first (the cases' usual shapes), in both panels.
TEST(HtmlReport, SketchLabelsNeverCoverEachOther) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0, 0}, {0, -1, 0}});
  sketch.bodies.push_back({"sphere 1", {0.95f, 0.5f, 0}, 0.5f, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  sketch.bodies.push_back({"particle 312", {0, 0, 0}, 0, {0, 0.2f, 0}, {0, 0, 0}, {0, 0.2f, 0}});
  sketch.bodies.push_back({"particle 313", {0.02f, 0.01f, 0}, 0, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  const std::string svg = stateSketchSvg(sketch);
  ASSERT_FALSE(svg.empty());
  // every label: x, y of its baseline and its text, per panel (the second panel starts at x 326)
  struct Label {
    double x, y;
    std::string text;
  };
  std::vector<Label> found;
  const std::string open = "<text x=\"";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1)) {
    const double x = std::stod(svg.substr(at + open.size()));
    const std::size_t y_at = svg.find("y=\"", at) + 3;
    const double y = std::stod(svg.substr(y_at));
    const std::size_t text_at = svg.find('>', at) + 1;
    const std::string text = svg.substr(text_at, svg.find('<', text_at) - text_at);
    if (text.rfind("sphere ", 0) == 0 || text.rfind("particle ", 0) == 0)
      found.push_back({x, y, text});
  }
  EXPECT_GE(found.size(), 4u) << svg;  // all four in the overview at least
  for (std::size_t i = 0; i < found.size(); ++i)
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      const Label& a = found[i];
      const Label& b = found[j];
      const bool apart = a.x + 6.2 * double(a.text.size()) <= b.x ||
                         b.x + 6.2 * double(b.text.size()) <= a.x || a.y <= b.y - 12 ||
                         b.y <= a.y - 12;
      EXPECT_TRUE(apart) << a.text << " at " << a.x << "," << a.y << " covers " << b.text << " at "
                         << b.x << "," << b.y;
    }
}

// A failed springs check: the grid's dots and one line per spring that differs, each kind in its
// own style and counted in the legend; springs outside the cloth are left to the text.
TEST(HtmlReport, AFailedSpringsCheckGetsTheGridWithTheSpringsThatDiffer) {
  Sketch sketch;
  sketch.grid = 4;
  sketch.missing = {{0, 5}, {1, 6}};
  sketch.unexpected = {{0, 2}, {3, 99}};  // 99 is outside a 4 x 4 cloth
  sketch.differing = {{4, 5}};
  sketch.differing_means = "wrong <label>";
  const std::string svg = stateSketchSvg(sketch);
  ASSERT_EQ(svg.rfind("<svg ", 0), 0u) << svg;
  EXPECT_EQ(countOf(svg, "<circle "), 16u);
  // one path per kind, one "M" per spring drawn
  const auto springsDrawn = [&](const std::string& kind) {
    const std::string start = "<path class=\"gr-" + kind + "\" d=\"";
    const std::size_t at = svg.find(start);
    if (at == std::string::npos) return std::size_t{0};
    const std::size_t from = at + start.size();
    return countOf(svg.substr(from, svg.find('"', from) - from), "M");
  };
  EXPECT_EQ(springsDrawn("missing"), 2u);
  EXPECT_EQ(springsDrawn("unexpected"), 1u);
  EXPECT_EQ(springsDrawn("differing"), 1u);
  EXPECT_NE(svg.find("missing (2)"), std::string::npos) << svg;
  EXPECT_NE(svg.find("only yours (2)"), std::string::npos) << svg;
  EXPECT_NE(svg.find("wrong &lt;label&gt; (1)"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("<label>"), std::string::npos);
  // a passed check (no grid, no bodies) and a cloth too large to draw get none
  sketch.grid = 0;
  EXPECT_EQ(stateSketchSvg(sketch), "");
  sketch.grid = 1000;
  EXPECT_EQ(stateSketchSvg(sketch), "");
}

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

TEST(HtmlReport, GradescopeSummaryIsStaticHtml) {
  nlohmann::ordered_json results = {{"score", 6},
                                    {"output", "Edition 2022. **Verdict** <graded>."},
                                    {"output_format", "md"},
                                    {"tests", {{{"name", "x"}, {"output_format", "md"}}}}};
  const auto html = withHtmlSummary(results, sampleReport());
  EXPECT_EQ(html["output_format"], "html");
  EXPECT_EQ(html["tests"][0]["output_format"], "md");
  const std::string output = html["output"].get<std::string>();
  EXPECT_NE(output.find("<td>Spheres::collide(Cloth*)</td><td>0 / 1.25</td><td>0 of 1</td>"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("<li>Spheres::collide(Cloth*): approaching pair <em>(collision-normal-"
                        "sign)</em></li>"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("<strong>Verdict</strong> &lt;graded&gt;."), std::string::npos);
  EXPECT_EQ(output.find("<script"), std::string::npos);
  EXPECT_EQ(output.find("<style"), std::string::npos);
}

TEST(HtmlReport, ClassPageFromTheBatchFolders) {
  const test::TempDir dir;
  BatchRow a;
  a.name = "alice";
  a.verdict = grader::Verdict::Graded;
  a.score = 5;
  BatchRow b = a;
  b.name = "bob";  // no results.json: a row without checks
  fs::create_directories(dir.path() / "alice");
  test::writeText(dir.path() / "alice" / "results.json",
                  R"({"tests": [{"name": "Cloth::initializeSpring: count", "status": "failed",
                      "tags": ["Cloth::initializeSpring", "backup-</script>-aliases"]}]})");
  test::writeText(dir.path() / "alice" / "report.html", "x");
  const std::string page = batchIndexHtml(dir.path(), {a, b});
  const std::string open = "<script type=\"application/json\" id=\"class-data\">";
  const std::size_t begin = page.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = page.find("</script>", begin);
  ASSERT_NE(end, std::string::npos);
  const auto data =
      nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
  ASSERT_EQ(data["submissions"].size(), 2u);
  EXPECT_EQ(data["checks"], nlohmann::json({"Cloth::initializeSpring: count"}));
  // a results.json without extra_data: its tags, each taken as likely
  EXPECT_EQ(data["submissions"][0]["causes"],
            nlohmann::json::parse(R"([{"id": "backup-</script>-aliases", "likely": true}])"));
  EXPECT_EQ(data["submissions"][0]["checks"]["0"], false);
  EXPECT_EQ(data["submissions"][0]["report"], "alice/report.html");
  EXPECT_EQ(data["submissions"][1]["report"], "bob/report.md");
  EXPECT_TRUE(data["submissions"][1]["checks"].empty());
}

}  // namespace
}  // namespace clothref::grader
