// What Gradescope shows as HTML (gradescope_html.h).
#include "grader/grade/report/gradescope_html.h"

#include <algorithm>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/report/markdown_html.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/report/sketch_svg.h"
#include "grader/grade/report/whole_run_svg.h"
#include "pages/html.h"

namespace clothref::grader {
namespace {

// What is wrong with a stub, on one line: its likely causes, then its guesses marked "?".
std::string causesLine(const GradeReport& report, const std::string& stub) {
  std::vector<std::pair<std::string, bool>> named;
  for (const TestResult& t : report.tests) {
    if (t.stub != stub || t.passed() || t.informational) continue;
    for (const Cause& cause : t.causes) {
      auto it = std::find_if(named.begin(), named.end(),
                             [&](const auto& n) { return n.first == cause.id; });
      if (it == named.end())
        named.push_back({cause.id, cause.likely});
      else
        it->second = it->second || cause.likely;
    }
  }
  std::string out;
  for (bool likely : {true, false})
    for (const auto& [id, is_likely] : named)
      if (is_likely == likely)
        out += std::string(out.empty() ? "" : ", ") + "<em>" + pages::escapeHtml(id) + "</em>" +
               (likely ? "" : "?");
  return out;
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
  // One line per stub that lost points: its points, its checks passed, what is wrong; the stubs
  // whose every check passed on one line after them.
  std::string rows, passed_stubs;
  const std::set<std::string> later = stubsShownLater(report);
  for (const std::string& stub : stubNames()) {
    if (!report.stub_max.count(stub) || later.count(stub)) continue;
    const auto [passed, total] = checksPassed(report, stub);
    const std::string score =
        points(report.stub_score.count(stub) ? report.stub_score.at(stub) : 0) + " / " +
        points(report.stub_max.at(stub));
    if (passed == total)
      passed_stubs += (passed_stubs.empty() ? "" : ", ") + pages::escapeHtml(stub) + " " + score;
    else
      rows += "<tr><td>" + pages::escapeHtml(stub) + "</td><td>" + score + "</td><td>" +
              std::to_string(passed) + " of " + std::to_string(total) + "</td><td>" +
              causesLine(report, stub) + "</td></tr>\n";
  }
  // with a stub shown later the Markdown summary below says why there is no score yet
  std::string out = later.empty() ? "<p><strong>Score " + points(report.score) + " / " +
                                        points(report.max_score) + "</strong> (edition " +
                                        std::to_string(report.edition) + ", verdict " +
                                        std::string(verdictId(report.verdict)) + ")</p>\n"
                                  : std::string();
  if (!rows.empty())
    out +=
        "<table>\n<tr><th>stub</th><th>points</th><th>checks passed</th><th>what is wrong "
        "(a guess: ?; each test below says why)</th></tr>\n" +
        rows + "</table>\n";
  if (!passed_stubs.empty()) out += "<p>Every check passed: " + passed_stubs + ".</p>\n";
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
