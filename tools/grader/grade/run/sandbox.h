// The isolation a student process gets on top of its rlimits: unprivileged uids of its grade's
// own (leased host-wide when the grader runs as root) and, where it works, a bubblewrap sandbox
// (new network, pid, mount, ipc and uts namespaces; only /usr and the probe executable visible,
// read-only; a private writable folder as its working directory). Detected once per grader
// process; the environment variable CLOTHREF_GRADER_ISOLATION (auto | bubblewrap | rlimits |
// none) forces a layer, so tests cover each; `none` (no confinement at all) only when asked.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "grader/grade/run/uid_lease.h"

namespace clothref::grader {

enum class IsolationKind {
  None,     // rlimits only, the grader's uid: for code one trusts (CLOTHREF_GRADER_ISOLATION=none)
  Rlimits,  // rlimits + uid drop (when root) + a private working directory
  Bubblewrap  // all of Rlimits, inside bubblewrap
};

// How the rlimits fallback makes sure no student process outlives its run (bubblewrap has its own
// pid namespace). Every run gets a supervisor of ours between the grader and the student program.
enum class Containment {
  None,          // the student program is the grader's direct child (IsolationKind::None)
  PidNamespace,  // the supervisor is pid 1 of a new pid namespace: when it exits, the kernel
                 // kills every process left in it, detached (setsid, double fork) or not
  Subreaper      // no pid namespace allowed: the supervisor is a child subreaper, so orphans
                 // become its children, and it kills and reaps all of them before it exits
};

struct Isolation {
  IsolationKind kind = IsolationKind::None;
  Containment containment = Containment::None;  // for IsolationKind::Rlimits
  // uid and gid of the probes (kProbeUid - 2k when root, leased per grade); -1 = the grader's
  int uid = -1;
  // uid and gid of compiles and links of student files (kToolUid - 2k when root); -1 = the
  // grader's. Never root: a compile reads only the course kit (folders.h), /usr and its folder.
  int tool_uid = -1;
  // Rlimits as root: whether a private mount namespace can cover `ours` with an empty tmpfs in
  // every run, compiles and probes (not in a chroot, whose root is no mount point, nor in a
  // container without CAP_SYS_ADMIN); the reason if not. Without it, `ours` must be out of the
  // student uids' reach by their permissions, or the grader refuses to grade.
  bool private_mounts = false;
  std::string why_not_private_mounts;
  std::string bwrap;               // bubblewrap executable (Bubblewrap only)
  std::string why_not_bubblewrap;  // why the detection fell back, for the description
  // Our folders (sources, build, install data, reference, cache): no student process may read
  // them. Bubblewrap shows none of them (those under /usr are covered with an empty tmpfs).
  std::vector<std::filesystem::path> ours;
  // Root with a cgroup v2 tree that has cgroup.kill (Linux >= 5.14): a folder of ours in it; each
  // run gets its own cgroup below, and every process in it is killed when the run ends, however
  // it detached itself. Empty: no cgroup tier (`why_no_cgroup` says why).
  std::string cgroup_parent;
  std::string why_no_cgroup;
  // As root where the host lets a process join a memory cgroup of ours (cgroup v2 with the memory
  // controller delegated to `cgroup_parent`, or cgroup v1's memory hierarchy): a folder of ours in
  // it; each run gets its own memory cgroup below, limited to ChildLimits::memory_bytes. Empty:
  // none (`why_no_memory_cgroup` says why), and a run's memory is bounded by RLIMIT_AS alone.
  std::string memory_cgroup;
  bool memory_cgroup_v1 = false;
  std::string why_no_memory_cgroup;
  // As root: holds `uid` and `tool_uid` for this grade alone (leaseUids()) until the last copy of
  // this Isolation is gone.
  std::shared_ptr<const void> uid_lease;
  // Short exact description for GradeReport::isolation, e.g. "bubblewrap (new net, pid, mount,
  // ipc, uts namespaces; only /usr visible), uid 65534, rlimits".
  std::string describe() const;
};

// Whether `uid` (and its gid) can open every folder of `folders` (tried in a forked child that
// drops to it); the first one it cannot open is named in `failed`.
bool readableAs(int uid, const std::vector<std::filesystem::path>& folders, std::string* failed);

// The first of `paths` that `uid` (and its gid) can reach (search a folder, read a file), tried in
// a forked child that drops to it; "" when it reaches none.
std::string firstReachableAs(int uid, const std::vector<std::filesystem::path>& paths);

// Whether this process can make a private mount namespace (unshare(CLONE_NEWNS), then "/" made
// private so no mount leaks to the host), tried once in a forked child; "" if so, else why not.
std::string whyNoPrivateMountNamespace();

// The cgroup tier's folder for this grader process (made once, removed at exit), or "" with the
// reason in `why`: not root, no cgroup v2 mount, no cgroup.kill, or a process cannot join a child
// cgroup there (tried in a forked child).
std::string cgroupParent(std::string* why);

// The memory cgroup folder for this grader process (made once, removed at exit), or "" with the
// reason in `why`; `v1` says whether it is cgroup v1's memory hierarchy (memory.limit_in_bytes)
// rather than v2 (memory.max). `v2_parent` is cgroupParent()'s folder, where v2 delegates the
// memory controller.
std::string memoryCgroupParent(const std::string& v2_parent, bool* v1, std::string* why);

// The isolation for this grader process: probes bubblewrap once (same uid drop and flags as a
// real run, command /bin/true) and caches the answer. Throws InputError for an unknown
// CLOTHREF_GRADER_ISOLATION value or when `bubblewrap` is forced but does not work.
Isolation detectIsolation();

// A run's own folder: a filesystem of this size where one can be mounted (bubblewrap's tmpfs,
// the fallback's private mount namespace), so a burst of writes meets the limit at write time.
inline constexpr std::uint64_t kRunFolderBytes = 32ull << 20;
// Every other place a run may write (its /tmp and /dev/shm, and in the fallback every folder any
// user may write into, /var/tmp and /run/lock among them): a private filesystem of this size each.
inline constexpr std::uint64_t kPrivateTmpBytes = 8ull << 20;
// The descriptor of the sanitizers' own channel in a sanitizer run (child_process.h), and the name
// its link takes in the run's folder: `.sanitizer-report.<pid>` -> /proc/self/fd/<this>, which
// ASAN_OPTIONS and UBSAN_OPTIONS name as log_path (the sanitizers add ".<pid>").
inline constexpr int kSanitizerReportFd = 6;
inline constexpr const char* kSanitizerReportName = ".sanitizer-report";

// The argv that runs `command` (argv[0] an absolute path) inside bubblewrap: the working
// directory /sandbox/work is an empty tmpfs of kRunFolderBytes, /tmp and /dev/shm empty tmpfs of
// kPrivateTmpBytes, and the rest read-only (/, /dev, /usr); argv[0] is bound read-only at
// /sandbox/bin/<name>; with `sanitizer_channel`, /sandbox/work/.sanitizer-report.2 links to the
// channel (the program is pid 2 of the sandbox); `status_fd` is the descriptor bubblewrap reports
// on (--json-status-fd: the sandbox's pid first, the program's exit code when it ends; without
// the exit code, bubblewrap itself failed).
std::vector<std::string> bubblewrapArgv(const Isolation& isolation,
                                        const std::vector<std::string>& command, int status_fd,
                                        bool sanitizer_channel = false);

// The argv that runs a compiler or linker `command` inside bubblewrap with the grader's uid:
// /usr, `work_dir` (read-write) and the absolute paths the command names (read-only; the folder
// of an output that does not exist yet read-write) are all it sees, so `#include "/etc/shadow"`
// or an include of the reference finds nothing.
std::vector<std::string> bubblewrapToolArgv(const Isolation& isolation,
                                            const std::vector<std::string>& command,
                                            const std::filesystem::path& work_dir,
                                            int status_fd = -1);

// The "child-pid" and "pid-namespace" fields of bubblewrap's --info-fd JSON (0 when absent).
struct BubblewrapInfo {
  long child_pid = 0;
  unsigned long long pid_namespace = 0;
};
BubblewrapInfo parseBubblewrapInfo(const std::string& json);

}  // namespace clothref::grader
