// What one grade's student code can reach of another's (issue 30, defects 2 and 3): two `clothref
// grade` processes side by side in the fallback, and two submissions of one batch, each with a
// spy in ExplicitEuler::integrate that looks for the other's probes in /proc (their memory,
// their folders), for the other's sources and results, and for the grader's command line. Every
// spy must run under a uid of its own, find the other and get nothing from it, and the grades
// must be full marks. The spies write what they tried to their stderr, which --keep-work keeps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;
const fs::path kBase = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "submissions" / "2022" /
                       "reference" / "src";

// Runs once per probe process (the explicit probe calls integrate every step), for about two
// seconds, so that two graders started together overlap. @NAME@ is this submission's name,
// @OTHER@ the other's; @OTHER_FILES@ a file of the other's submission, @OTHER_RESULTS@ a results
// file of the other's grade.
const char* kSpy = R"spy(
  static bool spied = false;
  if (!spied) {
    spied = true;
    std::fprintf(stderr, "SPY-UID %d\n", static_cast<int>(getuid()));
    const auto got = [](const char *what, const std::string &where) {
      std::fprintf(stderr, "SPY-%s %s\n", what, where.c_str());
      std::abort();
    };
    // read(2), not std::ifstream: libstdc++'s filebuf throws when a read fails (a process that
    // ends between open and read: ESRCH), and the spy then aborted for nothing it reached.
    const auto slurp = [](const std::string &path) {
      std::string text;
      const int fd = open(path.c_str(), O_RDONLY);
      if (fd < 0) return text;
      char buffer[4096];
      for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;)
        text.append(buffer, static_cast<std::size_t>(n));
      close(fd);
      return text;
    };
    const std::string other_mark = std::string("SPY-OF-") + "@OTHER_NAME@";
    for (int round = 0; round < 40; ++round) {
      DIR *proc = opendir("/proc");
      for (dirent *entry; proc && (entry = readdir(proc));) {
        const std::string pid = entry->d_name;
        if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
        const std::string status = slurp("/proc/" + pid + "/status");
        const std::size_t uid_at = status.find("\nUid:");
        const int uid = uid_at == std::string::npos ? -1 : std::atoi(status.c_str() + uid_at + 5);
        const std::string cmdline = slurp("/proc/" + pid + "/cmdline");
        if (cmdline.find("@OTHER@") != std::string::npos) got("SAW-OTHER-PATH", pid);
        if (uid < 0 || uid == static_cast<int>(getuid()) || uid == 0) continue;
        if (cmdline.find("probe") == std::string::npos) continue;
        static bool said = false;  // once: the report keeps only a run's first lines of stderr
        if (!said) std::fprintf(stderr, "SPY-FOUND %d\n", uid);
        said = true;
        if (open(("/proc/" + pid + "/mem").c_str(), O_RDWR) >= 0) got("GOT-MEM", pid);
        if (open(("/proc/" + pid + "/cwd/spy-was-here").c_str(), O_WRONLY | O_CREAT, 0644) >= 0)
          got("WROTE", pid);
      }
      if (proc) closedir(proc);
      for (const char *path : {"@OTHER_FILES@", "@OTHER_RESULTS@"})
        if (std::FILE *file = std::fopen(path, "rb")) got("READ", path);
      DIR *tmp = opendir("/tmp");
      for (dirent *entry; tmp && (entry = readdir(tmp));) {
        const std::string name = entry->d_name;
        if (name.rfind("clothref-grade-", 0) != 0) continue;
        if (slurp("/tmp/" + name + "/build/src-integrator/integrator.cpp").find(other_mark) !=
            std::string::npos)
          got("READ-SOURCE", name);
      }
      if (tmp) closedir(tmp);
      usleep(50000);
    }
  }
)spy";

// The submissions' folder names, unique to this test process: a spy aborts on any command line
// naming the other submission, and the suite runs these tests side by side (ctest -j), so with
// shared names one test's grader, before it blanks its arguments, could stop another's spy.
const std::string kAlice = "alice-subm-" + std::to_string(getpid());
const std::string kBobby = "bobby-subm-" + std::to_string(getpid());

