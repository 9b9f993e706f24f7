#include "grader/grade/run/child_process.h"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/personality.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <random>
#include <regex>
#include <sstream>

#include "grader/grade/run/folders.h"

namespace clothref::grader {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void setLimit(int resource, std::uint64_t value) {
  rlimit limit{static_cast<rlim_t>(value), static_cast<rlim_t>(value)};
  setrlimit(resource, &limit);
}

std::string readHead(const std::filesystem::path& path, std::size_t max_bytes, int max_lines) {
  std::ifstream in(path, std::ios::binary);
  std::string out, line;
  int lines = 0;
  while (lines < max_lines && out.size() < max_bytes && std::getline(in, line)) {
    out += line.substr(0, max_bytes - out.size());
    out += '\n';
    ++lines;
  }
  return out;
}

std::string signalName(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "SIGSEGV, segmentation fault";
    case SIGABRT:
      return "SIGABRT, abort";
    case SIGFPE:
      return "SIGFPE, arithmetic error";
    case SIGBUS:
      return "SIGBUS, bus error";
    case SIGILL:
      return "SIGILL, illegal instruction";
    case SIGKILL:
      return "SIGKILL";
    case SIGXCPU:
      return "SIGXCPU, CPU time limit";
    case SIGXFSZ:
      return "SIGXFSZ, output file size limit";
    default:
      return "signal " + std::to_string(signal);
  }
}

// Child side of fork: never returns.
// argv and env are built before fork: after fork in a threaded grader only async-signal-safe
// calls are allowed (no allocation).
struct ExecArgs {
  std::vector<std::string> strings, environment;
  std::vector<char*> argv, envp;
  std::string dir;
  // A clean environment: nothing of the grader's leaks into student code; `extra` adds to it.
  ExecArgs(const std::vector<std::string>& command, const std::filesystem::path& where,
           const std::vector<std::string>& extra = {})
      : strings(command), environment{"PATH=/usr/local/bin:/usr/bin:/bin", "LC_ALL=C"},
        dir(where.string()) {
    for (std::string& a : strings) argv.push_back(a.data());
    argv.push_back(nullptr);
    environment.insert(environment.end(), extra.begin(), extra.end());
    for (std::string& e : environment) envp.push_back(e.data());
    envp.push_back(nullptr);
  }
};

// bubblewrap reports the sandbox's pid and, at the end, the program's exit code on this
// descriptor (--json-status-fd; the one after the answer's).
constexpr int kInfoFd = probe::kResultFd + 1;
// Where a child reports why it could not start the program (before exec; close-on-exec, so a
// successful exec closes it unwritten): the grader's failures, told apart from the student's.
constexpr int kSetupFd = kInfoFd + 1;

enum SetupFailure : unsigned char {
  kSetupChdir = 1,  // its folder
  kSetupMount,      // the private mount namespace or a mount in it
  kSetupUid,        // the uid drop
  kSetupExec,       // the program could not be executed
  kSetupNoSlot,     // no process slot for the uid (another run's fork bomb): retried
  kSetupClone,      // the fallback's supervisor could not start the program
  kSetupInjected    // a fault injected by CLOTHREF_GRADER_FAULT (tests)
};

const char* setupFailureText(unsigned char why) {
  switch (why) {
    case kSetupChdir:
      return "could not enter its folder";
    case kSetupMount:
      return "could not make its private mount namespace";
    case kSetupUid:
      return "could not drop to its uid";
    case kSetupExec:
      return "could not execute the program";
    case kSetupNoSlot:
      return "no process slot for the uid";
    case kSetupClone:
      return "the supervisor could not start the program";
    case kSetupInjected:
      return "an injected fault (CLOTHREF_GRADER_FAULT)";
    default:
      return "an unknown failure";
  }
}

[[noreturn]] void setupFailed(SetupFailure why, int fd = kSetupFd) {
  const unsigned char code = why;
  [[maybe_unused]] const ssize_t n = write(fd, &code, 1);
  _exit(126);
}

