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

#include <string>

#include <nlohmann/json.hpp>

#include "grader/grade/report/class_page.h"
#include "grader/grade/report/gradescope_html.h"
#include "grader/grade/report/markdown_html.h"
#include "grader/grade/report/sketch_svg.h"
#include "grader/grade/report/whole_run_svg.h"

namespace clothref::grader {

// The whole run's two traces (reference and student), as the whole-run check of a graded report
// keeps them (TestResult::traces), turned into viewer data (pages/view_data.h); null when the
// whole run wrote none (not run, or the student's simulation did not finish). A student trace the
// reader refuses (cut short by a crash) adds a note to `report` saying the run could not be
// pictured, and gives null.
nlohmann::ordered_json wholeRunView(GradeReport& report);

// The student's report page; `whole_run_view` as from wholeRunView (null: no viewer).
std::string studentReportHtml(const GradeReport& report,
                              const nlohmann::ordered_json& whole_run_view);

}  // namespace clothref::grader
