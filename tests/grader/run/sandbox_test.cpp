// The sandbox: the bubblewrap command line shows the student only /usr, its program and its own
// folder; a child in the fallback runs as the probe uid with a process limit in a private folder;
// in bubblewrap it has no network, its own pid namespace, and a timeout leaves nothing alive.
#include "grader/grade/run/sandbox.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "clothref/io/error.h"
#include "grader/grade/run/child_process.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

bool contains(const std::vector<std::string>& argv, const std::vector<std::string>& run) {
  return std::search(argv.begin(), argv.end(), run.begin(), run.end()) != argv.end();
}

TEST(BubblewrapArgv, ShowsOnlyUsrTheProgramAndItsFolder) {
  Isolation isolation;
  isolation.kind = IsolationKind::Bubblewrap;
  isolation.bwrap = "/usr/bin/bwrap";
  isolation.ours = {"/usr/share/clothref", "/work/clothref"};
  const auto argv = bubblewrapArgv(isolation, {"/tmp/x/probe", "--flag"}, 4);
  EXPECT_EQ(argv.front(), "/usr/bin/bwrap");
  EXPECT_TRUE(contains(argv, {"--unshare-all"}));
  EXPECT_TRUE(contains(argv, {"--die-with-parent"}));
  EXPECT_TRUE(contains(argv, {"--ro-bind", "/usr", "/usr"}));
  EXPECT_FALSE(contains(argv, {"--ro-bind", "/", "/"}));  // an allow-list, not the whole disk
  EXPECT_TRUE(contains(argv, {"--ro-bind", "/tmp/x/probe", "/sandbox/bin/probe"}));
  // its folder, /tmp and /dev/shm are bounded filesystems of its own; / and /dev read-only; no
  // folder of the host is writable
  EXPECT_TRUE(
      contains(argv, {"--size", std::to_string(kRunFolderBytes), "--tmpfs", "/sandbox/work"}));
  EXPECT_TRUE(contains(argv, {"--size", std::to_string(kPrivateTmpBytes), "--tmpfs", "/dev/shm"}));
  EXPECT_TRUE(contains(argv, {"--remount-ro", "/dev", "--remount-ro", "/"}));
  EXPECT_FALSE(contains(argv, {"--bind"}));
  EXPECT_FALSE(contains(argv, {"--symlink", "/proc/self/fd/6"}));
  // the sanitizer run's channel: a link the sanitizers open as their log (the program is pid 2)
  EXPECT_TRUE(contains(bubblewrapArgv(isolation, {"/tmp/x/probe"}, 4, true),
                       {"--symlink", "/proc/self/fd/6", "/sandbox/work/.sanitizer-report.2"}));
  EXPECT_TRUE(contains(argv, {"--tmpfs", "/usr/share/clothref"}) ||
              !fs::is_directory("/usr/share/clothref"));
  EXPECT_FALSE(contains(argv, {"--tmpfs", "/work/clothref"}));  // not visible anyway
  EXPECT_TRUE(contains(argv, {"--json-status-fd", "4"}));
  // its /tmp is its own, and bounded
  EXPECT_TRUE(contains(argv, {"--size", std::to_string(kPrivateTmpBytes), "--tmpfs", "/tmp"}));
  EXPECT_TRUE(contains(argv, {"--", "/sandbox/bin/probe", "--flag"}));
  EXPECT_EQ(argv.back(), "--flag");
}