// CLOTHREF_GRADER_FAULT: faults of ours injected by the tests (docs/reliability.md), a comma list
// of points, each once ("fork") or a number of times ("fork*2") or always ("fork*0"): fork (a
// probe's fork fails), pipe (its pipes), files (its stdout/stderr files), setup (the child fails
// before exec), bwrap (bubblewrap fails before the program starts), tool-fork (a compile's fork),
// tool-setup (a compile's child fails before exec). Read once; student code never sees it.
bool injectFault(const char* point) {
  struct Budget {
    std::string point;
    long left;  // < 0: always
  };
  static std::mutex mutex;
  static std::vector<Budget> budgets = [] {
    std::vector<Budget> all;
    const char* spec = std::getenv("CLOTHREF_GRADER_FAULT");
    std::istringstream in(spec ? spec : "");
    for (std::string item; std::getline(in, item, ',');) {
      const std::size_t star = item.find('*');
      const long count = star == std::string::npos ? 1 : std::atol(item.c_str() + star + 1);
      all.push_back({item.substr(0, star), count == 0 ? -1 : count});
    }
    return all;
  }();
  std::lock_guard<std::mutex> lock(mutex);
  for (Budget& budget : budgets)
    if (budget.point == point && budget.left != 0) {
      if (budget.left > 0) --budget.left;
      return true;
    }
  return false;
}

struct ExecLimits {
  const ChildLimits* limits = nullptr;  // nullptr: tool limits below
  double tool_seconds = 0;
  int uid = -1;
  // A run in the fallback as root: a private mount namespace where `hide` (our folders) is
  // covered by an empty read-only tmpfs and `private_tmp` by an empty writable one of
  // kPrivateTmpBytes each (built before fork: no allocation after it).
  bool new_mount_namespace = false;
  std::vector<std::string> hide, private_tmp;
  bool injected_fault = false;  // CLOTHREF_GRADER_FAULT: fail before exec, as a setup failure
};

// The private /var/tmp and /dev/shm of a fallback run (its /tmp holds our scratch folder).
constexpr const char* kPrivateTmpOptions = "size=16m,mode=1777";

// Covers `hide` in a private mount namespace (root only, before the uid drop). It fails closed:
// where the namespace or a mount fails, the child reports it and exits instead of running with
// our folders visible.
void hideFolders(const ExecLimits& how) {
  if (!how.new_mount_namespace) return;
  if (unshare(CLONE_NEWNS) != 0) setupFailed(kSetupMount);
  if (mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) setupFailed(kSetupMount);
  for (const std::string& folder : how.hide)
    if (mount("tmpfs", folder.c_str(), "tmpfs", MS_RDONLY | MS_NOSUID | MS_NODEV | MS_NOEXEC,
              "size=4k,mode=0555") != 0)
      setupFailed(kSetupMount);
  for (const std::string& folder : how.private_tmp)
    if (mount("tmpfs", folder.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, kPrivateTmpOptions) != 0)
      setupFailed(kSetupMount);
}

// Moves `fd` to `target` (a fixed number the child's layout reserves); -1 stays closed.
void place(int fd, int target) {
  if (fd >= 0 && fd != target) dup2(fd, target);
}

[[noreturn]] void execChild(const ExecArgs& exec, int stdin_fd, int stdout_fd, int stderr_fd,
                            int answer_fd, int info_fd, int setup_fd, const ExecLimits& how) {
  setpgid(0, 0);
  // The setup pipe first, above every other descriptor the layout uses, then the rest in place.
  const int setup = fcntl(setup_fd, F_DUPFD_CLOEXEC, kSetupFd + 1);
  dup2(stdin_fd, 0);
  dup2(stdout_fd, 1);
  dup2(stderr_fd, 2);
  if (answer_fd >= 0) {
    dup2(answer_fd, probe::kResultFd);
  } else {
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, probe::kResultFd);
  }
  if (info_fd >= 0)
    place(info_fd, kInfoFd);
  else
    close(kInfoFd);  // no descriptor of the grader's leaks into the program
  if (setup >= 0) {
    dup3(setup, kSetupFd, O_CLOEXEC);
    close(setup);
  }
  for (int fd = kSetupFd + 1; fd < 1024; ++fd) close(fd);
  if (how.injected_fault) setupFailed(kSetupInjected);
  if (chdir(exec.dir.c_str()) != 0) setupFailed(kSetupChdir);
  if (const ChildLimits* limits = how.limits) {
    setLimit(RLIMIT_CPU, limits->cpu_seconds);
    setLimit(RLIMIT_AS, limits->address_space_bytes);
    setLimit(RLIMIT_FSIZE, limits->file_size_bytes);
    setLimit(RLIMIT_NOFILE, limits->open_files);
    setLimit(RLIMIT_NPROC, limits->processes);
  } else {
    setLimit(RLIMIT_CPU, static_cast<std::uint64_t>(how.tool_seconds) + 1);
    setLimit(RLIMIT_AS, kToolAddressSpace);
    setLimit(RLIMIT_FSIZE, kToolFileSize);
  }
  setLimit(RLIMIT_CORE, 0);
  hideFolders(how);
  if (how.uid >= 0) {
    // Groups first, then gid, then uid: after setresuid we could not change the others.
    const auto id = static_cast<uid_t>(how.uid);
    // Raw system calls: glibc's wrappers signal every thread glibc believes exists and wait for
    // them, and after the raw clone of the fallback's supervisor it still believes in the
    // grader's threads (a wait that never ends). This process has one thread.
    if (syscall(SYS_setgroups, 0, nullptr) != 0 || syscall(SYS_setresgid, id, id, id) != 0 ||
        syscall(SYS_setresuid, id, id, id) != 0)
      setupFailed(kSetupUid);
  }
  prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0);  // no set-uid program gives the privileges back
  // The same addresses on every run (kept through bubblewrap's exec, which is not set-uid): what
  // undefined behaviour reads then depends on the run's variant only (ChildLimits::variant).
  if (how.limits && how.limits->fixed_layout) personality(ADDR_NO_RANDOMIZE);
  execve(exec.argv[0], exec.argv.data(), exec.envp.data());
  if (errno == ENOENT) execvpe(exec.argv[0], exec.argv.data(), exec.envp.data());
  // The uid's process slots are taken (another run's fork bomb): the caller retries.
  setupFailed(errno == EAGAIN ? kSetupNoSlot : kSetupExec);
}

