// How the collision and spring-force probes name the causes of their failed checks, from two kinds
// of evidence (docs/grading-reference.md, "Collisions and spring forces explained by the constants
// that fit"): mistake variants (formula_variants.h) run on every case, and quantities read back
// from the student's numbers (contact_fit.h, spring_fit.h). One rule for both probes: a cause is
// likely only when it explains every case; a variant that matches some cases only is a guess.
#pragma once
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

struct CauseEvidence {
  std::vector<std::string> variant_ids;  // the catalogue id of each mistake variant
  // [case][variant]: the variant's result differs from the course's there (beyond the check's
  // tolerance), and it gives the student's numbers (within 10 x the tolerance).
  std::vector<std::vector<bool>> differs, matches;
  std::vector<bool> passed;  // [case]
  struct Finding {
    std::string cause, text;  // a catalogue id; what was measured, for the student
  };
  std::vector<Finding> findings;  // quantities read back the same from every case
  // [case]: causes measured directly (a fixed particle moved, NaN out of the call), shown when
  // nothing likely explains that case.
  std::vector<std::vector<std::string>> measured;
};

// The evidence for `cases` cases and the variants `ids`, nothing matched yet.
CauseEvidence makeEvidence(std::size_t cases, std::vector<std::string> ids);

// Whether variant m explains every case: it gives the student's numbers wherever it differs from
// the course, and the student's failed cases are all among those.
bool explainsEveryCase(const CauseEvidence& evidence, std::size_t m);

// The likely causes: the variants that explain every case, or else the findings.
std::set<std::string> likelyCauses(const CauseEvidence& evidence);

// Writes the causes of each failed test, tests[k] being case k: the likely causes it shows (a
// variant's where it matches, a finding's where `finding_applies[k]`, its measurement once per
// stub, later checks referring to the first), else the measured ones, else `unknown` followed by
// the variants this case alone matches, as guesses.
void nameCauses(const CauseEvidence& evidence, const std::set<std::string>& likely,
                const std::vector<bool>& finding_applies, std::vector<TestResult>& tests);

}  // namespace clothref::grader