TEST(BubblewrapToolArgv, BindsTheNamedPathsAndTheWorkDirOnly) {
  test::TempDir temp;
  fs::create_directories(temp.path() / "include");
  test::writeText(temp.file("source.cpp"), "int x;\n");
  Isolation isolation;
  isolation.kind = IsolationKind::Bubblewrap;
  isolation.bwrap = "bwrap";
  const fs::path work = temp.path() / "work";
  fs::create_directories(work);
  const auto argv = bubblewrapToolArgv(isolation,
                                       {"g++", "-I" + temp.file("include"), "-c",
                                        temp.file("source.cpp"), "-o", (work / "a.o").string()},
                                       work);
  EXPECT_TRUE(contains(argv, {"--bind", work.string(), work.string()}));
  EXPECT_TRUE(contains(argv, {"--ro-bind", temp.file("include"), temp.file("include")}));
  // A file's folder (a precompiled header sits next to its header).
  EXPECT_TRUE(contains(argv, {"--ro-bind", temp.path().string(), temp.path().string()}));
  EXPECT_FALSE(contains(argv, {"--ro-bind", "/", "/"}));
  EXPECT_EQ(argv.back(), (work / "a.o").string());
}

TEST(BubblewrapInfo, ReadsThePidAndNamespace) {
  const auto info = parseBubblewrapInfo(
      "{\n    \"child-pid\": 23401,\n    \"cgroup-namespace\": 4026532182,\n"
      "    \"pid-namespace\": 4026532181\n}\n");
  EXPECT_EQ(info.child_pid, 23401);
  EXPECT_EQ(info.pid_namespace, 4026532181ull);
  EXPECT_EQ(parseBubblewrapInfo("garbage").child_pid, 0);
}

TEST(Isolation, DescriptionsSayWhatRan) {
  Isolation isolation;
  isolation.kind = IsolationKind::Rlimits;
  isolation.uid = kProbeUid;
  isolation.tool_uid = kToolUid;
  isolation.why_not_bubblewrap = "bwrap not installed";
  isolation.containment = Containment::PidNamespace;
  isolation.private_mounts = true;
  EXPECT_EQ(isolation.describe(),
            "rlimits, uid 65533, private working directory, own pid namespace per run; compiles "
            "as uid 65532; our folders covered in a private mount namespace; no bubblewrap (bwrap "
            "not installed)");
  // Where no private mount namespace can be made (a chroot, a container), the line says so.
  isolation.private_mounts = false;
  isolation.why_not_private_mounts = "unshare(CLONE_NEWNS) is not allowed";
  EXPECT_NE(isolation.describe().find("; compiles as uid 65532; our folders out of reach by their "
                                      "permissions (no private mount namespace: "
                                      "unshare(CLONE_NEWNS) is not allowed);"),
            std::string::npos)
      << isolation.describe();
  isolation.containment = Containment::Subreaper;
  EXPECT_NE(isolation.describe().find("a subreaper that kills what a run leaves behind"),
            std::string::npos);
  isolation.cgroup_parent = "/sys/fs/cgroup/clothref-grader-1";
  EXPECT_NE(isolation.describe().find(
                "private working directory, own cgroup per run (killed when it ends), a subreaper"),
            std::string::npos)
      << isolation.describe();
  isolation.kind = IsolationKind::Bubblewrap;
  EXPECT_EQ(isolation.describe().rfind("bubblewrap (new user, net, pid, mount", 0), 0u);
  EXPECT_NE(isolation.describe().find("; compiles as uid 65532 in bubblewrap"), std::string::npos)
      << isolation.describe();
  // never a root compile: the line has no such branch any more
  EXPECT_EQ(Isolation{}.describe().rfind("none (CLOTHREF_GRADER_ISOLATION=none", 0), 0u);
}

// Each TEST runs in its own process under ctest, so the cached detection sees this variable.
// Whether the compilers' uid can open the folders a compile needs: a folder only root may enter
// is named; open ones pass. Needs root (to drop to another uid), as the grader's check does.
TEST(ReadableAs, NamesTheFirstFolderTheUidCannotOpen) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to drop to another uid";
  test::TempDir temp;
  const fs::path closed = temp.path() / "closed";
  fs::create_directories(closed);
  fs::permissions(closed, fs::perms::owner_all, fs::perm_options::replace);
  fs::permissions(temp.path(),
                  fs::perms::owner_all | fs::perms::others_exec | fs::perms::group_exec,
                  fs::perm_options::replace);
  std::string failed;
  EXPECT_TRUE(readableAs(65534, {"/", "/usr"}, &failed)) << failed;
  EXPECT_FALSE(readableAs(65534, {"/usr", closed, "/"}, &failed));
  EXPECT_EQ(failed, closed.string());
  EXPECT_FALSE(readableAs(65534, {temp.path() / "missing"}, &failed));
  EXPECT_EQ(failed, (temp.path() / "missing").string());
}

