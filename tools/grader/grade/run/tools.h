// Compiles and links of student files as child processes: the tool uid (never root), time, memory
// and file-size limits, bubblewrap or the fallback's private mount namespace, and failures of the
// grader's own told apart from the compiler's.
#pragma once
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "grader/grade/run/sandbox.h"

namespace clothref::grader {

// A failure of the grader's own that stops a grade (a compile it could not run): never a verdict
// of the student's; a batch makes it that submission's grader-error row.
struct GraderFault : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A compiler or linker run: exit status and the combined output.
struct ToolRun {
  bool ok = false;
  bool ours = false;  // the grader failed (could not start it, bubblewrap failed): not a verdict
  std::string output;
  double seconds = 0;
};
// Runs several tool commands at once (at most `jobs` in parallel); results in command order. A
// command the grader could not start (fork, pipes, the child's set-up, bubblewrap) is tried once
// more, then is a failed run marked `ours`, whose output says what failed.
// With an `isolation` each command runs as its tool uid (never root: sandbox.h); of kind
// Bubblewrap in bubblewrap seeing only /usr, the work dir and the paths it names; every run has
// CPU (wall + 1 s), address-space (kToolAddressSpace), file-size (kToolFileSize), open-file
// (kToolOpenFiles) and, under the tool uid, process (kToolProcesses) limits. A failed run whose
// log holds nothing but white space, and that was stopped by a signal or wrote nothing at all,
// is ours (a tool stopped from outside); any byte the compiler wrote makes it the compiler's.
std::vector<ToolRun> runTools(const std::vector<std::vector<std::string>>& commands,
                              const std::filesystem::path& work_dir, int jobs, double wall_seconds,
                              const Isolation* isolation = nullptr);
inline constexpr std::uint64_t kToolAddressSpace = 8ull << 30;  // a 10 GB constexpr stops here
inline constexpr std::uint64_t kToolFileSize = 1ull << 30;
inline constexpr std::uint64_t kToolOpenFiles = 256;  // RLIMIT_NOFILE
inline constexpr std::uint64_t kToolProcesses = 64;   // RLIMIT_NPROC of the tool uid (not root)

}  // namespace clothref::grader