// SPY-OF-<name> marks each spy's own source, so reading the other's is visible.
std::string spySubmission(const fs::path& dir, const std::string& name, const std::string& other,
                          const std::string& other_files, const std::string& other_results) {
  fs::create_directories(dir / "src");
  for (const char* file : {"cloth.cpp", "sphere.cpp"})
    fs::copy_file(kBase / file, dir / "src" / file);
  std::string text = readText(kBase / "integrator.cpp");
  std::string spy = kSpy;
  const auto fill = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = 0; (at = spy.find(from, at)) != std::string::npos; at += to.size())
      spy.replace(at, from.size(), to);
  };
  fill("@OTHER_FILES@", other_files);
  fill("@OTHER_RESULTS@", other_results);
  fill("@OTHER_NAME@", other.substr(0, other.find('-')));
  fill("@OTHER@", other);
  const std::string includes =
      "#include \"configs.h\"\n\n#include <dirent.h>\n#include <fcntl.h>\n#include <unistd.h>\n\n"
      "#include <cstdio>\n#include <cstdlib>\n#include <cstring>\n#include <fstream>\n"
      "#include <string>\n\n// SPY-OF-" +
      name + "\n";
  const std::string body =
      "  for (const auto &p : particles) {\n    p->position() += p->velocity()";
  const std::size_t include_at = text.find("#include \"configs.h\"\n");
  const std::size_t body_at = text.find(body);
  EXPECT_NE(include_at, std::string::npos);
  EXPECT_NE(body_at, std::string::npos);
  if (include_at == std::string::npos || body_at == std::string::npos) return "";
  text.insert(body_at, spy);
  text.replace(include_at, std::string("#include \"configs.h\"\n").size(), includes);
  writeText(dir / "src" / "integrator.cpp", text);
  return (dir / "src" / "integrator.cpp").string();
}

struct SpyReport {
  std::set<int> uids;            // the uids the spy ran as (one per probe process)
  std::vector<std::string> got;  // what it got: every line but SPY-UID and SPY-FOUND
  bool found_other = false;
  std::string stderr_text;  // every run's stderr, under its folder's name (printed on a failure)
};

SpyReport spyReport(const fs::path& keep) {
  SpyReport report;
  // Every run of the explicit probe (integrate-0 is the first; a second run, a retry or the
  // sanitizer run keep theirs beside it), so a spy that got something in any of them is seen.
  std::string text;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(keep / "probes", error))
    if (entry.path().filename().string().rfind("integrate-0", 0) == 0 &&
        fs::exists(entry.path() / "child.stderr")) {
      const std::string run = readText(entry.path() / "child.stderr");
      text += run;
      report.stderr_text += entry.path().filename().string() + ":\n" + run;
    }
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("SPY-UID ", 0) == 0)
      report.uids.insert(std::stoi(line.substr(8)));
    else if (line.rfind("SPY-FOUND ", 0) == 0)
      report.found_other = true;
    else if (line.rfind("SPY-", 0) == 0)
      report.got.push_back(line);
  }
  return report;
}

// On a failure, why: each test of a results.json that did not pass, its name and output (a spy
// that got something aborts, and the output then quotes its stderr's first lines).
std::string failedTests(const fs::path& results) {
  const nlohmann::json json = nlohmann::json::parse(readText(results), nullptr, false);
  std::string failed;
  if (json.is_object() && json.contains("tests") && json["tests"].is_array())
    for (const auto& t : json["tests"])
      if (t.value("status", "") != "passed")
        failed += t.value("name", "?") + ": " + t.value("output", "").substr(0, 2000) + "\n";
  return failed;
}

// Runs clothref without a shell (a shell's command line would name the submissions).
CommandResult gradeDirect(const std::vector<std::string>& args, const fs::path& scratch) {
  fs::create_directories(scratch);
  const ProcessResult run = runCliDirect(args, scratch);
  return {run.exit_code, run.stdout_text + run.stderr_text};
}

