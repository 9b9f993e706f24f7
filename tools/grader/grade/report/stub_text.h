// What a student reads of one stub, in a minute (report.md, report.html, the Gradescope summary;
// docs/grading-reference.md): first its points and the rule that gave them, then what is
// wrong (each cause its failed checks name, once: the likely ones, then the guesses, each with the
// catalogue's text, the likely ones with its why and example, and the quoted lines), then the
// failed checks as rows (check, expected, yours, by how much), then the passed checks. Made from a
// cleaned report (outputs.h), so it names the same causes and points as every other output.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// A failed check as one row: the first quantity its output compares where yours differs (a line
// of explain/compare_text.h's compareValues: "- LABEL: expected E, yours Y" and, under it, by how
// much), split into its parts, Markdown (the differing components bold); the quantity named with
// the body it belongs to ("sphere 0: v after the call"). A check that compared no quantity (a
// crash, a count of springs, an order) has `yours` only: the sentence of its output's plain text
// that says what it found ("Observed order 0.0112394, ...", "0 missing, ... 162 wrong rest
// lengths"), never a line with a code span (a submission may control what is in one).
struct CheckRow {
  std::size_t test = 0;  // index in the report's tests
  std::string check;     // the check's name, then the quantity: "moving state: a of particle 312"
  std::string expected, yours, by;
};
CheckRow checkRow(const TestResult& test, std::size_t index);

struct StubText {
  std::string stub;
  // Markdown, one paragraph: its points and checks passed, then the rule that gave them: "**12 /
  // 20**, 1 of 8 checks passed. One mistake (`damper-sign`) explains every failed check of this
  // stub: it loses 40 % of its points once (rubric: per-mistake; ...)." (the rubric's line) or
  // "..., 1 of 8 checks passed: scored per check (each failed check loses its own points)."
  std::string points;
  // One Markdown block per cause of the failed checks, each cause once (results.h's Cause as
  // causeMarkdown renders it: head, what was measured, why and example, quoted lines).
  std::vector<std::string> likely, guesses;
  std::vector<std::pair<std::string, bool>> ids;  // the same causes: id, likely (chips, tables)
  std::vector<CheckRow> failed;                   // the scored checks that failed, in order
  std::vector<std::size_t> passed;                // the scored checks that passed (indices)
  std::vector<std::size_t> information;           // information-only checks (the whole run)
  int checks = 0;                                 // scored checks
  // What is wrong (the cause blocks), the table of failed checks, the passed checks on one line.
  std::string causesMarkdown() const;
  std::string tableMarkdown() const;
  std::string passedMarkdown(const GradeReport& report) const;
};

// One per stub that has checks in the report, in the course's order.
std::vector<StubText> stubTexts(const GradeReport& cleaned_report);

}  // namespace clothref::grader