// A status the supervisor passes on as its exit code, the way bubblewrap does: a child killed by
// signal S becomes 128 + S.
[[noreturn]] void exitLike(int status) {
  if (WIFSIGNALED(status)) _exit(128 + WTERMSIG(status));
  _exit(WIFEXITED(status) ? WEXITSTATUS(status) : 1);
}

// The exit code of a supervisor that lost its student program (waitpid failed).
constexpr int kSupervisorForkFailed = 124;

volatile pid_t supervised_student = 0;

// The grader's SIGTERM at a wall timeout: the student program dies, then the supervisor cleans up.
void stopStudent(int) {
  const pid_t student = supervised_student;
  if (student > 1) {
    kill(-student, SIGKILL);
    kill(student, SIGKILL);
  }
}

// Subreaper mode: kills every child the supervisor has (the student's orphans were reparented to
// it) until none is left; children of a killed child become ours in turn. Async-signal-safe.
void killInherited() {
  char path[64] = "/proc/self/task/";
  {
    // "/proc/self/task/<tid>/children" without snprintf: the supervisor has one thread.
    char digits[24];
    int n = 0;
    for (long v = getpid(); v > 0 && n < 23; v /= 10) digits[n++] = static_cast<char>('0' + v % 10);
    std::size_t at = std::strlen(path);
    while (n > 0) path[at++] = digits[--n];
    const char tail[] = "/children";
    for (const char* c = tail; *c; ++c) path[at++] = *c;
    path[at] = '\0';
  }
  for (;;) {
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
      char buffer[4096];
      const ssize_t n = read(fd, buffer, sizeof buffer - 1);
      close(fd);
      long pid = 0;
      for (ssize_t k = 0; k <= n && n > 0; ++k) {
        if (k < n && buffer[k] >= '0' && buffer[k] <= '9') {
          pid = pid * 10 + (buffer[k] - '0');
        } else {
          if (pid > 1) kill(static_cast<pid_t>(pid), SIGKILL);
          pid = 0;
        }
      }
    }
    int status = 0;
    if (waitpid(-1, &status, 0) < 0 && errno == ECHILD) return;
  }
}

// The rlimits fallback's process between the grader and the student program: pid 1 of a new pid
// namespace (`in_namespace`) or a child subreaper. It starts the student program, reaps it and
// whatever was reparented to it, passes the student's status on, and leaves nothing behind: in a
// namespace the kernel kills the rest when pid 1 exits; as a subreaper it kills them itself.
[[noreturn]] void superviseChild(const ExecArgs& exec, int stdin_fd, int stdout_fd, int stderr_fd,
                                 int answer_fd, int setup_fd, const ExecLimits& how,
                                 bool in_namespace) {
  setpgid(0, 0);
  prctl(PR_SET_PDEATHSIG, SIGKILL);  // the grader gone: so is the supervisor (and its namespace)
  if (!in_namespace) prctl(PR_SET_CHILD_SUBREAPER, 1);
  struct sigaction action {};
  action.sa_handler = stopStudent;
  sigaction(SIGTERM, &action, nullptr);
  // A raw clone, not glibc's fork(): in a child of a threaded grader, fork() would wait for the
  // malloc and stdio locks that other threads held when we were cloned, forever.
  const pid_t student = static_cast<pid_t>(syscall(SYS_clone, SIGCHLD, 0, 0, 0, 0));
  if (student < 0) setupFailed(kSetupClone, setup_fd);
  if (student == 0) {
    signal(SIGTERM, SIG_DFL);
    execChild(exec, stdin_fd, stdout_fd, stderr_fd, answer_fd, -1, setup_fd, how);
  }
  supervised_student = student;
  // Only the student holds the answer pipe and the output files: the grader sees the end of the
  // answer when the student's whole tree is gone, not when we are.
  for (int fd = 0; fd < 1024; ++fd) close(fd);
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(-1, &status, 0);
    if (done == student) break;
    if (done < 0 && errno != EINTR) _exit(kSupervisorForkFailed);
  }
  supervised_student = 0;
  if (!in_namespace) killInherited();
  exitLike(status);
}

