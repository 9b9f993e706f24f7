// Diagnosing a crash (`clothref grade --sanitize`, docs/grading.md): a submission whose code
// crashed is rebuilt with -fsanitize=address,undefined -g -O1, its probes run again, and the first
// AddressSanitizer / UndefinedBehaviorSanitizer report is quoted in its report. Typical find: an
// `auto` variable holding an Eigen expression over temporaries (stack-use-after-scope), which
// segfaults at -O2 without saying where.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "grader/grade/grade.h"

namespace clothref::grader {

// True when a probe of the student's code crashed (a test diagnosed `crashed`, or the verdict
// says crashed or aborted).
bool hasCrash(const GradeReport& report);

// The first sanitizer report in `stderr_text`: from its "ERROR: AddressSanitizer" (or
// LeakSanitizer) line or a UBSan "runtime error:" line, at most `max_lines` lines, with scratch
// paths cut to the file name (".../src-cloth/cloth.cpp:185" -> "cloth.cpp:185") and process ids
// ("==1234==") removed. Empty when there is none.
std::string firstSanitizerReport(const std::string& stderr_text, int max_lines = 10);

struct SanitizerFinding {
  std::string group;  // probe group whose process reported it, e.g. "forces"
  std::string stub;   // course stub that group grades ("" for the whole run)
  std::string quote;  // firstSanitizerReport of that process's stderr
};

// Rebuilds `dir` with the sanitizers (a fresh build; compiled objects are cached under their own
// flags), reruns every probe group with longer time limits and no address-space limit (the
// sanitizers reserve terabytes of virtual memory), and returns the first report, preferring a
// group whose stub crashed in `report`. nullopt when no process reported anything.
std::optional<SanitizerFinding> sanitizerFinding(const std::filesystem::path& dir,
                                                 const GradeReport& report,
                                                 const GradeOptions& options);

// Puts the finding into `report`: a note, and the quote appended to the output of that stub's
// failed tests. Without a finding, a note says that the sanitized rebuild reported nothing.
void addSanitizerFinding(GradeReport& report, const std::optional<SanitizerFinding>& finding);

// What --sanitize does after grading: when `report` has a crash, find and add the sanitizer
// report; a rebuild that fails becomes a note (it never fails the grading).
void diagnoseCrashWithSanitizers(const std::filesystem::path& dir, GradeReport& report,
                                 const GradeOptions& options);

}  // namespace clothref::grader
