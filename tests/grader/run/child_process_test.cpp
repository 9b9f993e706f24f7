// Child processes: every way a child can fail gets its own verdict, and only a frame on fd 3
// with the request's nonce counts as an answer.
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/tools.h"

#include <gtest/gtest.h>
#include <sched.h>

#include <atomic>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>
#include <utility>

#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

ChildRun runShell(const test::TempDir& temp, const std::string& script, double wall = 5) {
  std::ofstream(temp.file("in"), std::ios::trunc) << "";
  ChildLimits limits;
  limits.wall_seconds = wall;
  return runChild({"/bin/sh", "-c", script}, temp.path(), temp.file("in"), limits, true, 42);
}

TEST(RunChild, Verdicts) {
  test::TempDir temp;
  EXPECT_EQ(runShell(temp, "exit 3").status, ChildStatus::ExitedNonZero);
  EXPECT_EQ(runShell(temp, "kill -SEGV $$").status, ChildStatus::Crashed);
  EXPECT_EQ(runShell(temp, "echo hello; echo oops >&2").status, ChildStatus::NoAnswer);
  const ChildRun slow = runShell(temp, "sleep 30", 0.5);
  EXPECT_EQ(slow.status, ChildStatus::TimedOut);
  EXPECT_LT(slow.seconds, 5);
  EXPECT_EQ(runShell(temp, "echo oops >&2; exit 1").stderr_head, "oops\n");
}

TEST(RunChild, OneWordVerdicts) {
  test::TempDir temp;
  EXPECT_EQ(runShell(temp, "exit 3").verdict(), Verdict::ExitedNonZero);
  EXPECT_EQ(runShell(temp, "kill -SEGV $$").verdict(), Verdict::Crashed);
  EXPECT_EQ(runShell(temp, "kill -XCPU $$").verdict(), Verdict::TimedOut);
  EXPECT_EQ(runShell(temp, "kill -XFSZ $$").verdict(), Verdict::OutputLimit);
  EXPECT_EQ(runShell(temp,
                     "echo \"terminate called after throwing an instance of "
                     "'std::bad_alloc'\" >&2; kill -ABRT $$")
                .verdict(),
            Verdict::MemoryLimit);
  EXPECT_EQ(runShell(temp, "true").verdict(), Verdict::NoAnswer);
  EXPECT_EQ(runShell(temp, "sleep 30", 0.3).verdict(), Verdict::TimedOut);
}

TEST(RunChild, LimitsBite) {
  test::TempDir temp;
  // 64 MiB of output: the file-size limit stops it (SIGXFSZ), the grader's disk is safe.
  const ChildRun flood = runShell(temp, "exec yes flood-flood-flood-flood-flood");
  EXPECT_EQ(flood.verdict(), Verdict::OutputLimit) << flood.describe();
  EXPECT_LE(std::filesystem::file_size(temp.file("child.stdout")), 64u << 20);
  std::ofstream(temp.file("in"), std::ios::trunc) << "";
  ChildLimits limits;
  limits.address_space_bytes = 1ull << 30;
  limits.log = std::make_shared<RunLog>();
  // The address-space limit reaches the child; the log records each run's verdict.
  runChild({"/bin/sh", "-c", "ulimit -v >&2; exit 1"}, temp.path(), temp.file("in"), limits, true,
           42);
  std::string line;
  std::getline(std::ifstream(temp.file("child.stderr")), line);
  EXPECT_EQ(line, "1048576");  // KiB
  ASSERT_EQ(limits.log->verdicts.size(), 1u);
  EXPECT_EQ(limits.log->verdicts[0], Verdict::ExitedNonZero);
}

TEST(RunChild, PrintingAFrameOnStdoutIsNotAnAnswer) {
  test::TempDir temp;
  probe::ProbeMessage fake;
  fake.nonce = 42;
  fake.texts["score"] = "100";
  std::ofstream(temp.file("frame"), std::ios::binary) << probe::encodeMessage(fake);
  EXPECT_EQ(runShell(temp, "cat frame").status, ChildStatus::NoAnswer);
  const ChildRun fd3 = runShell(temp, "cat frame >&3");
  ASSERT_EQ(fd3.status, ChildStatus::Ok);
  EXPECT_EQ(fd3.answer->text("score"), "100");
  fake.nonce = 43;  // a stale or guessed nonce
  std::ofstream(temp.file("frame"), std::ios::binary | std::ios::trunc)
      << probe::encodeMessage(fake);
  EXPECT_EQ(runShell(temp, "cat frame >&3").status, ChildStatus::NoAnswer);
}