// Two graders on one host at once (two Slurm tasks, two TAs): distinct uids, and neither probe
// can open the other's memory, write into its folder or read its sources or results (a spy that
// gets anything aborts, and its grade is no longer full marks).
TEST(Confinement, TwoGradersSideBySideInTheFallbackRunAsDistinctUidsAndReachNothing) {
  if (geteuid() != 0) GTEST_SKIP() << "the fallback's uids need a grader running as root";
  TempDir temp;
  const fs::path a = temp.path() / kAlice, b = temp.path() / kBobby;
  const fs::path a_results = temp.path() / "alice-out" / "results.json";
  const fs::path b_results = temp.path() / "bobby-out" / "results.json";
  fs::create_directories(a_results.parent_path());
  fs::create_directories(b_results.parent_path());
  // Two graders know nothing of each other's submission folders (what a TA leaves readable is
  // the TA's to close): the spies go for what the graders hold, the probes and scratch folders.
  spySubmission(a, "alice", kBobby, "/nonexistent", "/nonexistent");
  spySubmission(b, "bobby", kAlice, "/nonexistent", "/nonexistent");
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  const auto grade = [&](const fs::path& dir, const fs::path& results, const fs::path& keep,
                         CommandResult& out) {
    out = gradeDirect(
        {"grade", dir.string(), "--no-whole-run", "--timeout", "20", "--results", results.string(),
         "--keep-work", keep.string(), "--cache-dir", CLOTHREF_GRADER_CACHE},
        keep.string() + "-run");
  };
  CommandResult a_run, b_run;
  std::thread first(grade, a, a_results, temp.path() / "alice-keep", std::ref(a_run));
  std::thread second(grade, b, b_results, temp.path() / "bobby-keep", std::ref(b_run));
  first.join();
  second.join();
  ASSERT_EQ(a_run.exit_code, 0) << a_run.output;
  ASSERT_EQ(b_run.exit_code, 0) << b_run.output;
  const SpyReport alice = spyReport(temp.path() / "alice-keep");
  const SpyReport bobby = spyReport(temp.path() / "bobby-keep");
  // On a failure, why: the failed tests and every run of each spy, with its whole stderr.
  for (const auto& [results, spy] : {std::pair{a_results, &alice}, std::pair{b_results, &bobby}}) {
    const nlohmann::json json = nlohmann::json::parse(readText(results));
    EXPECT_DOUBLE_EQ(json["score"].get<double>(), 80.0)
        << results << "\n"
        << failedTests(results) << "the spy's runs:\n"
        << spy->stderr_text;
  }
  ASSERT_EQ(alice.uids.size(), 1u);
  ASSERT_EQ(bobby.uids.size(), 1u);
  EXPECT_NE(*alice.uids.begin(), *bobby.uids.begin());
  std::cout << "[ info     ] the two graders ran their students as uids " << *alice.uids.begin()
            << " and " << *bobby.uids.begin()
            << "; each saw the other's probes: " << (alice.found_other ? "yes" : "no") << ", "
            << (bobby.found_other ? "yes" : "no") << "\n";
  RecordProperty("uids",
                 std::to_string(*alice.uids.begin()) + " " + std::to_string(*bobby.uids.begin()));
  // the spies ran at the same time (each looks for two seconds): else the test proves nothing
  EXPECT_TRUE(alice.found_other || bobby.found_other);
  EXPECT_TRUE(alice.got.empty()) << (alice.got.empty() ? "" : alice.got.front());
  EXPECT_TRUE(bobby.got.empty()) << (bobby.got.empty() ? "" : bobby.got.front());
}

