// Writers for a GradeReport: Gradescope results.json, JUnit XML and a Markdown report. Whatever
// bytes the report holds (a submission controls many of them), each output is valid UTF-8, the
// XML is well-formed and no control character reaches a terminal: the writers clean every text
// with text.h first and add a note saying what was decoded or replaced. In Markdown, text a
// submission controls is only ever inside a code block or span (text.h), so no renderer makes an
// element of it.
//
// One truth: every output renders the same data the same way. A test's Markdown is its output,
// then its causes (results.h's Cause: the likely ones, then the guesses, each its own block, with
// the catalogue's text; a likely one also with the catalogue's why and example), repeats folded;
// a stub as a student reads it (stub_text.h) shows the same causes once; the tags, badges and
// the class overview list the same causes; points are shown rounded to 0.001 everywhere
// (points()).
#pragma once
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// How the checks' numbers read (explain/compare_text.h writes them), said once at the top of every
// report (results.json's summary, report.md, report.html) and in docs/grading-reference.md.
inline constexpr const char* kNumberLegend =
    "How to read the checks: numbers have 6 significant digits (C's `%.6g`: 0.000371004, "
    "7.45961e-05), and the numbers of one comparison share one notation. Where yours differs from "
    "the expected value by more than the tolerance, that component is **bold** in both, and the "
    "line under it says by how much and how many times the tolerance that is (the tolerance and "
    "the ratio to 2 significant digits).";

// Checks of `stub` that count for points, and how many of them passed (the pages' stub tables).
std::pair<int, int> checksPassed(const GradeReport& report, const std::string& stub);

// The stubs a student sees later than the summary, or never: those with a check whose visibility
// (the rubric's) is not "visible". Before their release nothing a student sees names their points,
// checks passed or causes: the summaries leave them out, and the total and the verdict with them
// (both count them); the per-mistake line (how every check of a stub went) is left out of a stub
// whose checks are shown at different times.
std::set<std::string> stubsShownLater(const GradeReport& report);

// What a summary says of the whole: `score` "12 / 27.25" `verdict` "graded." ("Code score ",
// ". Verdict: "), or, with a stub shown later, that the score and the verdict come later.
std::string scoreSentence(const GradeReport& report, const std::string& score,
                          const std::string& verdict);

// Points as every output shows them: rounded to 0.001, without trailing zeros ("51.875", "80").
std::string points(double value);
// The same rounding as a JSON number (results.json, row.json readers).
double roundedPoints(double value);

// The report with every text made safe (text.h): valid UTF-8 (Big5 lines decoded, other bytes
// U+FFFD), control characters escaped, names on one line; plus a note saying what was done. And
// without how the probe's run ended (`crashed`, `timed-out` or `undefined-behaviour`) where
// another likely cause of the same check is what made it end so. Every
// writer starts from this, so every output names the same causes.
GradeReport cleaned(const GradeReport& report);

// The one cause renderer (every writer's text of a cause comes from here, from the catalogue's
// texts on the Cause): the head line ("**Likely cause** (`id`): text" or "**Possible cause (a
// guess)** (`id`): text"); under it, in one paragraph, what the probe measured for this check
// (`detail`: the place of a cause's one line of proof); for a likely cause the catalogue's why
// and example; then the quoted source lines, inside `stub`. Shown again for a later check of the
// same stub (`explained_under` names the check that explained it): the head names the id and
// where it was explained, what this check measured stays, the why and example are left out, and
// the lines only when they differ (`quote`). A cause whose why and example an earlier stub showed
// (`why_under` names that stub) keeps its head, measure, proof and lines, and refers to them.
struct CauseShown {
  std::string explained_under;  // empty: the first time
  bool quote = true;
  std::string why_under;  // empty: the why and example shown here
};
std::string causeMarkdown(const Cause& cause, const std::string& stub, const CauseShown& shown);

// What a writer shows of one test of a cleaned report (results.json's tests, JUnit's failures):
// its output (Markdown), then its causes as Markdown blocks, the likely ones and the guesses
// apart. Within a stub no text is said twice: an output of several lines equal to an earlier
// failed test's is shown once and referred to afterwards, and a cause is explained in full on the
// first failed test of its stub and visibility that names it (a visible test never refers to one
// the student cannot see yet) and referred to afterwards.
struct TestText {
  std::string output;
  std::vector<std::string> likely, guesses;  // one Markdown block per cause
  std::string markdown() const;              // all of it, as the Markdown writers show it
};
std::vector<TestText> testTexts(const GradeReport& cleaned_report);

// A Markdown line per note ("- ..."), then the notes with a verbatim block, each with its block.
std::string notesMarkdown(const std::vector<Note>& notes);

// "passed" or "failed"; an information-only test: "identical" or "differs".
std::string statusWord(const TestResult& test);

// The files and what became of them, as a Markdown list (a name a submission controls in a code
// span), with each failed build's first error and, folded under it, its whole log.
std::string filesMarkdown(const GradeReport& cleaned_report);

// Gradescope's results.json: top-level score, execution_time, output (Markdown summary) and one
// test per check with name ("<course stub>: <check>"), score, max_score, status, output
// (Markdown), output_format "md", visibility, tags (stub and cause ids) and extra_data (the causes
// with whether each is likely).
nlohmann::ordered_json resultsJson(const GradeReport& report);

// JUnit XML: one testsuite per submission, one testcase per check (classname = course stub),
// a <failure> with the feedback for each failed check.
std::string junitXml(const GradeReport& report);

// A Markdown report for staff and students (markdown_report.cpp): the score, a table of the
// stubs (points, checks passed, what is wrong), the files and notes, then per stub that lost
// points what a student reads in a minute (stub_text.h): its points and the rule, what is wrong,
// the failed checks as a table, the first failed check in full, the passed checks on one line;
// then the information-only checks.
std::string markdownReport(const GradeReport& report);

// One line for stderr: "graded DIR (2022): 72.5 / 80, verdict graded".
std::string summaryLine(const GradeReport& report);

// Lines for stderr about choices the grader made (a name found twice: which copy was used).
std::vector<std::string> choiceLines(const GradeReport& report);

}  // namespace clothref::grader
