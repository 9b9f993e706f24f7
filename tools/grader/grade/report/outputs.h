// Writers for a GradeReport: Gradescope results.json, JUnit XML and a Markdown report. Whatever
// bytes the report holds (a submission controls many of them), each output is valid UTF-8, the
// XML is well-formed and no control character reaches a terminal: the writers clean every text
// with text.h first and add a note saying what was decoded or replaced.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "grader/grade/results.h"

namespace clothref::grader {

// Gradescope's results.json: top-level score, execution_time, output (Markdown summary) and one
// test per check with name ("<course stub>: <check>"), score, max_score, status, output
// (Markdown), output_format "md", visibility and tags (stub and diagnosis ids).
nlohmann::ordered_json resultsJson(const GradeReport& report);

// JUnit XML: one testsuite per submission, one testcase per check (classname = course stub),
// a <failure> with the feedback for each failed check.
std::string junitXml(const GradeReport& report);

// A Markdown report for staff and students: score per stub, files used, notes, then each failed
// check with its feedback and the list of passed checks.
std::string markdownReport(const GradeReport& report);

// One line for stderr: "graded DIR (2022): 72.5 / 80".
std::string summaryLine(const GradeReport& report);

}  // namespace clothref::grader
