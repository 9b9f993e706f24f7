#include "grader/grade/run/sandbox.h"

#include <fcntl.h>
#include <grp.h>
#include <sched.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/submission/neighbours.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

std::string findOnPath(const std::string& name) {
  for (const char* dir : {"/usr/bin", "/bin", "/usr/local/bin", "/usr/sbin"}) {
    const fs::path candidate = fs::path(dir) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

// The host trees every sandbox sees (read-only): the system's programs and libraries. Merged-/usr
// systems have /lib, /bin... as symlinks into /usr: they become the same symlinks in the box.
void addSystemTrees(std::vector<std::string>& argv) {
  argv.insert(argv.end(), {"--ro-bind", "/usr", "/usr"});
  for (const char* top : {"/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"}) {
    std::error_code error;
    const fs::path path(top);
    if (fs::is_symlink(path, error))
      argv.insert(argv.end(), {"--symlink", fs::read_symlink(path, error).string(), top});
    else if (fs::is_directory(path, error))
      argv.insert(argv.end(), {"--ro-bind", top, top});
  }
  argv.insert(argv.end(), {"--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache"});
}

void addHidden(const Isolation& isolation, std::vector<std::string>& argv) {
  for (const fs::path& hidden : isolation.ours) {
    std::error_code error;
    if (isUnder(hidden, "/usr") && fs::is_directory(hidden, error))
      argv.insert(argv.end(), {"--tmpfs", hidden.string()});
  }
}

// Whether this process may make a pid namespace (root, or a kernel that lets users): one clone.
bool canMakePidNamespace() {
  const long pid = syscall(SYS_clone, CLONE_NEWPID | SIGCHLD, 0, 0, 0, 0);
  if (pid == 0) _exit(0);
  if (pid < 0) return false;
  int status = 0;
  waitpid(static_cast<pid_t>(pid), &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// What a forked child finds out: `in_child` runs in the child (which exits right after) and
// returns one byte; nullopt when the child could not be started or died before answering.
std::optional<unsigned char> askChild(const std::function<unsigned char()>& in_child) {
  int channel[2];
  if (pipe(channel) != 0) return std::nullopt;
  const pid_t pid = fork();
  if (pid < 0) {
    close(channel[0]);
    close(channel[1]);
    return std::nullopt;
  }
  if (pid == 0) {
    close(channel[0]);
    const unsigned char answer = in_child();
    (void)!write(channel[1], &answer, 1);
    _exit(0);
  }
  close(channel[1]);
  unsigned char answer = 0;
  const bool answered = read(channel[0], &answer, 1) == 1;
  close(channel[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!answered) return std::nullopt;
  return answer;
}

}  // namespace

std::string whyNoPrivateMountNamespace() {
  // 1: unshare refused (no CAP_SYS_ADMIN), 2: "/" is no mount point (a chroot).
  const auto failed = askChild([]() -> unsigned char {
    if (unshare(CLONE_NEWNS) != 0) return 1;
    if (mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return 2;
    return 0;
  });
  if (!failed) return "the check could not run";
  if (*failed == 1) return "unshare(CLONE_NEWNS) is not allowed";
  if (*failed == 2) return "\"/\" is not a mount point (a chroot?)";
  return "";
}

namespace {

// Our cgroup v2 folder: "<cgroup2 mount><our cgroup>" from /proc/self/mounts and /proc/self/cgroup.
std::string ownCgroupFolder() {
  std::ifstream mounts("/proc/self/mounts");
  std::string device, point, type, rest, mount_point;
  while (mounts >> device >> point >> type && std::getline(mounts, rest))
    if (type == "cgroup2") {
      mount_point = point;
      break;
    }
  if (mount_point.empty()) return {};
  std::ifstream groups("/proc/self/cgroup");
  for (std::string line; std::getline(groups, line);)
    if (line.rfind("0::", 0) == 0) return mount_point + (line.size() > 4 ? line.substr(3) : "");
  return {};
}

// Whether a forked child can move itself into `folder` (the "no internal processes" rule of
// cgroup v2 forbids it where the parent hands controllers down).
bool canJoin(const std::string& folder) {
  const int procs = open((folder + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
  if (procs < 0) return false;
  const pid_t pid = fork();
  if (pid == 0) _exit(write(procs, "0", 1) == 1 ? 0 : 1);
  close(procs);
  if (pid < 0) return false;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

struct CgroupParent {
  std::string path, why;
  CgroupParent() {
    if (geteuid() != 0) {
      why = "not root";
      return;
    }
    const std::string own = ownCgroupFolder();
    if (own.empty()) {
      why = "no cgroup v2 mount";
      return;
    }
    const std::string candidate = own + "/clothref-grader-" + std::to_string(getpid());
    if (mkdir(candidate.c_str(), 0700) != 0 && errno != EEXIST) {
      why = "cannot make a cgroup in " + own + " (" + std::strerror(errno) + ")";
      return;
    }
    const std::string trial = candidate + "/check";
    if (access((candidate + "/cgroup.kill").c_str(), W_OK) != 0)
      why = "no cgroup.kill (Linux < 5.14)";
    else if (mkdir(trial.c_str(), 0700) != 0 || !canJoin(trial))
      why = "a process cannot join a cgroup in " + own;
    rmdir(trial.c_str());
    if (why.empty())
      path = candidate;
    else
      rmdir(candidate.c_str());
  }
  // Empty by then: every run's cgroup is removed when its run ends.
  ~CgroupParent() {
    if (!path.empty()) rmdir(path.c_str());
  }
};

Isolation detect() {
  const char* forced_env = std::getenv("CLOTHREF_GRADER_ISOLATION");
  const std::string forced = forced_env && *forced_env ? forced_env : "auto";
  if (forced != "auto" && forced != "bubblewrap" && forced != "rlimits" && forced != "none")
    throw InputError("CLOTHREF_GRADER_ISOLATION: unknown value '" + forced +
                     "' (expected auto, bubblewrap, rlimits or none)");
  Isolation isolation;
  if (forced == "none") return isolation;  // asked for: student code runs unconfined
  isolation.kind = IsolationKind::Rlimits;
  isolation.uid = geteuid() == 0 ? kProbeUid : -1;
  isolation.tool_uid = geteuid() == 0 ? kToolUid : -1;
  isolation.cgroup_parent = cgroupParent(&isolation.why_no_cgroup);
  isolation.memory_cgroup = memoryCgroupParent(isolation.cgroup_parent, &isolation.memory_cgroup_v1,
                                               &isolation.why_no_memory_cgroup);
  if (isolation.uid >= 0) {
    isolation.why_not_private_mounts = whyNoPrivateMountNamespace();
    isolation.private_mounts = isolation.why_not_private_mounts.empty();
  }
  isolation.containment =
      canMakePidNamespace() ? Containment::PidNamespace : Containment::Subreaper;
  if (forced == "rlimits") {
    isolation.why_not_bubblewrap = "CLOTHREF_GRADER_ISOLATION=rlimits";
    return isolation;
  }
  const std::string bwrap = findOnPath("bwrap");
  if (bwrap.empty()) {
    isolation.why_not_bubblewrap = "bwrap not installed";
  } else {
    // The same uid drop, flags and launch path as a real probe run, with /bin/true as the probe.
    Isolation candidate = isolation;
    candidate.kind = IsolationKind::Bubblewrap;
    candidate.bwrap = bwrap;
    // The trial runs under a leased uid like any run: another grader may be using the first pair.
    UidLease trial;
    if (isolation.uid >= 0) {
      trial = leaseUids();
      candidate.uid = trial.uid;
    }
    ScratchDir scratch("clothref-sandbox-check");
    fs::permissions(scratch.path(),
                    fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
    ChildLimits limits;
    limits.wall_seconds = 10;
    limits.isolation = candidate;
    std::error_code error;
    const fs::path true_program = fs::canonical("/bin/true", error);
    const ChildRun run =
        runChild({true_program.string()}, scratch.path(), "/dev/null", limits, false, 0);
    candidate.uid = isolation.uid;  // each grade leases its own
    if (run.status == ChildStatus::Ok) return candidate;
    std::string reason = run.stderr_head.substr(0, run.stderr_head.find('\n'));
    isolation.why_not_bubblewrap =
        "bwrap fails here: " + (reason.empty() ? run.describe() : reason);
  }
  if (forced == "bubblewrap")
    throw InputError("CLOTHREF_GRADER_ISOLATION=bubblewrap: " + isolation.why_not_bubblewrap);
  // Not root and no bubblewrap: student code would run as the grader's uid and read all it reads.
  if (isolation.uid < 0)
    throw InputError("student code cannot be confined here: not root, and no bubblewrap (" +
                     isolation.why_not_bubblewrap +
                     "); grade as root, or set CLOTHREF_GRADER_ISOLATION=none for code you trust");
  return isolation;
}

}  // namespace

std::string cgroupParent(std::string* why) {
  static const CgroupParent parent;
  if (why) *why = parent.why;
  return parent.path;
}

namespace {

// Our cgroup v1 memory folder: "<memory mount><our memory cgroup>", or "".
std::string ownMemoryCgroupV1() {
  std::ifstream mounts("/proc/self/mounts");
  std::string device, point, type, options, rest, mount_point;
  while (mounts >> device >> point >> type >> options && std::getline(mounts, rest)) {
    if (type != "cgroup") continue;
    std::istringstream list(options);
    for (std::string option; std::getline(list, option, ',');)
      if (option == "memory") mount_point = point;
    if (!mount_point.empty()) break;
  }
  if (mount_point.empty()) return {};
  std::ifstream groups("/proc/self/cgroup");
  for (std::string line; std::getline(groups, line);) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    std::istringstream controllers(line.substr(first + 1, second - first - 1));
    for (std::string controller; std::getline(controllers, controller, ',');)
      if (controller == "memory") {
        const std::string path = line.substr(second + 1);
        return mount_point + (path == "/" ? "" : path);
      }
  }
  return {};
}

bool writeFile(const std::string& path, const std::string& text) {
  const int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  close(fd);
  return ok;
}

struct MemoryParent {
  std::string path, why;
  bool v1 = false, made = false;
  explicit MemoryParent(const std::string& v2_parent) {
    if (geteuid() != 0) {
      why = "not root";
      return;
    }
    // cgroup v2: the memory controller handed down to our folder's children.
    if (!v2_parent.empty() && writeFile(v2_parent + "/cgroup.subtree_control", "+memory")) {
      path = v2_parent;
      return;
    }
    const std::string own = ownMemoryCgroupV1();
    if (own.empty()) {
      why = v2_parent.empty() ? "no cgroup v2 tier and no cgroup v1 memory hierarchy"
                              : "the memory controller is not delegated to us";
      return;
    }
    // A killed grader's folder (its process gone) is removed: its runs' folders are empty.
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(own, error)) {
      const std::string name = entry.path().filename().string(), prefix = "clothref-grader-";
      if (name.rfind(prefix, 0) != 0 || fs::exists("/proc/" + name.substr(prefix.size()), error))
        continue;
      for (const auto& run : fs::directory_iterator(entry.path(), error))
        if (run.is_directory(error)) rmdir(run.path().c_str());
      rmdir(entry.path().c_str());
    }
    const std::string candidate = own + "/clothref-grader-" + std::to_string(getpid());
    if (mkdir(candidate.c_str(), 0700) != 0 && errno != EEXIST) {
      why = "cannot make a memory cgroup in " + own + " (" + std::strerror(errno) + ")";
      return;
    }
    const std::string trial = candidate + "/check";
    if (mkdir(trial.c_str(), 0700) != 0 ||
        !writeFile(trial + "/memory.limit_in_bytes", std::to_string(64ull << 20)) ||
        !canJoin(trial))
      why = "a process cannot join a memory cgroup in " + own;
    rmdir(trial.c_str());
    if (why.empty()) {
      path = candidate;
      v1 = made = true;
    } else {
      rmdir(candidate.c_str());
    }
  }
  ~MemoryParent() {
    if (made) rmdir(path.c_str());
  }
};

}  // namespace

std::string memoryCgroupParent(const std::string& v2_parent, bool* v1, std::string* why) {
  static const MemoryParent parent(v2_parent);
  if (v1) *v1 = parent.v1;
  if (why) *why = parent.why;
  return parent.path;
}

std::string Isolation::describe() const {
  // A leased pair depends on what else was graded at the time: the line names the scheme, not the
  // number, so a batch's CSV is the same whichever submission got which pair.
  const std::string user = uid < 0     ? "grader's uid (not root)"
                           : uid_lease ? "a uid of its own (" + std::to_string(kProbeUid) + " down)"
                                       : "uid " + std::to_string(uid);
  const std::string tool_user = tool_uid < 0 ? "the grader's uid (not root)"
                                : uid_lease
                                    ? "its own second uid (" + std::to_string(kToolUid) + " down)"
                                    : "uid " + std::to_string(tool_uid);
  switch (kind) {
    case IsolationKind::Bubblewrap:
      return "bubblewrap (new user, net, pid, mount, ipc, uts namespaces; only /usr visible), " +
             user + ", rlimits" + (cgroup_parent.empty() ? "" : ", own cgroup per run") +
             (memory_cgroup.empty() ? "" : ", own memory cgroup per run") + "; compiles as " +
             tool_user + " in bubblewrap";
    case IsolationKind::Rlimits:
      return "rlimits, " + user + ", private working directory, " +
             (cgroup_parent.empty() ? "" : "own cgroup per run (killed when it ends), ") +
             (memory_cgroup.empty() ? "" : "own memory cgroup per run, ") +
             (containment == Containment::PidNamespace
                  ? "own pid namespace per run"
                  : "a subreaper that kills what a run leaves behind") +
             "; compiles as " + tool_user +
             (private_mounts ? std::string("; our folders covered in a private mount namespace")
                             : "; our folders out of reach by their permissions (no private "
                               "mount namespace: " +
                                   why_not_private_mounts + ")") +
             "; no bubblewrap (" + why_not_bubblewrap + ")";
    case IsolationKind::None:
      break;
  }
  return "none (CLOTHREF_GRADER_ISOLATION=none: student code ran as the grader's uid, unconfined)";
}

bool readableAs(int uid, const std::vector<fs::path>& folders, std::string* failed) {
  // The child answers the index of the first folder the uid cannot open, folders.size() when it
  // opens them all (a handful: the course, reference, driver, prebuilt and cache folders), or
  // kNoUid when it cannot become the uid.
  constexpr unsigned char kNoUid = 255;
  if (folders.size() >= kNoUid) throw std::logic_error("readableAs: too many folders");
  const auto first_closed = askChild([&]() -> unsigned char {
    if (setgid(static_cast<gid_t>(uid)) != 0 || setuid(static_cast<uid_t>(uid)) != 0) return kNoUid;
    for (std::size_t k = 0; k < folders.size(); ++k) {
      const int fd = open(folders[k].c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd < 0) return static_cast<unsigned char>(k);
      close(fd);
    }
    return static_cast<unsigned char>(folders.size());
  });
  const bool ok = first_closed && *first_closed == folders.size();
  if (!ok && failed)
    *failed = first_closed && *first_closed < folders.size() ? folders[*first_closed].string()
                                                             : "(could not try)";
  return ok;
}

std::string firstReachableAs(int uid, const std::vector<fs::path>& paths) {
  // The child answers the index of the first path the uid reaches, paths.size() when none, or
  // kNoUid when it cannot become the uid.
  constexpr unsigned char kNoUid = 255;
  if (paths.size() >= kNoUid) throw std::logic_error("firstReachableAs: too many paths");
  const auto first = askChild([&]() -> unsigned char {
    if (setgroups(0, nullptr) != 0 || setgid(static_cast<gid_t>(uid)) != 0 ||
        setuid(static_cast<uid_t>(uid)) != 0)
      return kNoUid;
    for (std::size_t k = 0; k < paths.size(); ++k) {
      struct stat info {};
      if (stat(paths[k].c_str(), &info) != 0) continue;
      if (access(paths[k].c_str(), S_ISDIR(info.st_mode) ? X_OK : R_OK) == 0)
        return static_cast<unsigned char>(k);
    }
    return static_cast<unsigned char>(paths.size());
  });
  if (!first || *first == kNoUid) throw std::runtime_error("cannot try uid " + std::to_string(uid));
  return *first < paths.size() ? paths[*first].string() : std::string();
}

Isolation detectIsolation() {
  // Once per grader process: every submission of a batch gets the same isolation.
  static std::mutex mutex;
  static std::optional<Isolation> cached;
  std::lock_guard<std::mutex> lock(mutex);
  if (!cached) cached = detect();
  return *cached;
}

std::vector<std::string> bubblewrapArgv(const Isolation& isolation,
                                        const std::vector<std::string>& command, int status_fd,
                                        bool sanitizer_channel) {
  std::vector<std::string> argv = {isolation.bwrap, "--unshare-all", "--die-with-parent",
                                   "--new-session", "--cap-drop",    "ALL"};
  addSystemTrees(argv);
  // Every place the program may write is a bounded filesystem of its own: a burst of writes
  // meets its limit at write time (ENOSPC), whatever a poll would have seen.
  const std::string tmp_bytes = std::to_string(kPrivateTmpBytes);
  argv.insert(argv.end(), {"--proc", "/proc", "--dev", "/dev", "--size", tmp_bytes, "--tmpfs",
                           "/dev/shm", "--size", tmp_bytes, "--tmpfs", "/tmp"});
  addHidden(isolation, argv);
  const std::string program = "/sandbox/bin/" + fs::path(command.front()).filename().string();
  argv.insert(argv.end(), {"--ro-bind", command.front(), program, "--size",
                           std::to_string(kRunFolderBytes), "--tmpfs", "/sandbox/work"});
  if (sanitizer_channel)
    argv.insert(argv.end(), {"--symlink", "/proc/self/fd/" + std::to_string(kSanitizerReportFd),
                             "/sandbox/work/" + std::string(kSanitizerReportName) + ".2"});
  // The sandbox's root and /dev (tmpfs bubblewrap made, writable by the program's uid) read-only.
  argv.insert(argv.end(),
              {"--chdir", "/sandbox/work", "--remount-ro", "/dev", "--remount-ro", "/"});
  if (status_fd >= 0) argv.insert(argv.end(), {"--json-status-fd", std::to_string(status_fd)});
  argv.push_back("--");
  argv.push_back(program);
  argv.insert(argv.end(), command.begin() + 1, command.end());
  return argv;
}

std::vector<std::string> bubblewrapToolArgv(const Isolation& isolation,
                                            const std::vector<std::string>& command,
                                            const fs::path& work_dir, int status_fd) {
  std::vector<std::string> argv = {isolation.bwrap, "--unshare-all", "--die-with-parent",
                                   "--new-session", "--cap-drop",    "ALL"};
  addSystemTrees(argv);
  argv.insert(argv.end(), {"--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp"});
  addHidden(isolation, argv);
  argv.insert(argv.end(), {"--bind", work_dir.string(), work_dir.string()});
  // A compiler installed outside /usr (CLOTHREF_GRADER_CXX=/opt/gcc-13/bin/g++): its whole prefix.
  const fs::path program(command.front());
  if (program.is_absolute() && !isUnder(program, "/usr")) {
    const std::string prefix = program.parent_path().parent_path().string();
    argv.insert(argv.end(), {"--ro-bind", prefix, prefix});
  }
  std::vector<std::string> outputs;
  for (std::size_t k = 1; k < command.size(); ++k) {
    std::string arg = command[k];
    if (arg.rfind("-I", 0) == 0) arg = arg.substr(2);
    const fs::path path(arg);
    // Paths under /usr are bound again too: they may lie under a hidden (tmpfs) folder.
    if (!path.is_absolute() || isUnder(path, work_dir)) continue;
    std::error_code error;
    // A file's whole folder: gcc looks for a precompiled header next to the `-include` file.
    if (fs::is_directory(path, error))
      argv.insert(argv.end(), {"--ro-bind", arg, arg});
    else if (fs::exists(path, error))
      argv.insert(argv.end(),
                  {"--ro-bind", path.parent_path().string(), path.parent_path().string()});
    else if (fs::is_directory(path.parent_path(), error))
      outputs.push_back(path.parent_path().string());
  }
  for (const std::string& dir : outputs) argv.insert(argv.end(), {"--bind", dir, dir});
  if (status_fd >= 0) argv.insert(argv.end(), {"--json-status-fd", std::to_string(status_fd)});
  argv.insert(argv.end(), {"--chdir", work_dir.string(), "--"});
  argv.insert(argv.end(), command.begin(), command.end());
  return argv;
}

BubblewrapInfo parseBubblewrapInfo(const std::string& json) {
  BubblewrapInfo info;
  std::smatch match;
  static const std::regex pid(R"re("child-pid"\s*:\s*(\d+))re");
  static const std::regex ns(R"re("pid-namespace"\s*:\s*(\d+))re");
  if (std::regex_search(json, match, pid)) info.child_pid = std::stol(match[1]);
  if (std::regex_search(json, match, ns)) info.pid_namespace = std::stoull(match[1]);
  return info;
}

}  // namespace clothref::grader
