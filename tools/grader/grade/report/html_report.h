// The grader's HTML pages (docs/pictures.md): the report a student reads (`clothref grade --html
// FILE`, BATCHDIR/<name>/report.html) and BATCHDIR/index.html, the class at a glance.
//
// The student's report: per stub the score and every check with its output (expected and actual,
// the named cause), the whole run's cloth, the student's beside the reference, at a few times and
// in the embedded trace viewer. For Gradescope, whose results.json shows HTML but runs no script,
// a static summary of the same (gradescopeSummaryHtml) replaces the top-level output.
//
// Built from the batch's markers (each folder's row.json, as grades.csv is) and each folder's
// results.json (which checks passed, which named causes the grader gave), so an interrupted and
// resumed batch gets the same page as one that ran through. A page is self-contained: its script
// and data are inline and it loads nothing. Every name a student controls reaches the page as
// JSON data set with textContent, never as markup.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "grader/grade/batch.h"
#include "grader/grade/grade.h"

namespace clothref::grader {

// The class overview for `rows` (the batch's, sorted by name) of the batch in `batch_dir`: a
// sortable, filterable table (score per stub, total, verdict, time, report link), a histogram of
// totals, the pass rate per stub and per check, and per named cause the submissions it was found
// in. A folder whose results.json is missing or unreadable still gets its row, without checks.
std::string batchIndexHtml(const std::filesystem::path& batch_dir,
                           const std::vector<BatchRow>& rows);

// gradeSubmission, keeping the whole run's two traces (reference and student) long enough to turn
// them into viewer data (pages/view_data.h) in `whole_run_view`; null when the whole run wrote
// none (not run, or the student's simulation did not finish). Uses options.keep_work when set,
// else a temporary copy of the scratch folder that is removed before returning.
GradeReport gradeWithWholeRun(const std::filesystem::path& dir, const GradeOptions& options,
                              nlohmann::ordered_json& whole_run_view);

// The student's report page; `whole_run_view` as from gradeWithWholeRun (null: no pictures).
std::string studentReportHtml(const GradeReport& report,
                              const nlohmann::ordered_json& whole_run_view);

// `results` (resultsJson's) with its top-level "output" turned into static HTML (no script, no
// style element: Gradescope shows HTML but runs nothing) and "output_format": "html": the score
// per stub, the failed checks with their causes, then the Markdown summary as HTML. The tests keep
// their Markdown outputs.
nlohmann::ordered_json withHtmlSummary(nlohmann::ordered_json results, const GradeReport& report);

// The state a failed check tried, as a small static SVG (no script, no text from the student);
// "" for an empty sketch. A collision check: the bodies seen from the front (x right, y up),
// spheres as circles, cloth particles as dots, and from each body its velocity before the call
// (grey), after the course's collide (green) and after the student's (red), all arrows on one
// scale. A springs check: the n x n cloth as dots, row 0 at the top, and the springs the course
// has and the student lacks (green, dashed), that only the student has (red), and that differ
// (orange).
std::string stateSketchSvg(const Sketch& sketch);

// The grader's Markdown (paragraphs, "- " lists, "| a | b |" tables, ``` blocks, `code`, **bold**)
// as HTML; every
// character of the text is escaped first, so nothing in it becomes markup of its own.
std::string markdownToHtml(std::string_view markdown);

}  // namespace clothref::grader
