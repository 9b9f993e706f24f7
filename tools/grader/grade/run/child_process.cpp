#include "grader/grade/run/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>

#include "grader/grade/run/folders.h"
#include "grader/grade/run/process_tree.h"
#include "grader/grade/run/spawn.h"
#include "grader/grade/submission/neighbours.h"

namespace clothref::grader {
using namespace spawn;

std::string ChildRun::describe() const {
  std::ostringstream out;
  switch (status) {
    case ChildStatus::Ok:
      out << "finished";
      break;
    case ChildStatus::Crashed:
      if (memory_limit)
        out << "ran out of memory (the memory limit of a probe; stopped by the kernel)";
      else if (verdict() == Verdict::MemoryLimit)
        out << "ran out of memory (address-space limit; std::bad_alloc, then abort)";
      else if (verdict() == Verdict::OutputLimit)
        out << "was stopped for writing too much output (file-size limit, SIGXFSZ)";
      else if (verdict() == Verdict::TimedOut)
        out << "timed out: stopped at the CPU time limit (SIGXCPU)";
      else
        out << "crashed (" << signalName(signal) << ")";
      break;
    case ChildStatus::TimedOut:  // the limit its own time reached, whatever load added to it
      out << "timed out after "
          << static_cast<int>((limit_seconds > 0 ? limit_seconds : seconds) + 0.5) << " s";
      break;
    case ChildStatus::DiskLimit:
      out << "was stopped for holding more than " << (disk_limit_bytes >> 20)
          << " MiB of files (the disk limit of a probe)";
      break;
    case ChildStatus::Varies:
      out << "gave different results in two runs of the same input";
      break;
    case ChildStatus::ExitedNonZero:
      out << "exited with code " << exit_code;
      break;
    case ChildStatus::NoAnswer:
      out << "exited without sending the probe results";
      break;
    case ChildStatus::NotStarted:
      out << "could not be started by the grader (a grader error, not the student's)";
      break;
  }
  return out.str();
}

Verdict ChildRun::verdict() const {
  switch (status) {
    case ChildStatus::Ok:
      // An answer with NaN or infinity: the run worked, the numbers did not.
      if (answer)
        for (const auto& [key, values] : answer->floats)
          for (float value : values)
            if (!std::isfinite(value)) return Verdict::NonFinite;
      return Verdict::Graded;
    case ChildStatus::TimedOut:
      return Verdict::TimedOut;
    case ChildStatus::DiskLimit:
      return Verdict::OutputLimit;
    case ChildStatus::Varies:
      return Verdict::ResultsVary;
    case ChildStatus::ExitedNonZero:
      return Verdict::ExitedNonZero;
    case ChildStatus::NoAnswer:
      return Verdict::NoAnswer;
    case ChildStatus::NotStarted:
      return Verdict::GraderError;
    case ChildStatus::Crashed:
      break;
  }
  if (memory_limit) return Verdict::MemoryLimit;
  if (signal == SIGXCPU) return Verdict::TimedOut;
  if (signal == SIGXFSZ) return Verdict::OutputLimit;
  // The C++ runtime's last words when `new` fails under RLIMIT_AS (the student could print them
  // too: that only changes this word, never a score).
  if (signal == SIGABRT && stderr_head.find("std::bad_alloc") != std::string::npos)
    return Verdict::MemoryLimit;
  return Verdict::Crashed;
}

namespace {

// How close to its limit a run's own time must be to be stopped (else the limit is moved on by
// what it waited for a CPU, and read again then).
constexpr double kLimitRecheckSeconds = 0.05;

// A run the grader could not start: its own words, never the student's stderr.
ChildRun notStarted(const std::string& why, bool waiting_for_slot = false) {
  ChildRun run;
  run.status = ChildStatus::NotStarted;
  run.grader_problem = why;
  run.waiting_for_slot = waiting_for_slot;
  return run;
}

// The fallback's filesystems for a probe run as root with a private mount namespace: our folders
// covered; its folder a tmpfs of kRunFolderBytes owned by its uid; every folder any user may
// write into (sharedTemporaryFolders: /tmp, /var/tmp, /dev/shm, /run/lock, ...) an empty private
// tmpfs of kPrivateTmpBytes. The child enters its folder and runs its program by descriptors, so
// covering /tmp, where the scratch folder lies, hides nothing it needs.
void privateMounts(const Isolation& isolation, ExecLimits& how) {
  if (isolation.kind != IsolationKind::Rlimits || !isolation.private_mounts || isolation.uid < 0)
    return;
  how.new_mount_namespace = true;
  std::error_code error;
  for (const std::filesystem::path& folder : isolation.ours)
    if (std::filesystem::is_directory(folder, error))
      how.hide.push_back(folder.lexically_normal().string());
  // Outermost first; a folder inside another (or inside one of ours) is covered with it.
  const std::string uid = std::to_string(isolation.uid);
  how.folder_options =
      "size=" + std::to_string(kRunFolderBytes) + ",mode=0700,uid=" + uid + ",gid=" + uid;
  std::vector<std::string> shared;
  for (const std::filesystem::path& folder : sharedTemporaryFolders())
    shared.push_back(folder.lexically_normal().string());
  std::sort(shared.begin(), shared.end());
  for (const std::string& folder : shared) {
    bool covered = false;
    for (const std::string& outer : how.private_tmp) covered = covered || isUnder(folder, outer);
    for (const std::string& hidden : how.hide) covered = covered || isUnder(folder, hidden);
    if (!covered) how.private_tmp.push_back(folder);
  }
}

// One attempt; `start` is when the attempt began (the wall limit counts from it).
ChildRun runChildOnce(const std::vector<std::string>& command,
                      const std::filesystem::path& work_dir,
                      const std::filesystem::path& stdin_file, const ChildLimits& limits,
                      bool expect_answer, std::uint64_t request_nonce, Clock::time_point start) {
  const Isolation& isolation = limits.isolation;
  const bool boxed = isolation.kind == IsolationKind::Bubblewrap;
  // The student's own folder: the only place it may write (its owner is the uid it runs as).
  std::filesystem::path run_dir = work_dir;
  if (isolation.kind != IsolationKind::None) {
    run_dir = work_dir / "sandbox";
    std::error_code error;
    std::filesystem::create_directories(run_dir, error);
    if (chmod(run_dir.c_str(), 0700) != 0 ||
        (isolation.uid >= 0 && chown(run_dir.c_str(), static_cast<uid_t>(isolation.uid),
                                     static_cast<gid_t>(isolation.uid)) != 0))
      return notStarted("cannot hand the child's folder to uid " + std::to_string(isolation.uid));
  }
  std::vector<std::string> argv = limits.launcher;
  std::vector<std::string> inner =
      boxed ? bubblewrapArgv(isolation, command, kInfoFd, limits.sanitizer_channel) : command;
  // Injected faults reach probe runs only (not the isolation's detection run).
  const auto fault = [&](const char* point) { return expect_answer && injectFault(point); };
  // bubblewrap refuses an option it does not know before it starts anything
  if (boxed && fault("bwrap")) inner.insert(inner.begin() + 1, "--clothref-injected-fault");
  argv.insert(argv.end(), inner.begin(), inner.end());
  const auto out_path = work_dir / "child.stdout";
  const auto err_path = work_dir / "child.stderr";
  const bool files_fault = fault("files"), pipe_fault = fault("pipe");
  int in_fd = open(stdin_file.c_str(), O_RDONLY | O_CLOEXEC);
  int out_fd =
      files_fault ? -1 : open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  int pipe_fds[2] = {-1, -1};
  int info_fds[2] = {-1, -1};
  int setup_fds[2] = {-1, -1};
  int report_fds[2] = {-1, -1};
  // The sanitizers' channel: the probe's uid reopens its write end through /proc/self/fd.
  const bool channel = limits.sanitizer_channel;
  if (in_fd < 0 || out_fd < 0 || err_fd < 0 || pipe_fault || pipe2(pipe_fds, O_CLOEXEC) != 0 ||
      pipe2(setup_fds, O_CLOEXEC) != 0 || (boxed && pipe2(info_fds, O_CLOEXEC | O_NONBLOCK) != 0) ||
      (channel && (pipe2(report_fds, O_CLOEXEC) != 0 ||
                   (isolation.uid >= 0 && fchown(report_fds[1], static_cast<uid_t>(isolation.uid),
                                                 static_cast<gid_t>(isolation.uid)) != 0)))) {
    for (int fd : {in_fd, out_fd, err_fd, pipe_fds[0], pipe_fds[1], info_fds[0], info_fds[1],
                   setup_fds[0], setup_fds[1], report_fds[0], report_fds[1]})
      if (fd >= 0) close(fd);
    return notStarted(files_fault || pipe_fault ? setupFailureText(kSetupInjected)
                                                : "cannot set up the child's files or pipes");
  }
  const ExecArgs exec(argv, run_dir, limits.environment);
  ExecLimits how;
  how.limits = &limits;
  how.uid = isolation.uid;
  how.injected_fault = fault("setup");
  how.sanitizer_link = channel && !boxed;  // bubblewrap makes the link in the sandbox
  privateMounts(isolation, how);
  // The rlimits fallback puts a supervisor between us and the student (superviseChild).
  const bool supervised = !boxed && isolation.kind == IsolationKind::Rlimits &&
                          isolation.containment != Containment::None;
  bool in_namespace = supervised && isolation.containment == Containment::PidNamespace;
  const bool confined = isolation.kind != IsolationKind::None;
  const RunCgroup cgroup(confined ? isolation.cgroup_parent : "",
                         confined ? isolation.memory_cgroup : "", isolation.memory_cgroup_v1,
                         limits.memory_bytes);
  pid_t pid = -1;
  const bool fork_fault = fault("fork");
  if (fork_fault) {
    errno = EAGAIN;
  } else {
    if (in_namespace) {
      pid = static_cast<pid_t>(syscall(SYS_clone, CLONE_NEWPID | SIGCHLD, 0, 0, 0, 0));
      if (pid < 0 && (errno == EPERM || errno == EINVAL || errno == ENOSPC)) in_namespace = false;
    }
    if (!in_namespace) pid = fork();
  }
  ChildFds fds;
  fds.in = in_fd;
  fds.out = out_fd;
  fds.err = err_fd;
  fds.answer = expect_answer ? pipe_fds[1] : -1;
  fds.info = info_fds[1];
  fds.setup = setup_fds[1];
  fds.report = report_fds[1];
  if (pid == 0) {
    cgroup.join();
    if (supervised) superviseChild(exec, fds, how, in_namespace);
    execChild(exec, fds, how);
  }
  const int fork_error = errno;
  for (int fd : {in_fd, out_fd, err_fd, pipe_fds[1], info_fds[1], setup_fds[1], report_fds[1]})
    if (fd >= 0) close(fd);
  if (pid < 0) {
    // No process: nothing to wait for or kill (a kill(-1) would signal every process we may).
    for (int fd : {pipe_fds[0], info_fds[0], setup_fds[0], report_fds[0]})
      if (fd >= 0) close(fd);
    return notStarted(fork_fault ? setupFailureText(kSetupInjected)
                                 : std::string("cannot start the child (fork: ") +
                                       std::strerror(fork_error) + ")",
                      fork_error == EAGAIN && !fork_fault);
  }
  setpgid(pid, pid);  // also done in the child; whichever runs first wins the race harmlessly

  // What the run holds on disk: its folder, its output files and, outside bubblewrap, what its
  // uid owns in the shared temporary folders (with a private mount namespace /tmp still is one).
  const auto diskFull = [&] {
    std::uint64_t bytes = static_cast<std::uint64_t>(fileSize(out_path) + fileSize(err_path));
    if (bytes <= limits.disk_bytes) bytes += bytesBelow(run_dir, -1, limits.disk_bytes);
    if (bytes <= limits.disk_bytes && !boxed && isolation.uid >= 0)
      bytes += bytesOwnedBy(isolation.uid, sharedTemporaryFolders());
    return bytes > limits.disk_bytes;
  };
  std::string answer, info;
  SandboxInit sandbox;
  bool timed_out = false, disk_full = false;
  // The wall limit counts the run's own time: what its processes waited for a CPU is added to it
  // (read from /proc only once the limit is reached, and again when the added time has passed),
  // up to kLoadAllowance times the limit; stopped there short of its own limit, it was held back.
  // A tree that keeps more than one process runnable (a fork bomb, threads: its CPU time and
  // waits sum to more than its wall) waits for itself: no time added.
  const double cap = kLoadAllowance * limits.wall_seconds;
  double limit = limits.wall_seconds, waited = -1;
  bool held_back = false;
  const auto reachedLimit = [&] {
    const double now = secondsSince(start);
    if (now < limit) return false;
    const TreeTimes times = treeTimes(pid);
    if (times.cpu + times.waited_total > 1.5 * now)
      waited = -1;
    else
      waited = std::max(waited, times.waited);
    const double own = now - std::max(waited, 0.0);
    if (own >= limits.wall_seconds - kLimitRecheckSeconds) return true;
    if (now >= cap) return held_back = true;
    limit = std::min(cap, now + (limits.wall_seconds - own));
    return false;
  };
  auto next_disk_check = Clock::now();
  const auto checkDisk = [&] {
    if (Clock::now() < next_disk_check) return false;
    next_disk_check = Clock::now() + std::chrono::milliseconds(int(kDiskCheckSeconds * 1000));
    return disk_full = diskFull();
  };
  const std::size_t max_answer = 512u << 20;
  std::string report;  // the sanitizers' channel, read as it comes (a full pipe would block them)
  const std::size_t max_report = 1u << 20;
  if (report_fds[0] >= 0) fcntl(report_fds[0], F_SETFL, O_NONBLOCK);
  const auto readReport = [&] {
    if (report_fds[0] < 0) return;
    char buffer[65536];
    for (ssize_t n; (n = read(report_fds[0], buffer, sizeof buffer)) > 0;)
      if (report.size() < max_report)
        report.append(
            buffer, std::min<std::size_t>(static_cast<std::size_t>(n), max_report - report.size()));
  };
  for (bool open_pipe = true; open_pipe;) {
    if (boxed) {
      readAvailable(info_fds[0], info);
      sandbox.pin(info);
    }
    readReport();
    if (reachedLimit()) {
      timed_out = true;
      break;
    }
    const double left = std::max(0.0, limit - secondsSince(start));
    if (checkDisk()) break;
    pollfd polled[2] = {{pipe_fds[0], POLLIN, 0}, {report_fds[0], POLLIN, 0}};
    const int ready = poll(polled, report_fds[0] >= 0 ? 2 : 1,
                           static_cast<int>(std::min(left, kDiskCheckSeconds) * 1000) + 1);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0 || !(polled[0].revents & (POLLIN | POLLHUP | POLLERR))) continue;
    char buffer[65536];
    const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      open_pipe = false;
    else if (answer.size() < max_answer)
      answer.append(buffer, static_cast<std::size_t>(n));
  }
  close(pipe_fds[0]);
  int status = 0;
  bool reaped = false;
  while (!timed_out && !disk_full) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      reaped = true;
      break;
    }
    if (reachedLimit()) {
      timed_out = true;
      break;
    }
    if (checkDisk()) break;
    readReport();
    usleep(2000);
  }
  // Read before the kill: whether a run stopped at the limit computed, slept or was held back.
  const TreeTimes at_limit = reaped ? TreeTimes{} : treeTimes(pid);
  const double cpu_at_limit = at_limit.cpu;
  if (!reaped) waited = std::max(waited, at_limit.waited);
  if (boxed) {
    readAvailable(info_fds[0], info);
    close(info_fds[0]);
    if (!reaped) sandbox.pin(info);  // bubblewrap is still alive: its child cannot be reused
  }
  ChildRun run;
  run.disk_limit_bytes = limits.disk_bytes;
  run.cpu_seconds = cpu_at_limit;
  run.waited_seconds = waited;
  if (expect_answer) {
    const std::optional<probe::ProbeMessage> frame = probe::decodeMessage(answer);
    run.answered = frame && frame->nonce == request_nonce;
  }
  if (!reaped) {
    sandbox.killAndWait();
    if (!(supervised && stopSupervisor(pid, status))) {
      killGroup(pid);
      waitpid(pid, &status, 0);
    }
    run.status = disk_full ? ChildStatus::DiskLimit : ChildStatus::TimedOut;
    if (!disk_full) run.limit_seconds = limits.wall_seconds;
  } else {
    sandbox.killAndWait();             // normally gone already: bubblewrap exits after its sandbox
    if (pid > 1) kill(-pid, SIGKILL);  // any grandchildren left in the group (pid is reaped)
    const std::optional<int> boxed_exit = boxed ? bubblewrapExitCode(info) : std::nullopt;
    // bubblewrap and our supervisor report a child killed by signal S as exit code 128 + S.
    const int code = boxed_exit ? *boxed_exit : WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (boxed && !boxed_exit) {
      run.status = ChildStatus::NotStarted;  // bubblewrap failed before the program ended
    } else if ((boxed || supervised) && code > 128 && code < 160) {
      run.status = ChildStatus::Crashed;
      run.signal = code - 128;
    } else if (!boxed && WIFSIGNALED(status)) {
      run.status = ChildStatus::Crashed;
      run.signal = WTERMSIG(status);
    } else if (code != 0) {
      run.status = ChildStatus::ExitedNonZero;
      run.exit_code = code;
    } else if (expect_answer) {
      run.answer = probe::decodeMessage(answer);
      if (run.answer && run.answer->nonce != request_nonce) run.answer.reset();
      run.status = run.answer ? ChildStatus::Ok : ChildStatus::NoAnswer;
    } else {
      run.status = ChildStatus::Ok;
    }
  }
  // A failure of ours before the program started outranks whatever the exit code says.
  if (const unsigned char why = setupReport(setup_fds[0])) {
    run = notStarted(setupFailureText(why), why == kSetupNoSlot);
  } else if (run.status == ChildStatus::NotStarted) {
    const std::string said = readHead(err_path, 2000, 1);
    run.grader_problem = "bubblewrap failed: " + said.substr(0, said.find('\n'));
    run.waiting_for_slot = said.find("Resource temporarily unavailable") != std::string::npos;
  }
  close(setup_fds[0]);
  if (report_fds[0] >= 0) {
    readReport();
    close(report_fds[0]);
    run.sanitizer_report = report;
  }
  // Killed by the kernel at the memory cgroup's limit: the memory limit, not a crash.
  if (run.status == ChildStatus::Crashed && run.signal == SIGKILL && cgroup.oomKilled())
    run.memory_limit = true;
  run.seconds = secondsSince(start);
  if (run.status == ChildStatus::TimedOut && held_back) {
    // Held back by load to kLoadAllowance times the limit: ours, whatever the program is.
    std::ostringstream why;
    why << "the machine's load held the run back: stopped after " << static_cast<int>(run.seconds)
        << " s, of which it waited " << static_cast<int>(waited) << " s for a CPU, short of its "
        << limits.wall_seconds << " s limit";
    ChildRun ours = notStarted(why.str());
    ours.seconds = run.seconds;
    ours.cpu_seconds = run.cpu_seconds;
    ours.waited_seconds = run.waited_seconds;
    run = ours;
  }
  if (run.status != ChildStatus::NotStarted) run.stderr_head = readHead(err_path, 2000, 12);
  // What the run wrote does not outlive it: its folder's files (unless kept for --keep-work) and
  // all but the start of its output files.
  if (!limits.keep_files) {
    if (run_dir != work_dir) removeTree(run_dir);  // the student's own folder, not ours
    for (const auto& path : {out_path, err_path})
      if (fileSize(path) > static_cast<long>(kKeptOutputBytes))
        truncate(path.c_str(), static_cast<off_t>(kKeptOutputBytes));
  }
  return run;
}

}  // namespace

