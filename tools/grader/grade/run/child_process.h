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
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/results.h"
#include "grader/grade/run/sandbox.h"

namespace clothref::grader {

// The verdicts of every run made with one ChildLimits (its copies share the log), so a grade can
// name the worst thing that happened to a submission, and the folder each ran in (the folder's
// name, e.g. "forces"), so a grade knows which probe answered what.
struct RunLog {
  std::mutex mutex;
  std::vector<Verdict> verdicts;     // ChildRun::verdict() of each run, in completion order
  std::vector<std::string> folders;  // the work_dir's name of each, in the same order
  // The folders of the runs that answered with NaN or infinity (ChildLimits::answers).
  std::set<std::string> non_finite;
  // Of those, the runs whose only non-finite numbers ended a long run that first grew past any
  // cloth's size (an unstable method overflowing): the stub's instability, not its NaN.
  std::set<std::string> diverged;
};

inline constexpr std::uint64_t kRunDiskBytes = 128ull << 20;
inline constexpr double kDiskCheckSeconds = 0.02;
inline constexpr std::uint64_t kKeptOutputBytes = 64ull << 10;
// The sanitizer run is this much slower than the probe it explains: its wall and CPU limits are
// this times the probe's, and a run waiting for the uid's process slots waits out the longest.
inline constexpr double kSanitizerSlowdown = 3;
inline constexpr double kSlotWaitMarginSeconds = 5;  // a stopped run's cleanup (2 s + 2 s)
// The wall-clock limit counts a run's own time: what it spent waiting for a CPU (runnable while
// the machine's other work held the CPUs) is added to it, up to this times the limit. A run
// stopped there before its own time reached the limit was held back by load: a failure of ours.
inline constexpr double kLoadAllowance = 3;

struct ChildLimits {
  double wall_seconds = 20;  // killed (whole process group) after this, load's wait not counted
  std::uint64_t cpu_seconds = 20;                  // RLIMIT_CPU
  std::uint64_t address_space_bytes = 4ull << 30;  // RLIMIT_AS (RLIM_INFINITY: none)
  // The run's memory cgroup (memory.max, or cgroup v1's memory.limit_in_bytes) where the host
  // has one: what its processes hold in memory, their private filesystems included. 0: none.
  std::uint64_t memory_bytes = 4ull << 30;
  std::uint64_t file_size_bytes = 32ull << 20;  // RLIMIT_FSIZE (stdout/stderr floods, any file)
  std::uint64_t open_files = 64;                // RLIMIT_NOFILE
  std::uint64_t processes = 64;  // RLIMIT_NPROC (counts the uid's processes; not for root)
  // Files a run may hold at once: its folder, stdout, stderr and, outside bubblewrap, what its uid
  // owns in the shared temporary folders; checked every kDiskCheckSeconds, the run is stopped
  // past it (DiskLimit). Where its folder and temporary places are bounded filesystems (above),
  // those hold at write time and this count is the second line. Two runs of a submission at
  // once: twice this per submission.
  std::uint64_t disk_bytes = kRunDiskBytes;
  // How long a run waits for the uid's process slots (another run's fork bomb holds them until
  // it is stopped); 0: kSanitizerSlowdown x kLoadAllowance x wall_seconds +
  // kSlotWaitMarginSeconds, the longest any run of the grade's uid can last.
  double slot_wait_seconds = 0;
  // The sanitizers' own channel (the sanitizer run): a pipe, fd kSanitizerReportFd in the child,
  // which the sanitizers reach through `.sanitizer-report.<pid>` in the run's folder (a link to
  // /proc/self/fd/<fd>, named by ASAN_OPTIONS/UBSAN_OPTIONS log_path); read into
  // ChildRun::sanitizer_report, never the student's stderr.
  bool sanitizer_channel = false;
  // Keep what the run wrote in its folder after it ends (--keep-work); else it is removed, and
  // stdout and stderr are cut to their first kKeptOutputBytes.
  bool keep_files = false;
  // The same address layout on every run (no ASLR), and these variables added to the child's
  // clean environment: a probe is run twice with two fixed variants (probeVariants()), so what
  // undefined behaviour reads differs between the two and nowhere else.
  bool fixed_layout = false;
  std::vector<std::string> environment;
  Isolation isolation;                // uid drop, private folder, bubblewrap (default: none)
  std::vector<std::string> launcher;  // extra argv prefix, empty = none
  std::shared_ptr<RunLog> log;        // when set, every run's verdict is appended
  // When set, every run whose answer held NaN or infinity notes its folder here, also where `log`
  // is cleared (an integrator's first run, which its retry may replace): which stubs' answers
  // were non-finite (rubric.h, markNonFinite).
  std::shared_ptr<RunLog> answers;
};

enum class ChildStatus {
  Ok,             // exited 0 and answered with a well-formed frame carrying our nonce
  Crashed,        // killed by a signal (segfault, abort, CPU limit, ...)
  TimedOut,       // wall-clock limit reached (its own time: waiting for a CPU not counted)
  DiskLimit,      // stopped for holding more than ChildLimits::disk_bytes of files
  Varies,         // its two runs (probeVariants()) did not end alike: undefined behaviour
  ExitedNonZero,  // exited with a non-zero code
  NoAnswer,       // exited 0 but sent no valid answer (missing, malformed, wrong nonce)
  NotStarted      // the grader could not start it (fork, pipe, a file or a mount of ours failed):
                  // our failure, not the student's
};

struct ChildRun {
  ChildStatus status = ChildStatus::NoAnswer;
  int signal = 0;      // for Crashed
  int exit_code = 0;   // for ExitedNonZero
  double seconds = 0;  // wall time
  // Stopped at the wall-clock limit: the CPU time (s) its processes had used (-1: unknown), the
  // limit (s) it reached (its own time), and how long it had waited for a CPU (-1: unknown).
  double cpu_seconds = -1;
  double limit_seconds = 0;
  double waited_seconds = -1;
  std::string stderr_head;  // first lines of the child's stderr (for the report)
  std::optional<probe::ProbeMessage> answer;
  // NotStarted: what failed on our side (for the staff), and whether it was the uid's process
  // slots being taken (retried for longer: another run's fork bomb holds them for a while).
  std::string grader_problem;
  bool waiting_for_slot = false;
  std::uint64_t disk_limit_bytes = 0;  // the limit a DiskLimit run passed
  // Killed by the memory cgroup's limit (its OOM killer): a MemoryLimit verdict.
  bool memory_limit = false;
  // A whole answer frame with our nonce arrived, however the run then ended (a crash at exit).
  bool answered = false;
  std::string sanitizer_report;  // what came on the sanitizers' channel (at most 1 MiB)
  // One line for a report: "crashed (SIGSEGV)", "timed out after 20 s", ...
  std::string describe() const;
  // What the run means for the submission (docs/grading-reference.md, "Verdicts"): Graded (it
  // finished and answered with finite numbers), NonFinite, TimedOut (wall or CPU limit),
  // MemoryLimit (std::bad_alloc under the address-space limit, or the memory cgroup's limit),
  // OutputLimit (file size), Crashed,
  // ExitedNonZero, NoAnswer, GraderError (NotStarted: ours).
  Verdict verdict() const;
};

// The limits of a probe run for `grade --timeout SECONDS`: that wall time, one second more of CPU,
// the rest as ChildLimits has them.
ChildLimits limitsForTimeout(double seconds);

// Runs `command` (argv; argv[0] a path) in `work_dir` with `stdin_file` as stdin, a clean
// environment and the limits; reads its fd-3 answer when `expect_answer`. `request_nonce` is the
// nonce the answer must carry. A run held back by load (kLoadAllowance) is ours: tried once more,
// then NotStarted with the wait in grader_problem.
ChildRun runChild(const std::vector<std::string>& command, const std::filesystem::path& work_dir,
                  const std::filesystem::path& stdin_file, const ChildLimits& limits,
                  bool expect_answer, std::uint64_t request_nonce);

// How long a run waits for its uid's process slots (ChildLimits::slot_wait_seconds).
double slotWait(const ChildLimits& limits);

// The two variants a scored probe runs in, both with a fixed address layout: the first as the
// student would run it, the second with freed memory filled (MALLOC_PERTURB_), the stack below
// each stub's call filled with 0xff instead of 0x00 (probe::kStackFillVariable, read by the
// driver) and the stack moved (a longer environment). A stub that reads memory it does not own
// (a dangling `auto` Eigen expression, a freed buffer, an uninitialised local) answers
// differently in the two; a correct one cannot.
std::vector<std::vector<std::string>> probeVariants();

// Whether two answers are the same to the bit (NaN payloads included).
bool sameAnswer(const probe::ProbeMessage& a, const probe::ProbeMessage& b);

// Sends `request` (its nonce is set here, fresh and random) to the probe executable and returns
// the run. The request is written to a file in `work_dir` first.
ChildRun runProbe(const std::filesystem::path& executable, probe::ProbeMessage request,
                  const std::filesystem::path& work_dir, const ChildLimits& limits);

// A scored probe: `request` run in both probeVariants() with a fixed address layout, so that the
// answer is a function of the files alone. The rule (docs/grading-reference.md, "One submission,
// one score"): both ended alike (the same answer to the bit, or the same failure) -> the first run;
// otherwise the run is Varies, whatever either answered, and its checks fail. A first run stopped
// at a limit (time, output, disk) or not started is not repeated: its own time reached the limit
// (runChild does not count load's wait), so a second run cannot change the verdict. One verdict
// goes to the log.
ChildRun runProbeTwice(const std::filesystem::path& executable, const probe::ProbeMessage& request,
                       const std::filesystem::path& work_dir, const ChildLimits& limits);

}  // namespace clothref::grader
