// The sanitizer run the grader starts by itself when a probe of a student's code crashed or
// answered differently in its two runs (docs/grading-reference.md, "One submission, one score"):
// the files that probe runs are built once more with -fsanitize=address,undefined -g -Og, that
// probe's request runs again on the instrumented code, and the first AddressSanitizer or
// UndefinedBehaviorSanitizer report names the line. Only then: a submission that neither crashes
// nor varies never pays for the second build. The scores are those of the normal build; the
// instrumented run only explains.
#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/run/build.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/submission/submission.h"

namespace clothref::grader {

// The first sanitizer report in `stderr_text`: from its "ERROR: AddressSanitizer" (or
// LeakSanitizer) line or a UBSan "runtime error:" line, at most `max_lines` lines, with scratch
// paths cut to the file name (".../src-cloth/cloth.cpp:185" -> "cloth.cpp:185"), every other
// path too (no host path is quoted), and process ids ("==1234==") removed; of the stack, only
// frames in the student's files. Empty when there is none.
std::string firstSanitizerReport(const std::string& stderr_text, int max_lines = 10);

// The last report of the sanitizers' channel (ChildRun::sanitizer_report), cut as above: the
// report that ended the run (ASan halts at its first; UBSan is told to), whatever came before.
std::string lastSanitizerReport(const std::string& channel, int max_lines = 10);

// The limits of the sanitizer run that explains a probe run with `probe`'s limits: the same
// limits, with wall and CPU time kSanitizerSlowdown times as long, no address-space limit (the
// sanitizers reserve terabytes) but a memory limit (the probe's address space, plus an eighth
// for ASan's shadow memory and kSanitizerRuntimeBytes for its allocator, quarantine and
// redzones), the same wait for process slots as the probe, the sanitizers' own channel, and
// the sanitizers' options (report to that channel, stop at the first report, ASan's own memory
// limit as a second line where no memory cgroup exists).
inline constexpr std::uint64_t kSanitizerRuntimeBytes = 512ull << 20;
ChildLimits sanitizerLimits(const ChildLimits& probe);

// The student files whose code a probe group's request runs (driver/probe_driver.cpp): springs
// and forces cloth.cpp, the two collisions cloth.cpp and sphere.cpp, an integrator
// integrator.cpp, the whole run (and a group this list does not know) all three.
std::vector<std::string> filesRunBy(const std::string& group);

// One grade's instrumented builds, made on first use in their own folder of the grade's scratch
// (owned by the tool uid like build/): per probe group, only the files it runs are compiled
// again with the sanitizers (ProbeRebuilder, each file once), linked with the grade's own
// objects of the others; and runs of them.
class SanitizedProbes {
 public:
  SanitizedProbes(const SubmissionFiles& files, int edition, CourseToolchain toolchain,
                  const GradeScratch& scratch, ChildLimits limits, const ProbeBuild& base);
  // Wall time spent in explain() so far, building and running (summed over probe groups).
  double seconds() const;

  // Runs `request` on the instrumented probe in `folder` (made under the probe's folder) and
  // returns the sanitizers' report of the run's end, or "": no report, the build failed, or the
  // run answered first (a report at exit, after the probe's work, is not the crash it explains).
  // The whole run's crash is explained first on the files scored groups had rebuilt already, and
  // on all three only when that finds no report (docs/grading-reference.md, "Diagnosing crashes").
  std::string explain(const probe::ProbeMessage& request, const std::filesystem::path& folder);

 private:
  // The report of `request` run on the probe with `files` instrumented ("" as explain()).
  std::string reportOn(const std::vector<std::string>& files, const probe::ProbeMessage& request,
                       const std::filesystem::path& folder);

  const GradeScratch& scratch_;
  ChildLimits limits_;
  std::unique_ptr<ProbeRebuilder> rebuilder_;
  std::mutex mutex_;
  std::map<std::string, std::filesystem::path> published_;  // by build; empty when it failed
  mutable std::mutex seconds_mutex_;
  double seconds_ = 0;
};

}  // namespace clothref::grader