ChildRun runChild(const std::vector<std::string>& command, const std::filesystem::path& work_dir,
                  const std::filesystem::path& stdin_file, const ChildLimits& limits,
                  bool expect_answer, std::uint64_t request_nonce) {
  const auto first = Clock::now();
  ChildRun run;
  // A run the grader could not start is tried again: while the uid's process slots are taken
  // (another run's fork bomb), for as long as any run of the uid can hold them (slotWait: by
  // then that run has been stopped), the wall limit counting from the attempt that starts; any
  // other failure of ours, once.
  for (int attempt = 0;; ++attempt) {
    run = runChildOnce(command, work_dir, stdin_file, limits, expect_answer, request_nonce,
                       Clock::now());
    if (run.status != ChildStatus::NotStarted) break;
    if (run.waiting_for_slot ? secondsSince(first) >= slotWait(limits) : attempt >= 1) break;
    usleep(50000);
  }
  if (limits.answers && run.verdict() == Verdict::NonFinite) {
    std::lock_guard<std::mutex> lock(limits.answers->mutex);
    limits.answers->non_finite.insert(work_dir.filename().string());
  }
  if (limits.log) {
    std::lock_guard<std::mutex> lock(limits.log->mutex);
    limits.log->verdicts.push_back(run.verdict());
    limits.log->folders.push_back(work_dir.filename().string());
  }
  return run;
}