TEST(DetectIsolation, TheVariableForcesTheFallback) {
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  const Isolation isolation = detectIsolation();
  EXPECT_EQ(isolation.kind, IsolationKind::Rlimits);
  EXPECT_EQ(isolation.uid, geteuid() == 0 ? kProbeUid : -1);
  EXPECT_NE(isolation.describe().find("CLOTHREF_GRADER_ISOLATION=rlimits"), std::string::npos);
}

TEST(DetectIsolation, NoneIsOnlyWhatItSays) {
  setenv("CLOTHREF_GRADER_ISOLATION", "none", 1);
  const Isolation isolation = detectIsolation();
  EXPECT_EQ(isolation.kind, IsolationKind::None);
  EXPECT_EQ(isolation.uid, -1);
  EXPECT_NE(isolation.describe().find("unconfined"), std::string::npos);
}

TEST(DetectIsolation, AnUnknownValueIsRefused) {
  setenv("CLOTHREF_GRADER_ISOLATION", "chroot", 1);
  EXPECT_THROW(detectIsolation(), InputError);
}

// A run under a uid leased as a grade leases it (other graders may run beside the test); the uid
// it ran as in `uid_used`.
ChildRun runIsolated(const test::TempDir& temp, IsolationKind kind, const std::string& script,
                     double wall = 5, Containment containment = Containment::None,
                     int* uid_used = nullptr) {
  test::writeText(temp.file("in"), "");
  ChildLimits limits;
  limits.wall_seconds = wall;
  limits.isolation.kind = kind;
  limits.isolation.containment = containment;
  if (kind == IsolationKind::Bubblewrap) {
    setenv("CLOTHREF_GRADER_ISOLATION", "auto", 1);
    limits.isolation = detectIsolation();
  }
  UidLease lease;
  limits.isolation.uid = geteuid() == 0 ? (lease = leaseUids()).uid : -1;
  if (uid_used) *uid_used = limits.isolation.uid;
  // The unprivileged uid must pass through the folder to reach its own.
  fs::permissions(temp.path(), fs::perms::owner_all | fs::perms::others_exec);
  return runChild({"/bin/sh", "-c", script}, temp.path(), temp.file("in"), limits, false, 0);
}

TEST(Fallback, RunsAsNobodyInItsOwnFolderWithAProcessLimit) {
  if (geteuid() != 0) GTEST_SKIP() << "the uid drop needs root";
  test::TempDir temp;
  int uid = 0;
  const ChildRun run =
      runIsolated(temp, IsolationKind::Rlimits,
                  "id -u; pwd; grep 'Max processes' /proc/self/limits | tr -s ' ' | cut -d' ' -f3; "
                  "echo x > ../outside || echo denied",
                  5, Containment::None, &uid);
  ASSERT_EQ(run.status, ChildStatus::Ok) << run.stderr_head;
  EXPECT_LE(uid, kProbeUid);
  EXPECT_EQ(test::readText(temp.path() / "child.stdout"),
            std::to_string(uid) + "\n" + (temp.path() / "sandbox").string() + "\n64\ndenied\n");
  EXPECT_FALSE(fs::exists(temp.path() / "outside"));
}

// Processes whose command line holds `marker`, anywhere on the machine.
int processesWith(const std::string& marker) {
  int alive = 0;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (cmdline.find(marker) != std::string::npos) ++alive;
  }
  return alive;
}