// The sandbox's first process (bubblewrap's pid 1 of the new pid namespace), pinned by a pidfd,
// once bubblewrap has reported it and only if it really is in the reported namespace.
struct SandboxInit {
  int pidfd = -1;
  void pin(const std::string& info_json) {
    if (pidfd >= 0) return;
    const BubblewrapInfo info = parseBubblewrapInfo(info_json);
    if (info.child_pid <= 0) return;
    const int fd = static_cast<int>(syscall(SYS_pidfd_open, info.child_pid, 0));
    if (fd < 0) return;
    // The pid could have been reused by the time we opened it: check its pid namespace.
    char link[64] = {};
    const std::string ns_path = "/proc/" + std::to_string(info.child_pid) + "/ns/pid";
    const ssize_t n = readlink(ns_path.c_str(), link, sizeof link - 1);
    if (n > 0 && std::string(link) == "pid:[" + std::to_string(info.pid_namespace) + "]")
      pidfd = fd;
    else
      close(fd);
  }
  // Kills the namespace's init (the kernel then kills every process in the namespace) and waits
  // until it has exited, which happens only after all of them are gone.
  void killAndWait() {
    if (pidfd < 0) return;
    syscall(SYS_pidfd_send_signal, pidfd, SIGKILL, nullptr, 0);
    pollfd fd{pidfd, POLLIN, 0};
    for (int k = 0; k < 100 && poll(&fd, 1, 100) == 0; ++k) {
    }
    close(pidfd);
    pidfd = -1;
  }
};

// SIGKILL to the process group `pid` leads and to `pid`: never for a pid <= 1 (kill(-1) signals
// every process we may signal; kill(0) our own group).
void killGroup(pid_t pid) {
  if (pid <= 1) return;
  kill(-pid, SIGKILL);
  kill(pid, SIGKILL);
}

// A wall timeout in the rlimits fallback: SIGTERM lets the supervisor kill the student and reap
// (and, as a subreaper, kill) what it left; SIGKILL after 2 s if it does not finish.
// True when it exited (and was reaped, `status` set): its pid must not be signalled again.
bool stopSupervisor(pid_t pid, int& status) {
  if (pid <= 1) return false;
  kill(pid, SIGTERM);
  for (int k = 0; k < 200; ++k) {
    if (waitpid(pid, &status, WNOHANG) == pid) return true;
    usleep(10000);
  }
  return false;
}

// A run's own cgroup (Isolation::cgroup_parent set): the child joins it first thing after fork;
// when the run ends, cgroup.kill ends every process in it, whatever it did to detach (setsid,
// double fork, a new session in another process group), and the empty folder is removed.
struct RunCgroup {
  std::string dir;
  int procs_fd = -1;  // cgroup.procs, opened before fork (no allocation in the child)
  explicit RunCgroup(const std::string& parent) {
    if (parent.empty()) return;
    static std::atomic<unsigned long> next{0};
    dir = parent + "/run-" + std::to_string(next++);
    if (mkdir(dir.c_str(), 0700) != 0) {
      dir.clear();
      return;
    }
    procs_fd = open((dir + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
  }
  // Child side, before the uid drop: "0" moves the writing process.
  void join() const {
    if (procs_fd >= 0) (void)!write(procs_fd, "0", 1);
  }
  ~RunCgroup() {
    if (dir.empty()) return;
    if (procs_fd >= 0) close(procs_fd);
    const int kill_fd = open((dir + "/cgroup.kill").c_str(), O_WRONLY | O_CLOEXEC);
    if (kill_fd >= 0) {
      (void)!write(kill_fd, "1", 1);
      close(kill_fd);
    }
    // rmdir succeeds once the last process has been reaped by its parent (up to 2 s).
    for (int k = 0; k < 200 && rmdir(dir.c_str()) != 0 && errno == EBUSY; ++k) usleep(10000);
  }
};

void readAvailable(int fd, std::string& into) {
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;)
    into.append(buffer, static_cast<std::size_t>(n));
}

}  // namespace

