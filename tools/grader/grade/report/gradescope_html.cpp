// What Gradescope shows as HTML (gradescope_html.h).
#include "grader/grade/report/gradescope_html.h"

#include <string>
#include <vector>

#include "grader/grade/report/markdown_html.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/report/sketch_svg.h"
#include "grader/grade/report/whole_run_svg.h"
#include "pages/html.h"

namespace clothref::grader {
namespace {

// A failed check's line of the summary: its name, then its likely causes and its guesses on lines
// of their own.
std::string failedLine(const TestResult& t) {
  std::string likely, guesses;
  for (const Cause& cause : t.causes)
    (cause.likely ? likely : guesses) +=
        std::string((cause.likely ? likely : guesses).empty() ? "" : ", ") + "<em>" +
        pages::escapeHtml(cause.id) + "</em>";
  return "<li>" + pages::escapeHtml(t.name()) +
         (likely.empty() ? "" : "<br>likely cause: " + likely) +
         (guesses.empty() ? "" : "<br>possible cause (a guess): " + guesses) + "</li>\n";
}

}  // namespace

std::string testPicture(const TestResult& test, std::size_t index) {
  if (test.passed()) return {};
  const std::string id = "gr-test-" + std::to_string(index);
  if (test.traces) return wholeRunSvg(*test.traces, id);
  return stateSketchSvg(test.sketch, id);
}

nlohmann::ordered_json withHtmlSummary(nlohmann::ordered_json results, const GradeReport& given) {
  const GradeReport report = cleaned(given);
  std::string out = "<p><strong>Score " + points(report.score) + " / " + points(report.max_score) +
                    "</strong> (edition " + std::to_string(report.edition) + ", verdict " +
                    std::string(verdictId(report.verdict)) +
                    ")</p>\n<table>\n<tr><th>stub</th>"
                    "<th>points</th><th>checks passed</th></tr>\n";
  for (const std::string& stub : stubNames()) {
    if (!report.stub_max.count(stub)) continue;
    const auto [passed, total] = checksPassed(report, stub);
    out += "<tr><td>" + pages::escapeHtml(stub) + "</td><td>" +
           points(report.stub_score.count(stub) ? report.stub_score.at(stub) : 0) + " / " +
           points(report.stub_max.at(stub)) + "</td><td>" + std::to_string(passed) + " of " +
           std::to_string(total) + "</td></tr>\n";
  }
  out += "</table>\n";
  std::string failed;
  int not_shown = 0;  // failed tests the rubric shows later or never: not named here either
  for (const TestResult& t : report.tests) {
    if (t.passed() || t.informational) continue;
    if (t.visibility != "visible") {
      ++not_shown;
      continue;
    }
    failed += failedLine(t);
  }
  if (!failed.empty())
    out += "<p>Failed checks (details in each test below):</p>\n<ul>\n" + failed + "</ul>\n";
  if (not_shown)
    out += "<p>" + std::to_string(not_shown) + " more failed check" + (not_shown == 1 ? "" : "s") +
           " shown later.</p>\n";
  if (results.contains("output") && results["output"].is_string())
    out += markdownToHtml(results["output"].get<std::string>());
  results["output"] = out;
  results["output_format"] = "html";
  // The tests with a picture: HTML, the picture first (tests and report.tests are in one order).
  if (!results.contains("tests") || !results["tests"].is_array() ||
      results["tests"].size() != report.tests.size())
    return results;
  const std::vector<TestText> texts = testTexts(report);
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    const std::string picture = testPicture(report.tests[k], k);
    if (picture.empty()) continue;
    results["tests"][k]["output"] =
        "<div class=\"gr-picture\">" + picture + "</div>\n" + testHtml(texts[k]);
    results["tests"][k]["output_format"] = "html";
  }
  return results;
}

}  // namespace clothref::grader