// `sleep MARKER` processes: as argv ("sleep\0MARKER", what `sh -c` execs) or inside a shell's
// command line.
int sleepers(const std::string& marker) {
  return processesWith(std::string("sleep\0", 6) + marker) + processesWith("sleep " + marker);
}

// What the fallback can do here: a pid namespace needs root (or unprivileged user namespaces).
bool canUse(Containment containment) {
  if (containment == Containment::Subreaper) return true;
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  return detectIsolation().containment == Containment::PidNamespace;
}

class FallbackContainment : public ::testing::TestWithParam<Containment> {};

// A detached grandchild (setsid, then a double fork) of a run that ends normally, and of one that
// times out, is gone when runChild returns: nothing of a run outlives it.
TEST_P(FallbackContainment, NoDetachedProcessOutlivesItsRun) {
  if (!canUse(GetParam())) GTEST_SKIP() << "no pid namespace here (needs root)";
  test::TempDir temp;
  const std::string marker = GetParam() == Containment::PidNamespace ? "27.1801" : "27.1802";
  const std::string daemon =
      "setsid sh -c '(sleep " + marker + " &); sleep " + marker + "' >/dev/null 2>&1 &";
  const ChildRun finished =
      runIsolated(temp, IsolationKind::Rlimits, daemon + " echo started", 10, GetParam());
  EXPECT_EQ(finished.status, ChildStatus::Ok) << finished.describe() << finished.stderr_head;
  EXPECT_LT(finished.seconds, 5);  // the detached ones do not hold the run open either
  EXPECT_EQ(sleepers(marker), 0);
  const ChildRun stuck =
      runIsolated(temp, IsolationKind::Rlimits, daemon + " sleep " + marker, 0.5, GetParam());
  EXPECT_EQ(stuck.status, ChildStatus::TimedOut);
  EXPECT_EQ(sleepers(marker), 0);
}

// The student's exit code and signal come through the supervisor unchanged.
TEST_P(FallbackContainment, VerdictsComeThroughTheSupervisor) {
  if (!canUse(GetParam())) GTEST_SKIP() << "no pid namespace here (needs root)";
  test::TempDir temp;
  const ChildRun exited = runIsolated(temp, IsolationKind::Rlimits, "exit 3", 5, GetParam());
  EXPECT_EQ(exited.status, ChildStatus::ExitedNonZero);
  EXPECT_EQ(exited.exit_code, 3);
  const ChildRun crashed =
      runIsolated(temp, IsolationKind::Rlimits, "kill -SEGV $$", 5, GetParam());
  EXPECT_EQ(crashed.status, ChildStatus::Crashed);
  EXPECT_EQ(crashed.signal, SIGSEGV);
}

INSTANTIATE_TEST_SUITE_P(Modes, FallbackContainment,
                         ::testing::Values(Containment::PidNamespace, Containment::Subreaper),
                         [](const auto& info) {
                           return info.param == Containment::PidNamespace ? "PidNamespace"
                                                                          : "Subreaper";
                         });

