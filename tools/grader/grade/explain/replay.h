// A mistake's model replayed on every probe state of a stub (docs/grading-reference.md, "Likely
// means proven"): the library's formula with the mistake's switches, with a fitted constant, or
// a method with the mistake's stages, run on each state the probe tried, and compared with the
// student's numbers on every check of the stub, passed and failed, within each check's
// tolerance. A cause is named as likely only when its model reproduces every check; otherwise the
// report says where the model and the student part, and the cause is at most a guess.
//
// Plain data and one text: the probes run the models and fill the checks.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

// One check of the stub as the model reproduced it: per quantity the check compares
// ("positions", "velocities", "accelerations", "the convergence order"), whether the model gives
// the student's value within the check's tolerance.
struct ReplayCheck {
  std::string check;
  std::vector<std::pair<std::string, bool>> quantities;
  bool reproduced() const {
    for (const auto& q : quantities)
      if (!q.second) return false;
    return true;
  }
};

struct Replay {
  // The model in a student's words: "the course's collide without the position correction".
  std::string model;
  std::vector<ReplayCheck> checks;
  int reproduced() const;
  // Every check reproduced (and there is one).
  bool proven() const;
  // The line under the cause: "Proven: <model> gives your numbers on 8 of 8 checks." or "Not
  // proven: <model> gives your numbers on 5 of 8 checks; on 3 (“approaching pair”, ...) it gives
  // your positions but not your velocities."
  std::string line() const;
};

// Names `ids` as likely on every failed test that names one of them, with the replay's line as
// their proof, when the replay is proven; otherwise as guesses, with the line saying where the
// model parts from the student (a proof line is never overwritten by a weaker one).
void applyReplay(const Replay& replay, const std::vector<std::string>& ids,
                 std::vector<TestResult>& tests);

// A second model that gives the student's numbers too, after `named`'s proved them: the same
// numbers read another way. Its causes, where the tests name them, are guesses whose line says
// so ("Gives your numbers too: <model> ...; `named` is the cause named.").
void alternative(const Replay& replay, const std::vector<std::string>& ids,
                 const std::string& named, std::vector<TestResult>& tests);

// Every cause of `tests` named as likely without a proof becomes a guess, except those in
// `observed` (a property read directly: NaN, a changed deltaTime, a crash).
void requireProofs(std::vector<TestResult>& tests, const std::vector<std::string>& observed);

}  // namespace clothref::grader
