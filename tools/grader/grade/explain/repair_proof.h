// Causes proven by repair (docs/grading-reference.md, "Likely means proven"): a mistake in the
// source (an `auto` holding an Eigen expression over temporaries, an integer division, a backup
// that is a vector of pointers or an Eigen::Ref view, the result of `normalized()` discarded, the
// global deltaTime changed) is repaired on its quoted lines in a private copy of the file; the
// grader rebuilds that one file, probes the stub again and says what the repair changed ("With
// line 129's `auto` expression stored as a vector: 6 of 8 checks pass; the other 2 are explained
// by `wrong-mass-split` (proven)"). A repair that does not build or changes nothing disproves the
// cause.
//
// Pure text and data: the probes room builds and probes (probes/repair.cpp).
// The repairs are made in repair_proof.cpp and judged in repair_judgement.cpp.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// One repair of one pattern of a stub.
struct Repair {
  std::string file;                // "integrator.cpp"
  std::string stub;                // the course name of the stub whose lines it repairs
  std::string cause;               // the catalogue id the pattern stands for
  std::vector<SourceQuote> lines;  // the repaired lines, as the student wrote them
  std::string patched;             // the whole file with those lines repaired
  std::string what;                // "line 129's `auto` expression stored as a vector"
};

// The repairs of `stub` in `source` (the bytes of `file`): one per kind of pattern found inside
// the stub's body (comments and literals ignored), all its lines repaired together.
std::vector<Repair> repairsOf(const std::string& file, const std::string& source,
                              const std::string& stub);

// Judges `repair` on the stub's `tests` (in place) from the tests of the repaired build
// (`repaired`, the same checks in the same order; ignored when `built` is false, `problem` then
// saying why). Proven when a failed check passes after the repair: the cause is named likely on
// each check the repair mends, with the line "With line N ...: X of T checks pass; ..." as its
// proof, and the other causes of those checks become guesses (the repair shows they were not the
// mistake); a check still failing takes the repaired build's causes. Otherwise the cause, where
// named, is a guess whose line says what the repair did. Returns whether it was proven.
bool applyRepair(const Repair& repair, bool built, const std::string& problem,
                 const std::vector<TestResult>& repaired, std::vector<TestResult>& tests);

// A stub that passes every check but holds a local declared without a value and first used in a
// compound assignment (`float sum; sum += ...`): the same file with those locals starting at 1,
// which a stub whose numbers do not rest on them passes alike. None: no such local.
std::optional<Repair> unsetStartProbe(const std::string& file, const std::string& source,
                                      const std::string& stub);

// Judges that probe on the passing stub's `tests` (in place) from the started build's checks
// (`started`, the same checks in the same order). When checks fail there, the stub's numbers rest
// on a value the code never sets (its build happened to give the course's): those checks fail
// with `undefined-behaviour` proven by that line, and the others keep their pass. Returns whether.
bool applyUnsetStart(const Repair& probe, bool built, const std::vector<TestResult>& started,
                     std::vector<TestResult>& tests);

}  // namespace clothref::grader
