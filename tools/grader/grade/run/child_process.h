// Running untrusted code: one child process per probe group (or per compile), with resource limits
// and a wall-clock timeout. The probe answer comes back on fd 3 (bridge/probe_protocol.h); stdout
// and stderr go to files in the child's work directory and are only quoted, never trusted.
//
// `ChildLimits::isolation` (sandbox.h) adds an unprivileged uid, a private working directory and,
// where it works, a bubblewrap sandbox; a wall timeout then kills the sandbox's whole pid
// namespace and waits until it is gone, so no process of the run outlives runChild.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/results.h"
#include "grader/grade/run/sandbox.h"

namespace clothref::grader {

// The verdicts of every run made with one ChildLimits (its copies share the log), so a grade can
// name the worst thing that happened to a submission.
struct RunLog {
  std::mutex mutex;
  std::vector<Verdict> verdicts;  // ChildRun::verdict() of each run, in completion order
};

struct ChildLimits {
  double wall_seconds = 20;                        // killed (whole process group) after this
  std::uint64_t cpu_seconds = 20;                  // RLIMIT_CPU
  std::uint64_t address_space_bytes = 4ull << 30;  // RLIMIT_AS
  std::uint64_t file_size_bytes = 64ull << 20;     // RLIMIT_FSIZE (stdout/stderr floods)
  std::uint64_t open_files = 64;                   // RLIMIT_NOFILE
  std::uint64_t processes = 64;       // RLIMIT_NPROC (counts the uid's processes; not for root)
  Isolation isolation;                // uid drop, private folder, bubblewrap (default: none)
  std::vector<std::string> launcher;  // extra argv prefix, empty = none
  std::shared_ptr<RunLog> log;        // when set, every run's verdict is appended
};

enum class ChildStatus {
  Ok,             // exited 0 and answered with a well-formed frame carrying our nonce
  Crashed,        // killed by a signal (segfault, abort, CPU limit, ...)
  TimedOut,       // wall-clock limit reached
  ExitedNonZero,  // exited with a non-zero code
  NoAnswer,       // exited 0 but sent no valid answer (missing, malformed, wrong nonce)
  NotStarted      // the grader could not start it (fork failed): our failure, not the student's
};

struct ChildRun {
  ChildStatus status = ChildStatus::NoAnswer;
  int signal = 0;           // for Crashed
  int exit_code = 0;        // for ExitedNonZero
  double seconds = 0;       // wall time
  std::string stderr_head;  // first lines of the child's stderr (for the report)
  std::optional<probe::ProbeMessage> answer;
  // One line for a report: "crashed (SIGSEGV)", "timed out after 20 s", ...
  std::string describe() const;
  // What the run means for the submission (docs/grading.md, "Verdicts"): Graded (it finished and
  // answered with finite numbers), NonFinite, TimedOut (wall or CPU limit), MemoryLimit
  // (std::bad_alloc under the address-space limit), OutputLimit (file size), Crashed,
  // ExitedNonZero, NoAnswer, GraderError (NotStarted: ours).
  Verdict verdict() const;
};

// Runs `command` (argv; argv[0] a path) in `work_dir` with `stdin_file` as stdin, a clean
// environment and the limits; reads its fd-3 answer when `expect_answer`. `request_nonce` is the
// nonce the answer must carry.
ChildRun runChild(const std::vector<std::string>& command, const std::filesystem::path& work_dir,
                  const std::filesystem::path& stdin_file, const ChildLimits& limits,
                  bool expect_answer, std::uint64_t request_nonce);

// Sends `request` (its nonce is set here, fresh and random) to the probe executable and returns
// the run. The request is written to a file in `work_dir` first.
ChildRun runProbe(const std::filesystem::path& executable, probe::ProbeMessage request,
                  const std::filesystem::path& work_dir, const ChildLimits& limits);

// A compiler or linker run: exit status and the combined output.
struct ToolRun {
  bool ok = false;
  std::string output;
  double seconds = 0;
};
// Runs several tool commands at once (at most `jobs` in parallel); results in command order. A
// command the grader cannot start (fork fails) is a failed run whose output says so.
// With an `isolation` of kind Bubblewrap each command runs in bubblewrap seeing only /usr, the
// work dir and the paths it names (sandbox.h); every run has CPU (wall + 1 s), address-space
// (kToolAddressSpace) and file-size (kToolFileSize) limits.
std::vector<ToolRun> runTools(const std::vector<std::vector<std::string>>& commands,
                              const std::filesystem::path& work_dir, int jobs, double wall_seconds,
                              const Isolation* isolation = nullptr);
inline constexpr std::uint64_t kToolAddressSpace = 8ull << 30;  // a 10 GB constexpr stops here
inline constexpr std::uint64_t kToolFileSize = 1ull << 30;

}  // namespace clothref::grader