std::string ChildRun::describe() const {
  std::ostringstream out;
  switch (status) {
    case ChildStatus::Ok:
      out << "finished";
      break;
    case ChildStatus::Crashed:
      if (verdict() == Verdict::MemoryLimit)
        out << "ran out of memory (address-space limit; std::bad_alloc, then abort)";
      else if (verdict() == Verdict::OutputLimit)
        out << "was stopped for writing too much output (file-size limit, SIGXFSZ)";
      else if (verdict() == Verdict::TimedOut)
        out << "timed out: stopped at the CPU time limit (SIGXCPU)";
      else
        out << "crashed (" << signalName(signal) << ")";
      break;
    case ChildStatus::TimedOut:
      out << "timed out after " << static_cast<int>(seconds + 0.5) << " s";
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
  if (signal == SIGXCPU) return Verdict::TimedOut;
  if (signal == SIGXFSZ) return Verdict::OutputLimit;
  // The C++ runtime's last words when `new` fails under RLIMIT_AS (the student could print them
  // too: that only changes this word, never a score).
  if (signal == SIGABRT && stderr_head.find("std::bad_alloc") != std::string::npos)
    return Verdict::MemoryLimit;
  return Verdict::Crashed;
}

namespace {

// The setup pipe's report: 0 when the program started (the pipe closed unwritten at exec).
unsigned char setupReport(int fd) {
  unsigned char code = 0;
  for (;;) {
    const ssize_t n = read(fd, &code, 1);
    if (n < 0 && errno == EINTR) continue;
    return n == 1 ? code : 0;
  }
}

// What bubblewrap reported on --json-status-fd: the sandbox's pid first, then, when the program
// ran to its end, its exit code. No exit code: bubblewrap itself failed (or was stopped).
std::optional<int> bubblewrapExitCode(const std::string& json) {
  std::smatch match;
  static const std::regex exit_code(R"re("exit-code"\s*:\s*(-?\d+))re");
  if (std::regex_search(json, match, exit_code)) return std::stoi(match[1]);
  return std::nullopt;
}

long fileSize(const std::filesystem::path& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0 ? static_cast<long>(info.st_size) : 0;
}

// A run the grader could not start: its own words, never the student's stderr.
ChildRun notStarted(const std::string& why, bool waiting_for_slot = false) {
  ChildRun run;
  run.status = ChildStatus::NotStarted;
  run.grader_problem = why;
  run.waiting_for_slot = waiting_for_slot;
  return run;
}

// The folders a fallback run may not see (our folders, covered) and the shared ones it gets empty
// and private (/var/tmp, /dev/shm; /tmp holds the scratch folder), as mount points that exist.
void privateMounts(const Isolation& isolation, const std::filesystem::path& work_dir,
                   ExecLimits& how) {
  if (isolation.kind != IsolationKind::Rlimits || !isolation.private_mounts || isolation.uid < 0)
    return;
  how.new_mount_namespace = true;
  std::error_code error;
  for (const std::filesystem::path& folder : isolation.ours)
    if (std::filesystem::is_directory(folder, error))
      how.hide.push_back(folder.lexically_normal().string());
  const std::string work = std::filesystem::weakly_canonical(work_dir, error).string();
  for (const char* shared : {"/var/tmp", "/dev/shm"}) {
    const std::string real = std::filesystem::weakly_canonical(shared, error).string();
    if (!error && std::filesystem::is_directory(real, error) &&
        work.rfind(real + "/", 0) != 0)
      how.private_tmp.push_back(real);
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
      boxed ? bubblewrapArgv(isolation, command, run_dir, kInfoFd) : command;
  // Injected faults reach probe runs only (not the isolation's detection run).
  const auto fault = [&](const char* point) { return expect_answer && injectFault(point); };
  // bubblewrap refuses an option it does not know before it starts anything
  if (boxed && fault("bwrap")) inner.insert(inner.begin() + 1, "--clothref-injected-fault");
  argv.insert(argv.end(), inner.begin(), inner.end());
  const auto out_path = work_dir / "child.stdout";
  const auto err_path = work_dir / "child.stderr";
  const bool files_fault = fault("files"), pipe_fault = fault("pipe");
  int in_fd = open(stdin_file.c_str(), O_RDONLY | O_CLOEXEC);
  int out_fd = files_fault ? -1 : open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  int pipe_fds[2] = {-1, -1};
  int info_fds[2] = {-1, -1};
  int setup_fds[2] = {-1, -1};
  if (in_fd < 0 || out_fd < 0 || err_fd < 0 || pipe_fault || pipe2(pipe_fds, O_CLOEXEC) != 0 ||
      pipe2(setup_fds, O_CLOEXEC) != 0 ||
      (boxed && pipe2(info_fds, O_CLOEXEC | O_NONBLOCK) != 0)) {
    for (int fd : {in_fd, out_fd, err_fd, pipe_fds[0], pipe_fds[1], info_fds[0], info_fds[1],
                   setup_fds[0], setup_fds[1]})
      if (fd >= 0) close(fd);
    return notStarted(files_fault || pipe_fault ? setupFailureText(kSetupInjected)
                                                : "cannot set up the child's files or pipes");
  }
  const ExecArgs exec(argv, run_dir, limits.environment);
  ExecLimits how;
  how.limits = &limits;
  how.uid = isolation.uid;
  how.injected_fault = fault("setup");
  privateMounts(isolation, work_dir, how);
  // The rlimits fallback puts a supervisor between us and the student (superviseChild).
  const bool supervised = !boxed && isolation.kind == IsolationKind::Rlimits &&
                          isolation.containment != Containment::None;
  bool in_namespace = supervised && isolation.containment == Containment::PidNamespace;
  const RunCgroup cgroup(isolation.kind == IsolationKind::None ? "" : isolation.cgroup_parent);
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
  const int answer_fd = expect_answer ? pipe_fds[1] : -1;
  if (pid == 0) {
    cgroup.join();
    if (supervised)
      superviseChild(exec, in_fd, out_fd, err_fd, answer_fd, setup_fds[1], how, in_namespace);
    execChild(exec, in_fd, out_fd, err_fd, answer_fd, info_fds[1], setup_fds[1], how);
  }
  const int fork_error = errno;
  for (int fd : {in_fd, out_fd, err_fd, pipe_fds[1], info_fds[1], setup_fds[1]})
    if (fd >= 0) close(fd);
  if (pid < 0) {
    // No process: nothing to wait for or kill (a kill(-1) would signal every process we may).
    for (int fd : {pipe_fds[0], info_fds[0], setup_fds[0]})
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
    if (bytes <= limits.disk_bytes)
      bytes += bytesBelow(run_dir, -1, limits.disk_bytes);
    if (bytes <= limits.disk_bytes && !boxed && isolation.uid >= 0)
      bytes += bytesOwnedBy(isolation.uid, sharedTemporaryFolders());
    return bytes > limits.disk_bytes;
  };
  std::string answer, info;
  SandboxInit sandbox;
  bool timed_out = false, disk_full = false;
  auto next_disk_check = Clock::now();
  const auto checkDisk = [&] {
    if (Clock::now() < next_disk_check) return false;
    next_disk_check = Clock::now() + std::chrono::milliseconds(int(kDiskCheckSeconds * 1000));
    return disk_full = diskFull();
  };
  const std::size_t max_answer = 512u << 20;
  for (bool open_pipe = true; open_pipe;) {
    if (boxed) {
      readAvailable(info_fds[0], info);
      sandbox.pin(info);
    }
    const double left = limits.wall_seconds - secondsSince(start);
    if (left <= 0) {
      timed_out = true;
      break;
    }
    if (checkDisk()) break;
    pollfd fd{pipe_fds[0], POLLIN, 0};
    const int ready = poll(&fd, 1, static_cast<int>(std::min(left, kDiskCheckSeconds) * 1000) + 1);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
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
    if (secondsSince(start) >= limits.wall_seconds) {
      timed_out = true;
      break;
    }
    if (checkDisk()) break;
    usleep(2000);
  }
  if (boxed) {
    readAvailable(info_fds[0], info);
    close(info_fds[0]);
    if (!reaped) sandbox.pin(info);  // bubblewrap is still alive: its child cannot be reused
  }
  ChildRun run;
  run.disk_limit_bytes = limits.disk_bytes;
  if (!reaped) {
    sandbox.killAndWait();
    if (!(supervised && stopSupervisor(pid, status))) {
      killGroup(pid);
      waitpid(pid, &status, 0);
    }
    run.status = disk_full ? ChildStatus::DiskLimit : ChildStatus::TimedOut;
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
  run.seconds = secondsSince(start);
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

// The fallback's confinement of one compile or link (docs/grading.md, "Sandbox"): as root, the
// tool uid, and (where a private mount namespace can be made) our folders covered. A command
// writing outside `work_dir` (the precompiled header into the cache) compiles only our own
// headers and keeps the grader's uid.
void confineTool(const Isolation& isolation, const std::vector<std::string>& command,
                 const std::filesystem::path& work_dir, ExecLimits& how) {
  if (isolation.tool_uid < 0) return;
  const auto under = [](const std::filesystem::path& path, const std::filesystem::path& root) {
    const std::string p = path.lexically_normal().string(), r = root.lexically_normal().string();
    return p == r || (p.size() > r.size() && p.compare(0, r.size(), r) == 0 && p[r.size()] == '/');
  };
  for (std::size_t k = 0; k + 1 < command.size(); ++k)
    if (command[k] == "-o" && !under(command[k + 1], work_dir)) return;
  // The tool uid writes its objects into the scratch folder, nowhere else.
  if (chown(work_dir.c_str(), static_cast<uid_t>(isolation.tool_uid),
            static_cast<gid_t>(isolation.tool_uid)) != 0 ||
      chmod(work_dir.c_str(), 0700) != 0)
    return;
  how.uid = isolation.tool_uid;
  if (isolation.kind != IsolationKind::Rlimits || !isolation.private_mounts) return;
  how.new_mount_namespace = true;
  std::error_code error;
  for (const std::filesystem::path& folder : isolation.ours) {
    if (folder.empty() || under(work_dir, folder) || !std::filesystem::is_directory(folder, error))
      continue;
    bool named = false;
    for (std::size_t k = 1; k < command.size() && !named; ++k) {
      const std::string arg = command[k].rfind("-I", 0) == 0 ? command[k].substr(2) : command[k];
      named = !arg.empty() && arg[0] == '/' && (under(arg, folder) || under(folder, arg));
    }
    if (!named) how.hide.push_back(folder.lexically_normal().string());
  }
}

}  // namespace

ChildRun runChild(const std::vector<std::string>& command, const std::filesystem::path& work_dir,
                  const std::filesystem::path& stdin_file, const ChildLimits& limits,
                  bool expect_answer, std::uint64_t request_nonce) {
  const auto first = Clock::now();
  ChildRun run;
  // A run the grader could not start is tried again: while the uid's process slots are taken
  // (another run's fork bomb), for up to one more wall limit (by then the run holding them has
  // been killed), the wall limit counting from the attempt that starts; any other failure of
  // ours, once.
  for (int attempt = 0;; ++attempt) {
    run = runChildOnce(command, work_dir, stdin_file, limits, expect_answer, request_nonce,
                       Clock::now());
    if (run.status != ChildStatus::NotStarted) break;
    if (run.waiting_for_slot ? secondsSince(first) >= 2 * limits.wall_seconds + 1 : attempt >= 1)
      break;
    usleep(50000);
  }
  if (limits.log) {
    std::lock_guard<std::mutex> lock(limits.log->mutex);
    limits.log->verdicts.push_back(run.verdict());
  }
  return run;
}

std::vector<std::vector<std::string>> probeVariants() {
  return {{}, {"MALLOC_PERTURB_=165", "CLOTHREF_PROBE_VARIANT=" + std::string(1021, 'b')}};
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
  ChildRun first = runProbe(executable, request, work_dir, variant);
  const bool repeat = first.status == ChildStatus::Ok || first.status == ChildStatus::Crashed ||
                      first.status == ChildStatus::ExitedNonZero ||
                      first.status == ChildStatus::NoAnswer;
  if (repeat) {
    variant.environment = variants[1];
    const ChildRun second = runProbe(executable, request, work_dir, variant);
    const bool alike =
        second.status == first.status &&
        (first.status == ChildStatus::Ok ? first.answer && second.answer &&
                                               sameAnswer(*first.answer, *second.answer)
                                         : first.verdict() == second.verdict() &&
                                               first.signal == second.signal &&
                                               first.exit_code == second.exit_code);
    if (second.status == ChildStatus::NotStarted) {
      first = second;  // ours: the pair is not decided
    } else if (!alike) {
      const std::string how = "first run: " + first.describe() + "; second run: " +
                              second.describe() + (first.status == second.status ?
                              " with different numbers" : "") + "\n";
      first.status = ChildStatus::Varies;
      first.answer.reset();
      first.stderr_head = how + (first.stderr_head.empty() ? second.stderr_head
                                                           : first.stderr_head);
    }
  }
  if (limits.log) {
    std::lock_guard<std::mutex> lock(limits.log->mutex);
    limits.log->verdicts.push_back(first.verdict());
  }
  return first;
}

std::vector<ToolRun> runTools(const std::vector<std::vector<std::string>>& commands,
                              const std::filesystem::path& work_dir, int jobs, double wall_seconds,
                              const Isolation* isolation) {
  struct Running {
    pid_t pid;
    std::size_t index;
    Clock::time_point start;
    int setup_fd, status_fd;
  };
  std::vector<ToolRun> results(commands.size());
  std::vector<int> attempts(commands.size(), 0);
  std::vector<Running> running;
  std::vector<std::size_t> queue;
  for (std::size_t k = commands.size(); k-- > 0;) queue.push_back(k);
  const auto log_path = [&](std::size_t i) {
    return work_dir / ("tool-" + std::to_string(i) + ".log");
  };
  const auto null_in = std::filesystem::path("/dev/null");
  const bool boxed = isolation && isolation->kind == IsolationKind::Bubblewrap;
  // A failure of ours (the tool not started, bubblewrap failing) is tried again once, then
  // reported as ours: never as the student's compile error.
  const auto ours = [&](std::size_t index, const std::string& why) {
    if (attempts[index]++ == 0) {
      queue.push_back(index);
      return;
    }
    results[index].ok = false;
    results[index].ours = true;
    results[index].output = "grader: " + why + "\n";
  };
  while (!queue.empty() || !running.empty()) {
    while (!queue.empty() && static_cast<int>(running.size()) < std::max(1, jobs)) {
      const std::size_t index = queue.back();
      queue.pop_back();
      const auto log = log_path(index);
      int in_fd = open(null_in.c_str(), O_RDONLY | O_CLOEXEC);
      int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      int setup_fds[2] = {-1, -1}, status_fds[2] = {-1, -1};
      const bool pipes = pipe2(setup_fds, O_CLOEXEC) == 0 &&
                         (!boxed || pipe2(status_fds, O_CLOEXEC | O_NONBLOCK) == 0);
      ExecLimits how;
      how.tool_seconds = wall_seconds;
      if (isolation && isolation->kind != IsolationKind::None)
        confineTool(*isolation, commands[index], work_dir, how);
      how.injected_fault = injectFault("tool-setup");
      std::vector<std::string> argv = commands[index];
      if (boxed) argv = bubblewrapToolArgv(*isolation, commands[index], work_dir, kInfoFd);
      const ExecArgs exec(argv, work_dir);
      const bool fork_fault = injectFault("tool-fork");
      const pid_t pid = in_fd < 0 || log_fd < 0 || !pipes || fork_fault ? -1 : fork();
      if (pid == 0) execChild(exec, in_fd, log_fd, log_fd, -1, status_fds[1], setup_fds[1], how);
      const int fork_error = errno;
      for (int fd : {in_fd, log_fd, setup_fds[1], status_fds[1]})
        if (fd >= 0) close(fd);
      if (pid < 0) {
        for (int fd : {setup_fds[0], status_fds[0]})
          if (fd >= 0) close(fd);
        ours(index, fork_fault ? setupFailureText(kSetupInjected)
                               : std::string("cannot start the tool (fork: ") +
                                     std::strerror(fork_error) + ")");
        continue;
      }
      setpgid(pid, pid);
      running.push_back({pid, index, Clock::now(), setup_fds[0], status_fds[0]});
    }
    for (std::size_t r = 0; r < running.size();) {
      int status = 0;
      const pid_t done = waitpid(running[r].pid, &status, WNOHANG);
      const bool late = secondsSince(running[r].start) > wall_seconds;
      if (done == running[r].pid || late) {
        if (late && done != running[r].pid) {
          killGroup(running[r].pid);
          waitpid(running[r].pid, &status, 0);
        }
        const Running finished = running[r];
        running.erase(running.begin() + static_cast<long>(r));
        std::string json;
        if (finished.status_fd >= 0) {
          readAvailable(finished.status_fd, json);
          close(finished.status_fd);
        }
        const unsigned char why = setupReport(finished.setup_fd);
        close(finished.setup_fd);
        const std::string output = readHead(log_path(finished.index), 200000, 4000);
        if (why) {
          ours(finished.index, setupFailureText(why));
          continue;
        }
        if (boxed && !late && !bubblewrapExitCode(json)) {
          ours(finished.index, "bubblewrap failed: " + output.substr(0, output.find('\n')));
          continue;
        }
        ToolRun& result = results[finished.index];
        result.ok = !late && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        result.seconds = secondsSince(finished.start);
        result.output = output;
        if (late)
          result.output += "\n(stopped after " + std::to_string(int(wall_seconds)) + " s)\n";
      } else {
        ++r;
      }
    }
    usleep(5000);
  }
  return results;
}

}  // namespace clothref::grader
