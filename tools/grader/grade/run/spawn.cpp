#include "grader/grade/run/spawn.h"

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
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

namespace clothref::grader::spawn {

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

static void setLimit(int resource, std::uint64_t value) {
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

[[noreturn]] static void setupFailed(SetupFailure why, int fd = kSetupFd) {
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

// Where the child goes once its mounts are made: its folder and its program, as descriptors
// opened before a private filesystem covered the folders they lie in (-1: by path).
struct Entered {
  int folder = -1, program = -1;
};

// Covers `hide` in a private mount namespace (root only, before the uid drop), makes a probe's
// folder a bounded filesystem of its own and every folder in `private_tmp` a private one. It
// fails closed: where the namespace or a mount fails, the child reports it and exits instead of
// running with our folders visible or its writes unbounded.
static Entered privateFilesystems(const ExecArgs& exec, const ExecLimits& how) {
  Entered entered;
  if (!how.new_mount_namespace) return entered;
  if (unshare(CLONE_NEWNS) != 0) setupFailed(kSetupMount);
  if (mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) setupFailed(kSetupMount);
  if (!how.folder_options.empty()) {
    if (mount("tmpfs", exec.dir.c_str(), "tmpfs", MS_NOSUID | MS_NODEV,
              how.folder_options.c_str()) != 0)
      setupFailed(kSetupMount);
    entered.folder = open(exec.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    entered.program = open(exec.argv[0], O_PATH | O_CLOEXEC);
    if (entered.folder < 0 || entered.program < 0) setupFailed(kSetupMount);
  }
  for (const std::string& folder : how.hide)
    if (mount("tmpfs", folder.c_str(), "tmpfs", MS_RDONLY | MS_NOSUID | MS_NODEV | MS_NOEXEC,
              "size=4k,mode=0555") != 0)
      setupFailed(kSetupMount);
  for (const std::string& folder : how.private_tmp)
    if (mount("tmpfs", folder.c_str(), "tmpfs", MS_NOSUID | MS_NODEV,
              how.private_tmp_options.c_str()) != 0)
      setupFailed(kSetupMount);
  return entered;
}

// `.sanitizer-report.<pid>` -> /proc/self/fd/<kSanitizerReportFd> in the current folder (no
// allocation: the name is built in place).
static void linkSanitizerChannel() {
  static_assert(kSanitizerReportFd >= 0 && kSanitizerReportFd < 10);
  char target[] = "/proc/self/fd/N", name[64];
  target[sizeof target - 2] = static_cast<char>('0' + kSanitizerReportFd);
  std::size_t at = 0;
  for (const char* c = kSanitizerReportName; *c && at < 40; ++c) name[at++] = *c;
  name[at++] = '.';
  char digits[24];
  int n = 0;
  for (long v = getpid(); v > 0 && n < 23; v /= 10) digits[n++] = static_cast<char>('0' + v % 10);
  while (n > 0) name[at++] = digits[--n];
  name[at] = '\0';
  (void)!symlink(target, name);
}

// Moves every descriptor the child keeps into its place: first all of them above the layout
// (so putting one in place never overwrites another), then each to its number, and every other
// descriptor closed. The setup pipe stays close-on-exec: a successful exec closes it unwritten.
static void placeDescriptors(const ChildFds& fds) {
  constexpr int kHigh = 100;
  const int from[] = {fds.in, fds.out, fds.err, fds.answer, fds.info, fds.setup, fds.report};
  const int target[] = {0, 1, 2, probe::kResultFd, kInfoFd, kSetupFd, kSanitizerReportFd};
  int high[7];
  for (int k = 0; k < 7; ++k) high[k] = from[k] >= 0 ? fcntl(from[k], F_DUPFD_CLOEXEC, kHigh) : -1;
  if (high[3] < 0)  // no answer expected: /dev/null in its place
    high[3] = fcntl(open("/dev/null", O_RDONLY | O_CLOEXEC), F_DUPFD_CLOEXEC, kHigh);
  for (int k = 0; k < 7; ++k)
    if (high[k] >= 0)
      dup3(high[k], target[k], k == 5 ? O_CLOEXEC : 0);
    else if (k >= 3)
      close(target[k]);  // no descriptor of the grader's leaks into the program
  if (syscall(SYS_close_range, kSanitizerReportFd + 1, ~0u, 0) != 0)
    for (int fd = kSanitizerReportFd + 1; fd < 1024 + kHigh; ++fd) close(fd);
}

[[noreturn]] void execChild(const ExecArgs& exec, const ChildFds& fds, const ExecLimits& how) {
  setpgid(0, 0);
  placeDescriptors(fds);
  if (how.injected_fault) setupFailed(kSetupInjected);
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
    setLimit(RLIMIT_NOFILE, kToolOpenFiles);
    if (how.uid >= 0) setLimit(RLIMIT_NPROC, kToolProcesses);
  }
  setLimit(RLIMIT_CORE, 0);
  const Entered entered = privateFilesystems(exec, how);
  if (entered.folder >= 0 ? fchdir(entered.folder) != 0 : chdir(exec.dir.c_str()) != 0)
    setupFailed(kSetupChdir);
  if (entered.folder >= 0) close(entered.folder);
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
  // Its parent gone (the grader killed, or the fallback's supervisor), the program goes too; set
  // after the uid drop, which clears it.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (how.sanitizer_link) linkSanitizerChannel();
  // The same addresses on every run (kept through bubblewrap's exec, which is not set-uid): what
  // undefined behaviour reads then depends on the run's variant only (ChildLimits::variant).
  if (how.limits && how.limits->fixed_layout) personality(ADDR_NO_RANDOMIZE);
  if (entered.program >= 0)
    syscall(SYS_execveat, entered.program, "", exec.argv.data(), exec.envp.data(), AT_EMPTY_PATH);
  else
    execve(exec.argv[0], exec.argv.data(), exec.envp.data());
  if (errno == ENOENT && entered.program < 0)
    execvpe(exec.argv[0], exec.argv.data(), exec.envp.data());
  // The uid's process slots are taken (another run's fork bomb): the caller retries.
  setupFailed(errno == EAGAIN ? kSetupNoSlot : kSetupExec);
}

// A status the supervisor passes on as its exit code, the way bubblewrap does: a child killed by
// signal S becomes 128 + S.
[[noreturn]] static void exitLike(int status) {
  if (WIFSIGNALED(status)) _exit(128 + WTERMSIG(status));
  _exit(WIFEXITED(status) ? WEXITSTATUS(status) : 1);
}

// The exit code of a supervisor that lost its student program (waitpid failed).
constexpr int kSupervisorForkFailed = 124;

static volatile pid_t supervised_student = 0;

// The grader's SIGTERM at a wall timeout: the student program dies, then the supervisor cleans up.
static void stopStudent(int) {
  const pid_t student = supervised_student;
  if (student > 1) {
    kill(-student, SIGKILL);
    kill(student, SIGKILL);
  }
}

// Subreaper mode: kills every child the supervisor has (the student's orphans were reparented to
// it) until none is left; children of a killed child become ours in turn. Async-signal-safe.
static void killInherited() {
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
[[noreturn]] void superviseChild(const ExecArgs& exec, const ChildFds& fds, const ExecLimits& how,
                                 bool in_namespace) {
  setpgid(0, 0);
  struct sigaction action {};
  action.sa_handler = stopStudent;
  sigaction(SIGTERM, &action, nullptr);
  // The grader gone (killed), the supervisor is told as at a wall timeout (SIGTERM): it kills the
  // student and, as a subreaper, everything reparented to it, before it exits; in a pid namespace
  // its exit ends the rest. A SIGKILL would leave a subreaper's orphans to init.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (!in_namespace) prctl(PR_SET_CHILD_SUBREAPER, 1);
  // A raw clone, not glibc's fork(): in a child of a threaded grader, fork() would wait for the
  // malloc and stdio locks that other threads held when we were cloned, forever.
  const pid_t student = static_cast<pid_t>(syscall(SYS_clone, SIGCHLD, 0, 0, 0, 0));
  if (student < 0) setupFailed(kSetupClone, fds.setup);
  if (student == 0) {
    signal(SIGTERM, SIG_DFL);
    ChildFds student_fds = fds;
    student_fds.info = -1;
    execChild(exec, student_fds, how);
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

void readAvailable(int fd, std::string& into) {
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;)
    into.append(buffer, static_cast<std::size_t>(n));
}

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

}  // namespace clothref::grader::spawn