// The cgroup tier alone (no supervisor, no pid namespace): a detached grandchild is gone when the
// run returns. Without the cgroup the same run leaves it alive (killed here by its pid), so the
// test sees the difference.
TEST(Cgroup, ADetachedProcessDiesWithItsRunsCgroup) {
  std::string why;
  const std::string parent = cgroupParent(&why);
  if (parent.empty()) GTEST_SKIP() << "no cgroup tier here: " << why;
  test::TempDir temp;
  const std::string marker = "29.1803";
  // the run ends only once the detached shell has started its first sleep
  const std::string daemon = "rm -f up; setsid sh -c '(sleep " + marker + " &); touch up; sleep " +
                             marker + "' >/dev/null 2>&1 & while [ ! -e up ]; do sleep 0.05; done";
  test::writeText(temp.file("in"), "");
  fs::permissions(temp.path(), fs::perms::owner_all | fs::perms::others_exec);
  ChildLimits limits;
  limits.wall_seconds = 10;
  limits.isolation.kind = IsolationKind::Rlimits;
  limits.isolation.containment = Containment::None;
  const UidLease lease = leaseUids();
  limits.isolation.uid = lease.uid;
  const ChildRun loose =
      runChild({"/bin/sh", "-c", daemon}, temp.path(), temp.file("in"), limits, false, 0);
  EXPECT_EQ(loose.status, ChildStatus::Ok) << loose.describe();
  int survivors = 0;  // the detached shell starts its sleeps (up to 5 s on a loaded machine)
  for (int k = 0; k < 100 && (survivors = sleepers(marker)) < 2; ++k) usleep(50000);
  // ours to end: every process whose command line holds the marker
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string name = entry.path().filename().string();
    if ((cmdline.find(std::string("sleep\0", 6) + marker) != std::string::npos ||
         cmdline.find("sleep " + marker) != std::string::npos) &&
        name.find_first_not_of("0123456789") == std::string::npos && std::stol(name) > 1)
      kill(static_cast<pid_t>(std::stol(name)), SIGKILL);
  }
  EXPECT_GT(survivors, 0) << "without the cgroup the detached processes should outlive the run";

  limits.isolation.cgroup_parent = parent;
  const ChildRun held =
      runChild({"/bin/sh", "-c", daemon}, temp.path(), temp.file("in"), limits, false, 0);
  EXPECT_EQ(held.status, ChildStatus::Ok) << held.describe();
  EXPECT_EQ(sleepers(marker), 0);
  usleep(300000);  // nothing of the run starts later either
  EXPECT_EQ(sleepers(marker), 0);
  // and the run's cgroup folder is gone
  int left = 0;
  for (const auto& entry : fs::directory_iterator(parent, error)) left += entry.is_directory();
  EXPECT_EQ(left, 0);
}

// A whole grade in each isolation mode: the reference, with a static initialiser in cloth.cpp
// that forks, setsid()s, double-forks and leaves a `sleep` behind in every probe process. The
// grade is full marks (the daemon holds nothing open that the grader waits for) and afterwards no
// process of it is left on the machine.
class GradeIsolation : public ::testing::TestWithParam<std::string> {};

