// The catalogue of known mistakes (tools/grader/diagnoses.json): what each cause id means, how the
// grader recognises it, why it gives the numbers a student sees and a two-line example of the
// mistake and its fix. The probes name causes by id (the constants of the generated header
// grader/grade/cause_ids.h, one per id of the JSON, so a mistyped id does not build); the writers
// render them from the texts filled in here.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// One entry of the catalogue. The JSON's "stub" is for the docs table only
// (docs/grading-reference.md).
struct Diagnosis {
  std::string id;
  std::string recognised_by;  // "signature", "property", "guess", "signature + pattern", ...
  std::string text;           // what the mistake is, in one or two sentences
  std::string why;            // why it gives the numbers the student sees (a paragraph)
  std::string example;        // the mistaken line and its fix, two lines of C++; may be empty
  // "non_finite" (optional, default false): the mistake's model can make NaN or infinity from the
  // probe's finite inputs (a division by a zero mass or speed, a method that blows up); a cause
  // without it is never likely on a check whose answers are non-finite (rubric.h, markNonFinite).
  bool non_finite = false;
};

struct Catalogue {
  std::map<std::string, Diagnosis> entries;
};

// Reads the catalogue at `path`. Throws InputError, one line "<path>: <JSON pointer>: <problem>",
// for a file that is missing or not JSON, a missing, empty or mistyped field, an unknown field,
// an id that is not lower-case words joined by '-', an unknown "recognised_by" or an id given
// twice.
Catalogue loadCatalogue(const std::filesystem::path& path);

// Each cause of `tests` gets the catalogue's text, why and example for its id (Cause::text, why,
// example), and is a guess when the catalogue recognises it only by guessing (`unknown`). The
// probes name causes as data; the writers render them (report/outputs.h), so no text of a cause
// is written anywhere else.
void fillCauseTexts(const Catalogue& catalogue, std::vector<TestResult>& tests);

}  // namespace clothref::grader
