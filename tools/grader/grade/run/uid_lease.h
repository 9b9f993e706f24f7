// The uids student code runs as, one pair per grade, leased host-wide (docs/grading-reference.md,
// "Layers").
#pragma once
#include <filesystem>
#include <memory>
#include <vector>

namespace clothref::grader {

// The first pair of uids a grade runs student code as (when the grader is root): probes, and
// compiles and links (not the probes' uid, so no student process can write into a scratch folder
// or replace a probe executable). Inside Debian's reserved uids 65000-65533, and not `nobody`
// (65534), which system services share.
inline constexpr int kProbeUid = 65533;
inline constexpr int kToolUid = 65532;

// The uids of one grade. Two probes under one uid could write into each other's folders, signal
// each other or open each other's /proc/<pid>/mem, so each grade holds its own pair until `hold`
// is released: slot k is (kProbeUid - 2k, kToolUid - 2k). The lease is host-wide, not per
// process: a slot is an exclusive flock on `<lock_dir>/slot-<k>.lock` (default
// /run/clothref-grader, a folder only root may enter), so any number of grader processes on one
// machine (Slurm tasks, TAs, CI jobs) never run two students under one uid at a time. The lock
// dies with the process that holds it. A slot whose uids run processes under another root is
// taken by a grader there (a chroot shares /proc and the uids, not /run) and is skipped; a
// process still running under the uids in our root (left by a grader that was killed) is killed.
// One that does not die (stuck in the kernel) is reported in one line on stderr and its slot
// skipped until it ends. `kill_rounds` are killProcessesOf's passes (0 in tests: a leftover that
// does not die). The lowest free slot is taken; kUidSlots at once at the most on a host (more
// throws).
struct UidLease {
  int uid = kProbeUid, tool_uid = kToolUid;
  std::shared_ptr<const void> hold;
};
inline constexpr int kUidSlots = 256;
UidLease leaseUids(const std::filesystem::path& lock_dir = "/run/clothref-grader",
                   int kill_rounds = 50);

// Kills (SIGKILL) every process under our root whose real or effective uid is one of `uids`,
// until none is left (at most `rounds` passes over /proc). Returns how many were killed.
int killProcessesOf(const std::vector<int>& uids, int rounds = 50);

// Whether a process under another root folder (a chroot's grader) runs as one of `uids`.
bool usedUnderAnotherRoot(const std::vector<int>& uids);

}  // namespace clothref::grader
