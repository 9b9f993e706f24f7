#include "grader/grade/run/uid_lease.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

// The lease folder: made by root with mode 0700, and used only when it is a real folder (not a
// link) that root owns and nobody else may write into, so no other user can plant or hold a lock.
int openLockDirectory(const fs::path& dir) {
  if (mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw std::runtime_error("cannot lease a uid: " + dir.string() + ": " + std::strerror(errno));
  const int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error("cannot lease a uid: " + dir.string() + ": " + std::strerror(errno));
  struct stat info {};
  if (fstat(fd, &info) != 0 || info.st_uid != geteuid() || (info.st_mode & 022) != 0) {
    close(fd);
    throw std::runtime_error("cannot lease a uid: " + dir.string() +
                             " is not a folder of ours that only we may write into");
  }
  return fd;
}

// The uids in /proc/<pid>/status ("Uid:\treal\teffective\tsaved\tfs") and its parent ("PPid:");
// no uids for a zombie, which is gone but for its parent's wait.
struct ProcessStatus {
  std::vector<int> uids;
  long parent = 0;
};
ProcessStatus processStatus(const fs::path& status_path) {
  ProcessStatus found;
  std::ifstream status(status_path);
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("State:", 0) == 0 && line.find('Z') != std::string::npos) return {};
    if (line.rfind("PPid:", 0) == 0) found.parent = std::atol(line.c_str() + 5);
    if (line.rfind("Uid:", 0) == 0) {
      std::istringstream fields(line.substr(4));
      for (int uid; fields >> uid;) found.uids.push_back(uid);
    }
  }
  return found;
}

bool anyOf(const std::vector<int>& ids, const std::vector<int>& uids) {
  return std::any_of(ids.begin(), ids.end(),
                     [&](int id) { return std::find(uids.begin(), uids.end(), id) != uids.end(); });
}

// Whether process `pid` sees the same root folder as we do. A grader in a chroot (a Gradescope
// image built in a root, the fresh-machine check) shares /proc and the uids with the host but
// not /run, where the leases are: its processes are another grader's, never leftovers of ours.
bool sharesOurRoot(const fs::path& proc_entry) {
  struct stat theirs {
  }, ours{};
  if (stat((proc_entry / "root").c_str(), &theirs) != 0 || stat("/", &ours) != 0) return false;
  return theirs.st_dev == ours.st_dev && theirs.st_ino == ours.st_ino;
}

// Whether process `pid` is in a user namespace other than ours: one it made itself (a probe's
// `unshare(CLONE_NEWUSER)`), or bubblewrap made for it.
bool inOtherUserNamespace(const fs::path& proc_entry) {
  struct stat theirs {
  }, ours{};
  if (stat((proc_entry / "ns" / "user").c_str(), &theirs) != 0 ||
      stat("/proc/self/ns/user", &ours) != 0)
    return false;
  return theirs.st_ino != ours.st_ino || theirs.st_dev != ours.st_dev;
}

// The first ancestor of `pid` that runs under none of `uids` (0 when the chain breaks): who
// started the processes of those uids it descends from. A grader's probes and compiles descend
// from that grader; a killed grader's leftovers from init (or a subreaper of ours).
long starterOf(long pid, const std::vector<int>& uids) {
  for (int depth = 0; depth < 64 && pid > 0; ++depth) {
    const ProcessStatus status = processStatus("/proc/" + std::to_string(pid) + "/status");
    if (status.uids.empty()) return 0;
    if (!anyOf(status.uids, uids)) return pid;
    pid = status.parent;
  }
  return 0;
}

// Whether the process at `proc_entry` (running under one of `uids`) is ours to kill: under our
// root, or in a user namespace and root of its own that it made from ours, started by nothing
// under another root. A process of another grader in a chroot (no user namespace, or started by
// that grader, under its root) is not: a chroot shares /proc and the uids with the host, not /run,
// where the leases are.
bool oursToKill(const fs::path& proc_entry, long pid, const std::vector<int>& uids) {
  if (sharesOurRoot(proc_entry)) return true;
  if (!inOtherUserNamespace(proc_entry)) return false;
  // Its starter under another root is another grader; init, or a process whose root we may not
  // read (a container's pid 1), started nothing of a grade: the process is an orphan of ours.
  const long starter = starterOf(pid, uids);
  if (starter <= 1) return true;
  const fs::path entry = "/proc/" + std::to_string(starter);
  struct stat root {};
  return stat((entry / "root").c_str(), &root) != 0 || sharesOurRoot(entry);
}