// A shell program that marks each of its runs in a folder of `temp` (run-0, run-1, ...; `$n` is
// the run's number) and then runs `body`, run by runProbeTwice with a 3 s wall limit (the quick
// runs finish well within it, even on a loaded machine): the pair's result and how many runs.
std::pair<ChildRun, std::size_t> runMarked(const test::TempDir& temp, const std::string& body) {
  const fs::path marks = temp.path() / "marks", work = temp.path() / "work";
  const fs::path program = temp.path() / "program";
  fs::remove_all(marks);
  fs::create_directories(marks);
  fs::create_directories(work);
  std::ofstream(program, std::ios::trunc)
      << "#!/bin/sh\ncd '" << marks.string() << "'\nn=$(ls | wc -l); touch run-$n\n"
      << body;
  fs::permissions(program, fs::perms::owner_all);
  ChildLimits limits;
  limits.wall_seconds = 3;
  const ChildRun run = runProbeTwice(program, probe::ProbeMessage{}, work, limits);
  std::size_t runs = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(marks)) ++runs;
  return {run, runs};
}

// A run stopped at the wall-clock limit spent its own time there (waiting for a CPU does not
// count), so a second run cannot change the verdict: an endless loop, a sleep, and a second run
// that runs away after a first that finished each cost one limit, and the pair's verdict stands.
TEST(RunProbeTwice, ARunStoppedAtTheWallLimitIsNotRepeated) {
  test::TempDir temp;
  const auto [busy, busy_runs] = runMarked(temp, "while :; do :; done\n");
  EXPECT_EQ(busy.status, ChildStatus::TimedOut) << busy.describe();
  EXPECT_GT(busy.cpu_seconds, 0.3) << "the loop's CPU time was not read";
  EXPECT_GE(busy.waited_seconds, 0) << "the loop's wait for a CPU was not read";
  EXPECT_EQ(busy_runs, 1u);  // one limit, however loaded the machine (was 2 under load)
  EXPECT_EQ(busy.describe(), "timed out after 3 s");  // its own time, not the wall's
  const auto [sleeps, sleeps_runs] = runMarked(temp, "exec sleep 30\n");
  EXPECT_EQ(sleeps.status, ChildStatus::TimedOut);
  EXPECT_LT(sleeps.cpu_seconds, 1);
  EXPECT_EQ(sleeps_runs, 1u);  // a sleep is the program's: not retried (was 2)
  const auto [second, second_runs] = runMarked(temp, "[ \"$n\" = 1 ] && exec sleep 30\nexit 3\n");
  EXPECT_EQ(second.status, ChildStatus::Varies) << second.describe();
  EXPECT_EQ(second_runs, 2u);  // the first, the second (was 3: the second's retry)
}

// Load never costs a student points: time a run waits for a CPU is not counted against its wall
// limit. Here the program needs about 0.25 s of CPU, its limit is 0.5 s, and it runs pinned to
// CPU 0 beside a busy thread pinned there too (it gets at most half of the CPU: at least 0.5 s
// of wall). Before, it was stopped at 0.5 s, `timed-out`, the student's. On a machine so loaded
// that it gets under a sixth of a CPU it is held back to 3 x the limit: then it is ours
// (`grader-error`), never the student's.
TEST(RunChild, TimeWaitingForACpuDoesNotCountAgainstTheLimit) {
  test::TempDir temp;
  std::atomic<bool> stop{false};
  std::thread rival([&] {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(0, &one);
    sched_setaffinity(0, sizeof one, &one);  // this thread only
    while (!stop) {
    }
  });
  const ChildRun run =
      runShell(temp,
               "exec taskset -c 0 python3 -c 'import time\nwhile time.process_time() < 0.25: "
               "pass\nraise SystemExit(3)'",
               0.5);
  stop = true;
  rival.join();
  EXPECT_NE(run.status, ChildStatus::TimedOut) << run.describe();
  if (run.status == ChildStatus::NotStarted) {
    EXPECT_NE(run.grader_problem.find("load held the run back"), std::string::npos)
        << run.grader_problem;
    EXPECT_EQ(run.verdict(), Verdict::GraderError);
    std::cout << "[ info     ] held back to 3 x the limit: " << run.grader_problem << "\n";
  } else {
    EXPECT_EQ(run.status, ChildStatus::ExitedNonZero) << run.describe() << run.stderr_head;
    EXPECT_EQ(run.exit_code, 3);
    std::cout << "[ info     ] finished after " << run.seconds << " s of wall (limit 0.5 s)\n";
  }
}

