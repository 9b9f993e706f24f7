// The student's report page (docs/pictures.md): `clothref grade --html FILE`,
// BATCHDIR/<name>/report.html. Per stub the score and every check with its output (expected and
// yours, the likely causes and the guesses), a picture of the state a failed check tried, and the
// whole run's cloth, the student's beside the reference, at a few times and in the embedded trace
// viewer. Self-contained: its script and data are inline and it loads nothing; every name a
// student controls reaches it escaped, or as JSON data set with textContent.
//
// The other pages and pictures have files of their own, included here for the writers that use
// them all (batch.cpp, the CLI): class_page.h (BATCHDIR/index.html), gradescope_html.h (what
// results.json gives as HTML), sketch_svg.h and whole_run_svg.h (the pictures), markdown_html.h.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "grader/grade/grade.h"
#include "grader/grade/report/class_page.h"
#include "grader/grade/report/gradescope_html.h"
#include "grader/grade/report/markdown_html.h"
#include "grader/grade/report/sketch_svg.h"
#include "grader/grade/report/whole_run_svg.h"

namespace clothref::grader {

// gradeSubmission, keeping the whole run's two traces (reference and student) long enough to turn
// them into viewer data (pages/view_data.h) in `whole_run_view`; null when the whole run wrote
// none (not run, or the student's simulation did not finish). Uses options.keep_work when set,
// else a temporary copy of the scratch folder that is removed before returning.
GradeReport gradeWithWholeRun(const std::filesystem::path& dir, const GradeOptions& options,
                              nlohmann::ordered_json& whole_run_view);

// The student's report page; `whole_run_view` as from gradeWithWholeRun (null: no viewer).
std::string studentReportHtml(const GradeReport& report,
                              const nlohmann::ordered_json& whole_run_view);

}  // namespace clothref::grader