// One batch, two submissions at once: neither probe reads the other's sources (scratch or
// submission folder), its results in the batch folder, or the grader's command line.
TEST(Confinement, TwoSubmissionsOfABatchReachNothingOfEachOther) {
  if (geteuid() != 0) GTEST_SKIP() << "the fallback's uids need a grader running as root";
  // In /srv, as ASingleGradeReachesNoNeighbour: under /tmp the probes' private /tmp hid the other
  // submission and the batch folder whatever the batch covered.
  const fs::path base = "/srv";
  if (!fs::is_directory(base) || access(base.c_str(), W_OK) != 0)
    GTEST_SKIP() << base << " is not a folder this test may make its own folder in";
  TempDir temp(base);
  const fs::path subs = temp.path() / "subs", out = temp.path() / "batch";
  const fs::path a = subs / kAlice, b = subs / kBobby;
  spySubmission(a, "alice", kBobby, (b / "src" / "cloth.cpp").string(),
                (out / kBobby / "report.md").string());
  spySubmission(b, "bobby", kAlice, (a / "src" / "cloth.cpp").string(),
                (out / kAlice / "report.md").string());
  fs::permissions(temp.path(), fs::perms::owner_all | fs::perms::others_exec |
                                   fs::perms::group_exec | fs::perms::others_read);
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  const CommandResult run = gradeDirect({"grade", a.string(), b.string(), "--out", out.string(),
                                         "--jobs", "2", "--no-whole-run", "--timeout", "20"},
                                        temp.path() / "run");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string csv = readText(out / "grades.csv");
  // The folders are readable on purpose: the batch must cover them. Where no private mount
  // namespace can be made (a chroot) it refuses them instead, which is the rule, not this test's.
  const std::string problem = readText(out / kAlice / "row.json");
  if (problem.find("allows no private mount namespace") != std::string::npos)
    GTEST_SKIP() << "no private mount namespace here: the batch refuses readable folders";
  // On a failure, why: each failed test's output, which quotes how its probe's runs ended and the
  // first lines of the spy's stderr (what it got, or why else it aborted).
  const auto why = [&](const std::string& name) {
    const std::string failed = failedTests(out / name / "results.json");
    return name + ":\n" + (failed.empty() ? "(no failed test)\n" : failed);
  };
  EXPECT_NE(csv.find(kAlice + ",2022,15,20,10,10,5,2.5,2.5,15,80,80,graded"), std::string::npos)
      << csv << why(kAlice);
  EXPECT_NE(csv.find(kBobby + ",2022,15,20,10,10,5,2.5,2.5,15,80,80,graded"), std::string::npos)
      << csv << why(kBobby);
}

// A single grade covers its neighbours as a batch does (issue 36): `clothref grade subs/alice`
// beside subs/bobby (a TA's usual layout, folders readable): alice's probe cannot read bobby's
// files. Before, in the fallback, it read them (alice's results quoted a line of bobby's code).
TEST(Confinement, ASingleGradeReachesNoNeighbour) {
  if (geteuid() != 0) GTEST_SKIP() << "the fallback's uids need a grader running as root";
  // In /srv, as a TA's folder of hand-ins lies outside every folder the grader hides anyway: a
  // probe gets a private /tmp (and /var/tmp, /dev/shm), and the checkout with the build is ours,
  // so under either this test passed with the cover taken out.
  const fs::path base = "/srv";
  if (!fs::is_directory(base) || access(base.c_str(), W_OK) != 0)
    GTEST_SKIP() << base << " is not a folder this test may make its own folder in";
  TempDir temp(base);
  // Every folder above must let other uids through, or the probe could not reach the
  // neighbour anyway and the test would prove nothing.
  for (fs::path up = base; !up.empty(); up = up.parent_path()) {
    if ((fs::status(up).permissions() & fs::perms::others_exec) == fs::perms::none)
      GTEST_SKIP() << up << " is closed to other uids: no neighbour is reachable to test";
    if (up == up.root_path()) break;
  }
  const fs::path subs = temp.path() / "subs";
  const fs::path a = subs / kAlice, b = subs / kBobby;
  spySubmission(a, "alice", kBobby, (b / "src" / "cloth.cpp").string(), "/nonexistent");
  spySubmission(b, "bobby", kAlice, (a / "src" / "cloth.cpp").string(), "/nonexistent");
  fs::permissions(temp.path(), fs::perms::owner_all | fs::perms::others_exec |
                                   fs::perms::group_exec | fs::perms::others_read);
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  const fs::path results = temp.path() / "alice-results.json";
  const CommandResult run =
      gradeDirect({"grade", a.string(), "--no-whole-run", "--timeout", "20", "--results",
                   results.string(), "--cache-dir", CLOTHREF_GRADER_CACHE},
                  temp.path() / "run");
  if (run.exit_code == 2 &&
      run.output.find("allows no private mount namespace") != std::string::npos)
    GTEST_SKIP() << "no private mount namespace here: the grade refuses readable neighbours";
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string text = readText(results);
  EXPECT_EQ(text.find("SPY-READ"), std::string::npos) << text.substr(0, 3000);
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(text)["score"].get<double>(), 80.0);
}

}  // namespace
}  // namespace clothref::test
