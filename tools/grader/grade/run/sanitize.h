// The sanitizer run the grader starts by itself when a probe of a student's code crashed or
// answered differently in its two runs (docs/grading-reference.md, "One submission, one score"):
// the student's files are built once more with -fsanitize=address,undefined -g -O1, that probe's
// request runs again on the instrumented code, and the first AddressSanitizer or
// UndefinedBehaviorSanitizer report names the line. Only then: a submission that neither crashes
// nor varies never pays for the second build. The scores are those of the normal build; the
// instrumented run only explains.
#pragma once
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/run/build.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/submission/submission.h"

namespace clothref::grader {

// The first sanitizer report in `stderr_text`: from its "ERROR: AddressSanitizer" (or
// LeakSanitizer) line or a UBSan "runtime error:" line, at most `max_lines` lines, with scratch
// paths cut to the file name (".../src-cloth/cloth.cpp:185" -> "cloth.cpp:185") and process ids
// ("==1234==") removed. Empty when there is none.
std::string firstSanitizerReport(const std::string& stderr_text, int max_lines = 10);

// One grade's instrumented build, made on first use (once, whichever probe group asks first) in
// its own folder of the grade's scratch (owned by the tool uid like build/), and runs of it.
class SanitizedProbes {
 public:
  SanitizedProbes(const SubmissionFiles& files, int edition, CourseToolchain toolchain,
                  const GradeScratch& scratch, ChildLimits limits);

  // Runs `request` on the instrumented probe in `folder` (made under the probe's folder) and
  // returns the first sanitizer report, or "" (no report, or the build failed).
  std::string explain(const probe::ProbeMessage& request, const std::filesystem::path& folder);

 private:
  const SubmissionFiles& files_;
  int edition_;
  CourseToolchain toolchain_;
  const GradeScratch& scratch_;
  ChildLimits limits_;
  std::once_flag built_;
  std::filesystem::path probe_;  // empty when the instrumented build failed
};

}  // namespace clothref::grader
