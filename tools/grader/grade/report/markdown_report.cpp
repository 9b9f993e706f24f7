// report.md (outputs.h, markdownReport): a stub as a student reads it in a minute (stub_text.h).
#include <sstream>

#include "grader/grade/report/outputs.h"
#include "grader/grade/report/stub_text.h"
#include "grader/grade/text.h"

namespace clothref::grader {

std::string markdownReport(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  const std::vector<TestText> texts = testTexts(report);
  const std::vector<StubText> stubs = stubTexts(report);
  std::ostringstream out;
  out << "# Grading report: " << codeSpan(report.submission) << "\n\n";
  out << "Edition " << report.edition << " (" << report.edition_source << "). **Code score "
      << points(report.score) << " / " << points(report.max_score) << "**. Verdict: **"
      << verdictId(report.verdict) << "**.\n\n";
  if (!report.isolation.empty()) out << "Student code ran with: " << report.isolation << ".\n\n";
  // the stubs at a glance: the likely causes by id, the text under each stub below
  out << "| stub | points | checks passed | likely causes |\n|---|---|---|---|\n";
  for (const StubText& stub : stubs) {
    if (!report.stub_max.count(stub.stub)) continue;
    std::string ids;
    for (const auto& [id, likely] : stub.ids)
      if (likely) ids += (ids.empty() ? "" : ", ") + codeSpan(id);
    out << "| `" << stub.stub << "` | " << points(report.stub_score.at(stub.stub)) << " / "
        << points(report.stub_max.at(stub.stub)) << " | " << stub.passed.size() << " of "
        << stub.checks << " | " << ids << " |\n";
  }
  out << "\n## Files\n\n" << filesMarkdown(report);
  if (!report.notes.empty()) out << "\n" << notesMarkdown(report.notes);
  out << "\n" << kNumberLegend << "\n";
  bool all_passed = true;
  for (const StubText& stub : stubs) {
    if (stub.failed.empty()) continue;
    all_passed = false;
    out << "\n## " << stub.stub << "\n\n" << stub.points << "\n\n";
    if (!stub.likely.empty() || !stub.guesses.empty()) out << stub.causesMarkdown() << "\n";
    out << stub.tableMarkdown();
    // the first failed check in full: the state it tried, every quantity it compared
    const TestResult& first = report.tests[stub.failed.front().test];
    if (!first.output.empty())
      out << "\nThe first failed check in full (" << first.check << "):\n\n"
          << first.output << (first.output.back() == '\n' ? "" : "\n");
    if (!stub.passed.empty()) out << "\n" << stub.passedMarkdown(report);
  }
  if (all_passed) out << "\nEvery check passed.\n";
  std::string passed_stubs;
  for (const StubText& stub : stubs)
    if (stub.failed.empty() && stub.checks > 0)
      passed_stubs += (passed_stubs.empty() ? "" : ", ") + codeSpan(stub.stub);
  if (!all_passed && !passed_stubs.empty())
    out << "\n## Every check passed\n\n" << passed_stubs << ".\n";
  for (std::size_t k = 0; k < report.tests.size(); ++k)
    if (report.tests[k].informational)
      out << "\n## " << report.tests[k].name() << ": " << statusWord(report.tests[k]) << "\n\n"
          << texts[k].markdown() << "\n";
  return out.str();
}

}  // namespace clothref::grader