ChildLimits limitsForTimeout(double seconds) {
  ChildLimits limits;
  limits.wall_seconds = seconds;
  limits.cpu_seconds = static_cast<std::uint64_t>(seconds) + 1;
  return limits;
}

double slotWait(const ChildLimits& limits) {
  return limits.slot_wait_seconds > 0
             ? limits.slot_wait_seconds
             : kSanitizerSlowdown * kLoadAllowance * limits.wall_seconds + kSlotWaitMarginSeconds;
}

std::vector<std::vector<std::string>> probeVariants() {
  return {{},
          {"MALLOC_PERTURB_=165", std::string(probe::kStackFillVariable) + "=ff",
           "CLOTHREF_PROBE_VARIANT=" + std::string(1021, 'b')}};
}

bool sameAnswer(const probe::ProbeMessage& a, const probe::ProbeMessage& b) {
  if (a.ints != b.ints || a.texts != b.texts || a.floats.size() != b.floats.size()) return false;
  for (auto x = a.floats.begin(), y = b.floats.begin(); x != a.floats.end(); ++x, ++y)
    if (x->first != y->first || x->second.size() != y->second.size() ||
        std::memcmp(x->second.data(), y->second.data(), x->second.size() * sizeof(float)) != 0)
      return false;
  return true;
}

