// Patterns in a student's source: what the text says, only ever to refine a finding the probes
// measured (a crash, numbers equal to a simulated mistake), never to make one
// (docs/grading-reference.md, "Diagnoses").
#pragma once
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// Lines that hold an Eigen *expression* in an `auto` variable (e.g. `auto d = p.position(i) -
// p.position(j);`): it refers to temporaries that are gone when it is read. Not when the
// expression ends in a call that returns a plain value (`.normalized()`, `.eval()`, `.norm()`,
// `.dot(...)`, `.cross3(...)`): those hold a vector or a number and nothing dangles.
std::vector<SourceQuote> autoExpressionLines(const std::string& file, const std::string& source);

// What the stub's source says, for refining measured findings only.
struct SourceHints {
  bool alias_backup = false;   // `auto b = particles;`, a Particles* vector or Eigen::Ref copy
  bool integer_half = false;   // `1 / 2` with integer literals
  bool integer_sixth = false;  // `1 / 6`
  bool value_backup = false;   // a real copy: std::vector<Particles>, a Particles or Matrix4Xf
};
// A corrector that steps from the prediction gives the numbers of a backup that follows the live
// state; a stub whose backup is a real copy and no view wrote the first.
inline bool copiesButNoView(const SourceHints& hints) {
  return hints.value_backup && !hints.alias_backup;
}
// The hints of a stub's body (stubCode: comments and literals blanked).
SourceHints sourceHints(const std::string& stub_source);

}  // namespace clothref::grader