TEST_P(GradeIsolation, ADaemonFromAStaticInitialiserDoesNotOutliveTheGrade) {
  const std::string mode = GetParam();
  setenv("CLOTHREF_GRADER_ISOLATION", mode.c_str(), 1);
  if (mode == "bubblewrap") {
    setenv("CLOTHREF_GRADER_ISOLATION", "auto", 1);
    if (detectIsolation().kind != IsolationKind::Bubblewrap)
      GTEST_SKIP() << "bubblewrap cannot make namespaces here: " << detectIsolation().describe();
  }
  test::TempDir temp;
  const fs::path reference = fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022";
  const fs::path submission = temp.path() / "daemon";
  fs::create_directories(submission);
  for (const char* file : {"sphere.cpp", "integrator.cpp"})
    fs::copy_file(reference / file, submission / file);
  const std::string marker = mode == "bubblewrap" ? "31.0601" : "31.0602";
  test::writeText(submission / "cloth.cpp",
                  test::readText(reference / "cloth.cpp") +
                      "\n#include <unistd.h>\n"
                      "static const int daemon_started = [] {\n"
                      "  if (fork() == 0) {\n"
                      "    setsid();\n"
                      "    if (fork() == 0) {\n"
                      "      if (fork() == 0) execl(\"/bin/sleep\", \"sleep\", \"" +
                      marker +
                      "\", (char*)nullptr);\n"
                      "      _exit(0);\n"
                      "    }\n"
                      "    _exit(0);\n"
                      "  }\n"
                      "  return 0;\n"
                      "}();\n");
  const test::CommandResult run = test::runCli(
      "grade '" + submission.string() + "' --results '" + temp.file("r.json") +
      "' --no-whole-run --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json results = nlohmann::json::parse(test::readText(temp.file("r.json")));
  EXPECT_EQ(results["extra_data"]["verdict"], "graded") << results["output"];
  EXPECT_EQ(results["score"].get<double>(), 80.0) << results["output"];
  EXPECT_EQ(results["extra_data"]["isolation"].get<std::string>().rfind(
                mode == "bubblewrap" ? "bubblewrap" : "rlimits", 0),
            0u);
  EXPECT_EQ(processesWith(std::string("sleep\0", 6) + marker), 0);  // argv: sleep MARKER
}

INSTANTIATE_TEST_SUITE_P(Modes, GradeIsolation, ::testing::Values("rlimits", "bubblewrap"));

TEST(Bubblewrap, NoNetworkOwnPidsAndNothingButUsr) {
  test::TempDir temp;
  setenv("CLOTHREF_GRADER_ISOLATION", "auto", 1);
  if (detectIsolation().kind != IsolationKind::Bubblewrap)
    GTEST_SKIP() << "bubblewrap does not work here: " << detectIsolation().describe();
  int leased = 0;
  const ChildRun run = runIsolated(
      temp, IsolationKind::Bubblewrap,
      "id -u; pwd; echo $$; tail -n +3 /proc/net/dev | cut -d: -f1 | tr -d ' '; test -e " +
          std::string(CLOTHREF_SOURCE_DIR) +
          " || echo no-source; echo x > /usr/x || echo read-only; ls / /etc",
      5, Containment::None, &leased);
  ASSERT_EQ(run.status, ChildStatus::Ok) << run.stderr_head;
  const std::string uid = std::to_string(geteuid() == 0 ? leased : geteuid());
  std::istringstream out(test::readText(temp.path() / "child.stdout"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(out, line);) lines.push_back(line);
  ASSERT_GE(lines.size(), 7u);
  EXPECT_EQ(lines[0], uid);
  EXPECT_EQ(lines[1], "/sandbox/work");
  EXPECT_EQ(lines[2], "2");   // bubblewrap is pid 1 of the new pid namespace, the shell pid 2
  EXPECT_EQ(lines[3], "lo");  // a new network namespace: loopback only
  EXPECT_EQ(lines[4], "no-source");
  EXPECT_EQ(lines[5], "read-only");
  // The root holds only the system trees and the sandbox's own folders; /etc only ld.so.cache.
  const std::set<std::string> allowed = {"/:",    "bin",    "dev",   "etc",        "lib",  "lib32",
                                         "lib64", "libx32", "proc",  "sandbox",    "sbin", "tmp",
                                         "usr",   "",       "/etc:", "ld.so.cache"};
  for (std::size_t k = 6; k < lines.size(); ++k) EXPECT_TRUE(allowed.count(lines[k])) << lines[k];
}

TEST(Bubblewrap, ATimeoutLeavesNoProcessAlive) {
  test::TempDir temp;
  setenv("CLOTHREF_GRADER_ISOLATION", "auto", 1);
  if (detectIsolation().kind != IsolationKind::Bubblewrap)
    GTEST_SKIP() << "bubblewrap does not work here: " << detectIsolation().describe();
  // A detached grandchild in its own session escapes a process-group kill, not the namespace.
  const ChildRun run = runIsolated(temp, IsolationKind::Bubblewrap,
                                   "setsid sh -c 'sleep 31.4159' & sleep 31.4159", 0.5);
  EXPECT_EQ(run.status, ChildStatus::TimedOut);
  int alive = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string cmdline = test::readText(entry.path() / "cmdline");
    if (cmdline.find("31.4159") != std::string::npos) ++alive;
  }
  EXPECT_EQ(alive, 0);
}

}  // namespace
}  // namespace clothref::grader
