// BATCHDIR/index.html, the class at a glance (docs/pictures.md), built from the batch's markers
// (each folder's row.json, as grades.csv is) and each folder's results.json (which checks passed,
// which causes the grader named), so an interrupted and resumed batch gets the same page as one
// that ran through. Self-contained: its script and data are inline and it loads nothing; every
// name a student controls reaches it as JSON data set with textContent, never as markup.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "grader/grade/batch.h"

namespace clothref::grader {

// The class overview for `rows` (the batch's, sorted by name) of the batch in `batch_dir`: a
// sortable, filterable table (score per stub, total, verdict, time, report link), a histogram of
// totals, the pass rate per stub and per check, and per named cause the submissions it was found
// in. A folder whose results.json is missing or unreadable still gets its row, without checks.
std::string batchIndexHtml(const std::filesystem::path& batch_dir,
                           const std::vector<BatchRow>& rows);

}  // namespace clothref::grader
