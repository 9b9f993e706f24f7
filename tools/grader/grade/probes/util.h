// Helpers shared by the probe files: conversions between clothref matrices and probe arrays,
// numbers and expected-against-yours comparisons (compare_text.h), and running a group's child
// with the failure verdicts.
#pragma once
#include <Eigen/Core>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "clothref/core/method.h"
#include "clothref/core/types.h"
#include "grader/bridge/probe_keys.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/compare_text.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/text.h"

namespace clothref::grader {
// The protocol's names (bridge/probe_keys.h), short in the probe files.
namespace key = probe::key;
namespace group = probe::group;
}  // namespace clothref::grader

namespace clothref::grader::util {

inline std::vector<float> flat(const Mat4X<float>& m) {
  return std::vector<float>(m.data(), m.data() + m.size());
}
inline Mat4X<float> matrix(const std::vector<float>& values, int columns) {
  Mat4X<float> m = Mat4X<float>::Zero(4, columns);
  for (int c = 0; c < columns && 4 * c + 3 < static_cast<int>(values.size()); ++c)
    for (int r = 0; r < 4; ++r) m(r, c) = values[static_cast<std::size_t>(4 * c + r)];
  return m;
}
inline std::vector<float> flat(const VecX<float>& v) {
  return std::vector<float>(v.data(), v.data() + v.size());
}

// The row of `method` in clothref's method table (core/method.h): how the protocol names an
// integrator (key::kMethod).
inline std::int64_t methodRow(Method method) {
  for (std::size_t row = 0; row < kMethods.size(); ++row)
    if (kMethods[row].method == method) return static_cast<std::int64_t>(row);
  return -1;  // not in the table: the driver refuses it
}

// Why a probe group has no usable answer: the run's verdict (never read back from words) and the
// text for the report (the verdict line, then the first lines of stderr).
struct ProbeFailure {
  Verdict verdict = Verdict::Graded;
  std::string text;
  // The catalogue id of the cause: grader-error (ours), timed-out (wall or CPU limit),
  // undefined-behaviour (the two runs differed), or crashed for every other way it ended.
  std::string causeId() const {
    if (verdict == Verdict::GraderError) return cause::kGraderError;
    if (verdict == Verdict::TimedOut) return cause::kTimedOut;
    if (verdict == Verdict::ResultsVary) return cause::kUndefinedBehaviour;
    return cause::kCrashed;
  }
};

// Appends to `failure.text` what the sanitizer says of `request` run again in `dir` (a crash or
// two runs that differ, of the context's main probe).
inline void explainFailure(const ProbeContext& context, const probe::ProbeMessage& request,
                           const std::filesystem::path& dir, ProbeFailure& failure) {
  const std::string report = context.sanitizer->explain(request, dir / "sanitize");
  failure.text += report.empty()
                      ? "\n\nThe grader rebuilt your files with AddressSanitizer and "
                        "UndefinedBehaviorSanitizer and ran this probe again: they reported "
                        "nothing (they do not see a read of an uninitialised variable, and the "
                        "fault may depend on the optimisation level)."
                      : "\n\nThe grader rebuilt your files with AddressSanitizer and "
                        "UndefinedBehaviorSanitizer (`-g -Og`) and ran this probe again; "
                        "their report:\n\n" +
                            codeBlock(report);
}

// The explanation a run with ProbeContext::explain_later left in `kept`, appended to `failure`'s
// text (nothing when none was kept).
inline void explainLater(const ProbeContext& context, Unexplained& kept, ProbeFailure& failure) {
  if (!kept.request) return;
  const probe::ProbeMessage request = std::move(*kept.request);
  kept.request.reset();
  explainFailure(context, request, kept.dir, failure);
}

// Runs `request` in a fresh folder under the context's work dir, twice (runProbeTwice: the
// answer depends on the files alone) unless `once` (information only, never scored). On failure
// returns nullopt and fills `failure`.
inline std::optional<probe::ProbeMessage> runGroup(const ProbeContext& context,
                                                   const std::filesystem::path& executable,
                                                   const std::string& folder,
                                                   probe::ProbeMessage request,
                                                   ProbeFailure& failure,
                                                   ChildRun* run_out = nullptr, bool once = false) {
  const auto dir = context.work_dir / folder;
  std::filesystem::create_directories(dir);
  ChildRun run = once ? runProbe(executable, request, dir, context.limits)
                      : runProbeTwice(executable, request, dir, context.limits);
  if (run_out) *run_out = run;
  if (run.status == ChildStatus::Ok) return run.answer;
  failure.verdict = run.verdict();
  failure.text = "The probe process " + run.describe() + ".";
  if (run.status == ChildStatus::NotStarted && !run.grader_problem.empty())
    failure.text += " (" + run.grader_problem + ")";
  if (!run.stderr_head.empty()) failure.text += "\n\n" + codeBlock(run.stderr_head);
  // A crash, or two runs that differ: the instrumented build names the line, when it finds one.
  const bool explain = run.status == ChildStatus::Varies || failure.verdict == Verdict::Crashed;
  if (explain && context.sanitizer && executable == context.probe) {
    if (context.explain_later) {
      context.explain_later->request = std::move(request);
      context.explain_later->dir = dir;
    } else {
      explainFailure(context, request, dir, failure);
    }
  }
  return std::nullopt;
}

// The test of one row of a probe's check table (its name and weight are written only there).
inline TestResult test(const PlannedTest& check) {
  return makeTest(check.stub, check.check, check.weight);
}

// A cause the numbers confirm, and one they only suggest (results.h, Cause).
inline Cause likely(const std::string& id) { return Cause{id, true, {}, {}, {}, {}, {}, {}}; }
inline Cause guess(const std::string& id) { return Cause{id, false, {}, {}, {}, {}, {}, {}}; }

// A test of the group that could not run: zero points, the verdict as output.
inline TestResult failedTest(const PlannedTest& check, const std::string& why,
                             std::vector<Cause> causes) {
  TestResult t = test(check);
  t.fraction = 0;
  t.output = why;
  t.causes = std::move(causes);
  return t;
}

inline bool finite(const std::vector<float>& v) {
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// A model's values against the student's within a check's tolerance, |model - yours| <= rel (1 +
// |yours|); a value that is not finite matches only one that is not finite either (a replay's
// comparison, explain/replay.h).
inline bool closeTo(const Mat4X<float>& model, const Mat4X<float>& yours, double rel) {
  if (model.size() != yours.size()) return false;
  for (int k = 0; k < model.size(); ++k) {
    const double m = model.data()[k], y = yours.data()[k];
    if (!std::isfinite(m) || !std::isfinite(y)) {
      if (std::isfinite(m) != std::isfinite(y)) return false;
      continue;
    }
    if (std::abs(m - y) > rel * (1 + std::abs(y))) return false;
  }
  return true;
}

}  // namespace clothref::grader::util