// Faults of ours, injected (CLOTHREF_GRADER_FAULT, read by the grader process only): each is
// tried once more and then, if it is still there, the grader's error, never the student's. Once:
// the retry grades the reference at full marks. Always: the verdict is grader-error (a probe) or
// no grade at all (a compile), and no student cause, verdict or stderr appears.
struct Fault {
  const char* spec;       // CLOTHREF_GRADER_FAULT
  const char* isolation;  // CLOTHREF_GRADER_ISOLATION
  const char* outcome;    // "80" (graded at full marks), "grader-error", "no grade"
};

void PrintTo(const Fault& fault, std::ostream* out) {
  *out << fault.spec << " (" << fault.isolation << ")";
}

class FaultInjection : public ::testing::TestWithParam<Fault> {};

TEST_P(FaultInjection, OursIsRetriedOnceThenOursNeverTheStudents) {
  const Fault& fault = GetParam();
  if (geteuid() != 0)
    GTEST_SKIP() << "the fallback's expectations are for a grader running as root";
  test::TempDir temp;
  setenv("CLOTHREF_GRADER_ISOLATION", fault.isolation, 1);
  setenv("CLOTHREF_GRADER_FAULT", fault.spec, 1);
  const fs::path reference =
      fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "submissions" / "2022" / "reference";
  const auto run = test::runCli(
      "grade '" + reference.string() + "' --no-whole-run --timeout 10 --results '" +
      temp.file("results.json") + "' --cache-dir '" + (temp.path() / "cache").string() + "'");
  unsetenv("CLOTHREF_GRADER_FAULT");
  const std::string outcome = fault.outcome;
  if (outcome == "no grade") {
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_FALSE(fs::exists(temp.file("results.json")));
    EXPECT_NE(run.output.find("grader: "), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("compile-error"), std::string::npos) << run.output;
    return;
  }
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto results = nlohmann::json::parse(test::readText(temp.file("results.json")));
  const bool boxed =
      results["extra_data"]["isolation"].get<std::string>().rfind("bubblewrap", 0) == 0;
  if (std::string(fault.isolation) == "auto" && !boxed) GTEST_SKIP() << "no bubblewrap here";
  if (outcome == "80") {
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), 80.0) << results.dump(1).substr(0, 2000);
    EXPECT_EQ(results["extra_data"]["verdict"].get<std::string>(), "graded");
    return;
  }
  EXPECT_EQ(results["extra_data"]["verdict"].get<std::string>(), "grader-error");
  for (const auto& t : results["tests"]) {
    if (t["status"] == "passed") continue;
    std::vector<std::string> tags;
    for (const auto& tag : t["tags"]) tags.push_back(tag.get<std::string>());
    ASSERT_EQ(tags.size(), 2u) << t["name"];
    EXPECT_EQ(tags[1], "grader-error") << t["name"];
    const std::string output = t["output"];
    EXPECT_NE(output.find("could not be started by the grader"), std::string::npos) << output;
    for (const char* theirs : {"crashed", "timed out", "exited with code", "```"})
      EXPECT_EQ(output.find(theirs), std::string::npos) << theirs << " in " << output;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Faults, FaultInjection,
    ::testing::Values(Fault{"fork", "rlimits", "80"}, Fault{"fork*0", "rlimits", "grader-error"},
                      Fault{"setup", "rlimits", "80"}, Fault{"setup*0", "rlimits", "grader-error"},
                      Fault{"pipe*0", "rlimits", "grader-error"},
                      Fault{"files*0", "rlimits", "grader-error"},
                      Fault{"setup*0", "auto", "grader-error"}, Fault{"bwrap", "auto", "80"},
                      Fault{"bwrap*0", "auto", "grader-error"}, Fault{"tool-fork", "rlimits", "80"},
                      Fault{"tool-fork*0", "rlimits", "no grade"},
                      Fault{"tool-setup*0", "rlimits", "no grade"},
                      Fault{"tool-setup*0", "auto", "no grade"}),
    [](const auto& info) {
      std::string name = std::string(info.param.spec) + "_" + info.param.isolation;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

}  // namespace
}  // namespace clothref::grader