// The processes running under one of `uids`: pid and whether it is ours to kill.
std::vector<std::pair<long, bool>> processesOf(const std::vector<int>& uids) {
  std::vector<std::pair<long, bool>> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const ProcessStatus status = processStatus(entry.path() / "status");
    const long pid = std::stol(name);
    if (!anyOf(status.uids, uids) || pid <= 1 || pid == getpid()) continue;
    found.emplace_back(pid, oursToKill(entry.path(), pid, uids));
  }
  return found;
}

}  // namespace

bool usedUnderAnotherRoot(const std::vector<int>& uids) {
  const auto found = processesOf(uids);
  return std::any_of(found.begin(), found.end(), [](const auto& p) { return !p.second; });
}

int killProcessesOf(const std::vector<int>& uids, int rounds) {
  std::set<long> killed;
  for (int round = 0; round < rounds; ++round) {
    bool found = false;
    for (const auto& [pid, ours] : processesOf(uids)) {
      if (!ours) continue;  // another root's grader: not ours to kill
      found = true;
      if (kill(static_cast<pid_t>(pid), SIGKILL) == 0) killed.insert(pid);
    }
    if (!found) break;
    usleep(10000);
  }
  return static_cast<int>(killed.size());
}

namespace {

// One line on stderr per skipped slot and grader process: a slot we cannot use is the staff's to
// know about, and it is tried again by every later lease.
void sayOnce(int slot, const std::string& why) {
  static std::mutex mutex;
  static std::set<int> said;
  std::lock_guard<std::mutex> lock(mutex);
  if (!said.insert(slot).second) return;
  std::cerr << "clothref: uid slot " << slot << " (uids " << kProbeUid - 2 * slot << " and "
            << kToolUid - 2 * slot << ") skipped: " << why << "\n";
}

}  // namespace

UidLease leaseUids(const fs::path& lock_dir, int kill_rounds) {
  // flock holds between open file descriptions, in this process as in others: one mutex keeps
  // this process's own leases from racing to the same slot's file.
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  const int dir_fd = openLockDirectory(lock_dir);
  for (int slot = 0; slot < kUidSlots; ++slot) {
    const std::string name = "slot-" + std::to_string(slot) + ".lock";
    const int fd = openat(dir_fd, name.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      close(fd);
      continue;
    }
    UidLease lease;
    lease.uid = kProbeUid - 2 * slot;
    lease.tool_uid = kToolUid - 2 * slot;
    // Free here, but a grader under another root (whose leases we cannot see) runs these uids.
    if (usedUnderAnotherRoot({lease.uid, lease.tool_uid})) {
      close(fd);
      sayOnce(slot,
              "in use by a process under another root (another grader's, not ours to "
              "kill); taken again once it ends");
      continue;
    }
    // A grader killed while it graded may have left processes under these uids: they are ours.
    // One that does not die (stuck in the kernel) keeps the slot from us until it ends.
    killProcessesOf({lease.uid, lease.tool_uid}, kill_rounds);
    if (!processesOf({lease.uid, lease.tool_uid}).empty()) {
      close(fd);
      sayOnce(slot,
              "held by a process left behind that could not be killed; taken again once it "
              "ends");
      continue;
    }
    close(dir_fd);
    // Released (the lock closed) when the last holder lets go. A non-null pointer, so that a
    // held lease tests true.
    lease.hold = std::shared_ptr<const void>(new int(fd), [](const void* held) {
      const int* lock_fd = static_cast<const int*>(held);
      close(*lock_fd);
      delete lock_fd;
    });
    return lease;
  }
  close(dir_fd);
  throw std::runtime_error("more than " + std::to_string(kUidSlots) +
                           " submissions graded at once on this machine: no uid left");
}

}  // namespace clothref::grader
