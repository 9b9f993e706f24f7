// What Gradescope shows as HTML (it shows HTML in results.json but runs no script): the summary
// at the top, and each check that has a picture (docs/pictures.md, "Pictures on Gradescope").
#pragma once
#include <nlohmann/json.hpp>

#include "grader/grade/results.h"

namespace clothref::grader {

// `results` (resultsJson's, for `report`) with
// - its top-level "output" turned into static HTML and "output_format": "html": the score per
//   stub, the failed checks with their likely causes and their guesses apart, then the Markdown
//   summary as HTML;
// - each test that has a picture (a failed collision or springs check's sketch, the whole run's
//   when it differs) given as HTML: the picture as inline SVG, then the test's Markdown (its
//   output, its likely causes, its guesses) rendered to HTML with every character escaped;
//   "output_format": "html" for that test only, the others keep "md".
// No script, no style element, no event attribute, no URL: nothing runs and nothing is loaded.
nlohmann::ordered_json withHtmlSummary(nlohmann::ordered_json results, const GradeReport& report);

// The picture results.json gives test `index` of `report` (inline SVG), or "" for none.
std::string testPicture(const TestResult& test, std::size_t index);

}  // namespace clothref::grader
