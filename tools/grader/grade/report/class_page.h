// BATCHDIR/index.html, the class at a glance (docs/pictures.md), built from the batch's markers
// (each folder's row.json, as grades.csv is) and each folder's results.json (which checks passed,
// which causes the grader named), so an interrupted and resumed batch gets the same page as one
// that ran through. Self-contained: its script and data are inline and it loads nothing; every
// name a student controls reaches it as JSON data set with textContent, never as markup.
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// One submission of the class overview, as plain data: its batch row (row.json's fields) and,
// from its results.json, each check's outcome and the causes named.
struct ClassRow {
  std::string name;                                    // the submission's folder in BATCHDIR
  int edition = 0;                                     // 0 when not gradable
  std::map<std::string, double> stub_score, stub_max;  // per course stub
  double score = 0, max_score = 0;
  Verdict verdict = Verdict::Graded;
  std::string problem;    // why it is not gradable, else empty
  double seconds = 0;     // wall time of grading it
  std::string isolation;  // how its student code was isolated (the page says each once)
  std::string report;     // its report, relative to BATCHDIR ("alice/report.html")
  std::vector<std::pair<std::string, bool>> checks;  // check name, passed; results.json's order
  std::vector<std::pair<std::string, bool>> causes;  // cause id, likely on some check
};

// The class overview: a first line saying how many were graded and how many need attention and
// why (their verdicts), how student code was isolated (each description once), a sortable,
// filterable table (score per stub, total, verdict, causes, time, report link) with its legend, a
// histogram of totals, the pass rate per stub and per check, and per named cause the submissions
// it was found in.
std::string batchIndexHtml(const std::vector<ClassRow>& rows);

}  // namespace clothref::grader
