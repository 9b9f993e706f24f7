// Starting a child process for untrusted code, the child's side of it (internal to run/): the
// descriptors it gets, its limits, its private mount namespace, its uid, the fallback's
// supervisor, and the one-byte report of a failure of ours before the program starts; the
// grader's side of a sandbox (its pid namespace, its cgroup). Used by child_process.cpp (probes)
// and tools.cpp (compiles and links).
#pragma once
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "grader/bridge/probe_protocol.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/sandbox.h"
#include "grader/grade/run/tools.h"

namespace clothref::grader::spawn {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start);

// The first `max_lines` lines of `path`, at most `max_bytes`.
std::string readHead(const std::filesystem::path& path, std::size_t max_bytes, int max_lines);
std::string signalName(int signal);

// bubblewrap reports the sandbox's pid and, at the end, the program's exit code on this
// descriptor (--json-status-fd; the one after the answer's).
constexpr int kInfoFd = probe::kResultFd + 1;
// Where a child reports why it could not start the program (before exec; close-on-exec, so a
// successful exec closes it unwritten): the grader's failures, told apart from the student's.
constexpr int kSetupFd = kInfoFd + 1;

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
      : strings(command),
        environment{"PATH=/usr/local/bin:/usr/bin:/bin", "LC_ALL=C"},
        dir(where.string()) {
    for (std::string& a : strings) argv.push_back(a.data());
    argv.push_back(nullptr);
    environment.insert(environment.end(), extra.begin(), extra.end());
    for (std::string& e : environment) envp.push_back(e.data());
    envp.push_back(nullptr);
  }
};
enum SetupFailure : unsigned char {
  kSetupChdir = 1,  // its folder
  kSetupMount,      // the private mount namespace or a mount in it
  kSetupUid,        // the uid drop
  kSetupExec,       // the program could not be executed
  kSetupNoSlot,     // no process slot for the uid (another run's fork bomb): retried
  kSetupClone,      // the fallback's supervisor could not start the program
  kSetupInjected    // a fault injected by CLOTHREF_GRADER_FAULT (tests)
};
struct ExecLimits {
  const ChildLimits* limits = nullptr;  // nullptr: tool limits below
  double tool_seconds = 0;
  int uid = -1;
  // A run in the fallback as root: a private mount namespace where `hide` (our folders) is
  // covered by an empty read-only tmpfs and `private_tmp` by an empty writable one of
  // kPrivateTmpBytes each (built before fork: no allocation after it).
  bool new_mount_namespace = false;
  std::vector<std::string> hide, private_tmp;
  std::string private_tmp_options = "size=" + std::to_string(kPrivateTmpBytes) + ",mode=1777";
  // A probe run there: its folder (ExecArgs::dir) becomes a tmpfs mounted with these options
  // (size, mode, owner), entered and the program executed through descriptors opened before
  // `private_tmp` covers the folders they lie in. Empty: the folder as it is.
  std::string folder_options;
  // A sanitizer run: `.sanitizer-report.<pid>` in its folder links to kSanitizerReportFd.
  bool sanitizer_link = false;
  bool injected_fault = false;  // CLOTHREF_GRADER_FAULT: fail before exec, as a setup failure
};
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
// A run's own cgroups: the child joins them first thing after fork. With Isolation::cgroup_parent
// (cgroup v2 with cgroup.kill), when the run ends cgroup.kill ends every process in it, whatever it
// did to detach (setsid, double fork, a new session in another process group); with
// Isolation::memory_cgroup, its processes together hold at most `memory_bytes` (their private
// filesystems included), past which the kernel's OOM killer stops one. The empty folders are
// removed when the run ends.
struct RunCgroup {
  std::string dir, memory_dir;
  int procs_fd = -1, memory_procs_fd = -1;  // cgroup.procs, opened before fork (no allocation)
  bool memory_v1 = false;
  RunCgroup(const std::string& parent, const std::string& memory_parent, bool v1,
            std::uint64_t memory_bytes) {
    static std::atomic<unsigned long> next{0};
    const std::string name = "/run-" + std::to_string(next++);
    if (!parent.empty()) {
      dir = parent + name;
      if (mkdir(dir.c_str(), 0700) != 0)
        dir.clear();
      else
        procs_fd = open((dir + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
    }
    if (memory_parent.empty() || memory_bytes == 0) return;
    const std::string bytes = std::to_string(memory_bytes);
    if (!v1) {  // v2: the same folder as the kill tier, the memory controller delegated to it
      if (memory_parent == parent && !dir.empty() && writeValue(dir + "/memory.max", bytes)) {
        writeValue(dir + "/memory.swap.max", "0");
        memory_dir = dir;
      }
      return;
    }
    memory_v1 = true;
    memory_dir = memory_parent + name;
    if (mkdir(memory_dir.c_str(), 0700) != 0 ||
        !writeValue(memory_dir + "/memory.limit_in_bytes", bytes)) {
      rmdir(memory_dir.c_str());
      memory_dir.clear();
      return;
    }
    writeValue(memory_dir + "/memory.memsw.limit_in_bytes", bytes);  // no swap either, if counted
    memory_procs_fd = open((memory_dir + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
  }
  // Child side, before the uid drop: "0" moves the writing process.
  void join() const {
    if (procs_fd >= 0) (void)!write(procs_fd, "0", 1);
    if (memory_procs_fd >= 0) (void)!write(memory_procs_fd, "0", 1);
  }
  // Whether the memory limit's OOM killer stopped a process of the run (v2 memory.events, v1
  // memory.oom_control: "oom_kill N").
  bool oomKilled() const {
    if (memory_dir.empty()) return false;
    std::ifstream in(memory_dir + (memory_v1 ? "/memory.oom_control" : "/memory.events"));
    std::string key;
    for (unsigned long long count = 0; in >> key >> count;)
      if (key == "oom_kill") return count > 0;
    return false;
  }
  ~RunCgroup() {
    if (procs_fd >= 0) close(procs_fd);
    if (memory_procs_fd >= 0) close(memory_procs_fd);
    if (!dir.empty()) {
      const int kill_fd = open((dir + "/cgroup.kill").c_str(), O_WRONLY | O_CLOEXEC);
      if (kill_fd >= 0) {
        (void)!write(kill_fd, "1", 1);
        close(kill_fd);
      }
    }
    // rmdir succeeds once the last process has been reaped by its parent (up to 2 s).
    for (const std::string& folder : {dir, memory_v1 ? memory_dir : std::string()})
      for (int k = 0; !folder.empty() && k < 200 && rmdir(folder.c_str()) != 0 && errno == EBUSY;
           ++k)
        usleep(10000);
  }
  static bool writeValue(const std::string& path, const std::string& value) {
    const int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return false;
    const bool ok = write(fd, value.data(), value.size()) == static_cast<ssize_t>(value.size());
    close(fd);
    return ok;
  }
};

// The text of a SetupFailure code (the byte read from the setup pipe).
const char* setupFailureText(unsigned char why);

// Whether the test hook CLOTHREF_GRADER_FAULT asks for a fault of ours at `point` now.
bool injectFault(const char* point);

// The descriptors a child gets, as the parent holds them (-1: none): its stdin, stdout and
// stderr, the answer pipe (fd 3), bubblewrap's status (kInfoFd), the setup pipe (kSetupFd) and
// the sanitizers' channel (kSanitizerReportFd).
struct ChildFds {
  int in = -1, out = -1, err = -1, answer = -1, info = -1, setup = -1, report = -1;
};

// The child's side, after fork: never return.
[[noreturn]] void execChild(const ExecArgs& exec, const ChildFds& fds, const ExecLimits& how);
[[noreturn]] void superviseChild(const ExecArgs& exec, const ChildFds& fds, const ExecLimits& how,
                                 bool in_namespace);

// SIGKILL to the process group `pid` leads and to `pid` (never for a pid <= 1).
void killGroup(pid_t pid);
// A wall timeout in the fallback: SIGTERM to the supervisor, SIGKILL after 2 s; true when it
// exited (and was reaped into `status`).
bool stopSupervisor(pid_t pid, int& status);
// Appends what can be read from the non-blocking `fd` now.
void readAvailable(int fd, std::string& into);

// The setup pipe's report: 0 when the program started (the pipe closed unwritten at exec).
unsigned char setupReport(int fd);
// bubblewrap's --json-status-fd: the program's exit code, none when bubblewrap itself failed.
std::optional<int> bubblewrapExitCode(const std::string& json);
long fileSize(const std::filesystem::path& path);

}  // namespace clothref::grader::spawn