ChildRun runProbe(const std::filesystem::path& executable, probe::ProbeMessage request,
                  const std::filesystem::path& work_dir, const ChildLimits& limits) {
  std::random_device entropy;
  request.nonce = (std::uint64_t(entropy()) << 32) ^ entropy();
  const auto request_path = work_dir / "request.bin";
  {
    std::ofstream out(request_path, std::ios::binary | std::ios::trunc);
    const std::string frame = probe::encodeMessage(request);
    out.write(frame.data(), static_cast<std::streamsize>(frame.size()));
  }
  chmod(request_path.c_str(), 0600);
  return runChild({executable.string()}, work_dir, request_path, limits, true, request.nonce);
}

ChildRun runProbeTwice(const std::filesystem::path& executable, const probe::ProbeMessage& request,
                       const std::filesystem::path& work_dir, const ChildLimits& limits) {
  ChildLimits variant = limits;
  variant.fixed_layout = true;
  variant.log = nullptr;  // one verdict for the pair, below
  const std::vector<std::vector<std::string>> variants = probeVariants();
  variant.environment = variants[0];
  // A run stopped at the wall-clock limit spent its own time there (runChild does not count
  // load's wait, and a run held back by load is ours): an endless loop costs one limit.
  ChildRun first = runProbe(executable, request, work_dir, variant);
  const bool repeat = first.status == ChildStatus::Ok || first.status == ChildStatus::Crashed ||
                      first.status == ChildStatus::ExitedNonZero ||
                      first.status == ChildStatus::NoAnswer;
  if (repeat) {
    variant.environment = variants[1];
    const ChildRun second = runProbe(executable, request, work_dir, variant);
    const bool alike =
        second.status == first.status &&
        (first.status == ChildStatus::Ok
             ? first.answer && second.answer && sameAnswer(*first.answer, *second.answer)
             : first.verdict() == second.verdict() && first.signal == second.signal &&
                   first.exit_code == second.exit_code);
    if (second.status == ChildStatus::NotStarted) {
      first = second;  // ours: the pair is not decided
    } else if (!alike) {
      const std::string how =
          "first run: " + first.describe() + "; second run: " + second.describe() +
          (first.status == second.status ? " with different numbers" : "") + "\n";
      first.status = ChildStatus::Varies;
      first.answer.reset();
      first.stderr_head =
          how + (first.stderr_head.empty() ? second.stderr_head : first.stderr_head);
    }
  }
  if (limits.log) {
    std::lock_guard<std::mutex> lock(limits.log->mutex);
    limits.log->verdicts.push_back(first.verdict());
    limits.log->folders.push_back(work_dir.filename().string());
  }
  return first;
}

}  // namespace clothref::grader
