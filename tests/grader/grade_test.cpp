// The corpus (tests/grader/submissions): every student-style submission scores 100 %, and every
// mutant loses points in exactly the stubs its expected.json names, with the expected diagnoses
// in the feedback of a failed test of those stubs. One test per submission, graded by the CLI
// (`clothref grade --results`), so ctest -j runs them in parallel.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "corpus.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/grade.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/probes/util.h"
#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;
const fs::path kCorpus = corpusDir();
const char* kFiles[] = {"cloth.cpp", "sphere.cpp", "integrator.cpp"};

std::vector<std::string> corpusCases() {
  std::vector<std::string> cases;
  for (const char* edition : {"2022", "2024"}) {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(kCorpus / edition, error))
      if (fs::exists(entry.path() / "expected.json"))
        cases.push_back(std::string(edition) + "/" + entry.path().filename().string());
  }
  std::sort(cases.begin(), cases.end());
  return cases;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A mutant with a "base" holds only its changed files: the submission is the base overlaid.
fs::path materialise(const fs::path& case_dir, const nlohmann::json& expected,
                     const fs::path& scratch) {
  if (!expected.contains("base")) return case_dir;
  const fs::path base = kCorpus / expected["base"].get<std::string>();
  const fs::path target = scratch / "submission" / "src";
  fs::create_directories(target);
  for (const char* name : kFiles) {
    fs::path own = corpusFile(case_dir, name);
    fs::copy_file(own.empty() ? corpusFile(base, name) : own, target / name);
  }
  return target.parent_path();
}

class Corpus : public ::testing::TestWithParam<std::string> {};
// Until the corpus is merged the folder may be empty: that is not a failure of this file.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Corpus);

TEST_P(Corpus, LosesPointsExactlyInTheExpectedStubsWithTheExpectedDiagnoses) {
  TempDir temp;
  const fs::path case_dir = kCorpus / GetParam();
  const nlohmann::json expected = readJson(case_dir / "expected.json");
  const fs::path submission = materialise(case_dir, expected, temp.path());
  std::string args = "grade '" + submission.string() + "' --no-whole-run --cache-dir '" +
                     std::string(CLOTHREF_GRADER_CACHE) + "' --results '" +
                     temp.file("results.json") + "'";
  if (expected.value("force_edition", false))
    args += " --edition " + expected["edition"].get<std::string>();
  const CommandResult run = runCli(args);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json results = readJson(temp.file("results.json"));
  EXPECT_EQ(results["extra_data"]["edition"].get<int>(),
            std::stoi(expected["edition"].get<std::string>()));

  std::set<std::string> losing, expected_losing;
  for (const auto& [stub, max] : results["extra_data"]["stub_max"].items())
    if (results["extra_data"]["stub_scores"][stub].get<double>() < max.get<double>() - 1e-9)
      losing.insert(stub);
  for (const auto& stub : expected["stubs_losing_points"])
    expected_losing.insert(stub.get<std::string>());
  EXPECT_EQ(losing, expected_losing) << results.dump(1).substr(0, 4000);

  std::set<std::string> shown;  // diagnosis ids on failed tests of the losing stubs
  for (const auto& test : results["tests"]) {
    const std::string name = test["name"];
    EXPECT_EQ(name.rfind(test["tags"][0].get<std::string>() + ": ", 0), 0u) << name;
    if (test["status"] == "failed" && expected_losing.count(test["tags"][0].get<std::string>()))
      for (std::size_t k = 1; k < test["tags"].size(); ++k)
        shown.insert(test["tags"][k].get<std::string>());
  }
  for (const auto& id : expected["diagnoses"])
    EXPECT_TRUE(shown.count(id.get<std::string>())) << "diagnosis " << id << " not shown";
  if (expected["kind"] == "correct") {
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), 80.0);
    // The tests the probes made are their check tables' rows, in order: the tests a stub gets
    // when its file does not compile (plannedTests) are the same names.
    std::vector<std::string> made, planned;
    for (const auto& test : results["tests"]) made.push_back(test["name"].get<std::string>());
    for (const grader::PlannedTest& p :
         grader::plannedTests(results["extra_data"]["edition"].get<int>()))
      planned.push_back(p.stub + ": " + p.check);
    EXPECT_EQ(made, planned);
  }
  if (expected.contains("compile_errors")) {
    for (const auto& file : expected["compile_errors"])
      for (const auto& used : results["extra_data"]["files"])
        if (used["name"] == file) {
          EXPECT_FALSE(used["compiled"].get<bool>()) << file;
        }
  }
}

INSTANTIATE_TEST_SUITE_P(Submissions, Corpus, ::testing::ValuesIn(corpusCases()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// A probe group that grades `stub` by running `run`.
grader::ProbeGroup groupOf(
    const std::string& stub,
    std::function<std::vector<grader::TestResult>(const grader::ProbeContext&)> run) {
  grader::ProbeGroup group;
  group.stub = stub;
  group.run = std::move(run);
  return group;
}

// A group that runs long (a loop until its time limit) holds one worker, never the groups behind
// it: here the first group waits for the last to run, which a pool that waits for its oldest job
// before starting the next never lets happen (the wait would end on its 20 s bound, unreleased).
TEST(ProbeGroups, ALongGroupDoesNotHoldBackTheGroupsBehindIt) {
  std::mutex mutex;
  std::condition_variable changed;
  bool last_ran = false;
  std::vector<grader::ProbeGroup> groups;
  groups.push_back(groupOf("first", [&](const grader::ProbeContext&) {
    std::unique_lock<std::mutex> lock(mutex);
    const bool released =
        changed.wait_for(lock, std::chrono::seconds(20), [&] { return last_ran; });
    return std::vector<grader::TestResult>{
        grader::makeTest("first", released ? "released" : "held", 1)};
  }));
  for (const char* name : {"second", "third", "skipped", "last"})
    groups.push_back(groupOf(name, [&, name](const grader::ProbeContext&) {
      if (std::string(name) == "last") {
        std::lock_guard<std::mutex> lock(mutex);
        last_ran = true;
        changed.notify_all();
      }
      return std::vector<grader::TestResult>{grader::makeTest(name, "ran", 1)};
    }));
  const auto results =
      grader::runProbeGroups(groups, grader::ProbeContext{}, {{"skipped", "no file"}}, 2);
  ASSERT_EQ(results.size(), groups.size());
  ASSERT_EQ(results[0].size(), 1u);
  EXPECT_EQ(results[0][0].check, "released");
  EXPECT_TRUE(results[3].empty());  // unavailable: not run
  for (std::size_t g : {1u, 2u, 4u}) {
    ASSERT_EQ(results[g].size(), 1u) << g;
    EXPECT_EQ(results[g][0].stub, groups[g].stub);
  }
}

// The information-only groups (the whole run: stub "") start only once every scored group has
// ended (issue 39: the whole run's crash is explained with the sanitizer's rebuilds of the scored
// groups' crashes, which must all be there, whatever the workers' timing): here the whole run,
// second in the table, would start at once on the free worker while the first group still runs.
TEST(ProbeGroups, TheWholeRunStartsAfterEveryScoredGroupEnded) {
  std::atomic<int> scored_ended{0};
  std::vector<grader::ProbeGroup> groups;
  const auto scored = [&](const grader::ProbeContext&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ++scored_ended;
    return std::vector<grader::TestResult>{};
  };
  groups.push_back(groupOf("first", scored));
  groups.push_back(groupOf("", [&](const grader::ProbeContext&) {
    return std::vector<grader::TestResult>{
        grader::makeTest("", "scored groups ended: " + std::to_string(scored_ended.load()), 1)};
  }));
  groups.push_back(groupOf("third", scored));
  const auto results = grader::runProbeGroups(groups, grader::ProbeContext{}, {}, 2);
  ASSERT_EQ(results.size(), groups.size());
  ASSERT_EQ(results[1].size(), 1u);
  EXPECT_EQ(results[1][0].check, "scored groups ended: 2");
}

// An exception a group throws reaches the caller once every group has ended.
TEST(ProbeGroups, AnExceptionReachesTheCallerAfterEveryGroupEnded) {
  std::atomic<int> ran{0};
  std::vector<grader::ProbeGroup> groups;
  groups.push_back(
      groupOf("throws", [&](const grader::ProbeContext&) -> std::vector<grader::TestResult> {
        ++ran;
        throw std::runtime_error("no fork");
      }));
  for (int k = 0; k < 3; ++k)
    groups.push_back(groupOf("fine", [&](const grader::ProbeContext&) {
      ++ran;
      return std::vector<grader::TestResult>{};
    }));
  EXPECT_THROW(grader::runProbeGroups(groups, grader::ProbeContext{}, {}, 2), std::runtime_error);
  EXPECT_EQ(ran.load(), 4);
}

// The whole-run check is information only, and the reference reproduces clothref bit for bit.
TEST(WholeRun, ReferenceIsIdenticalToClothrefAndNeverScored) {
  TempDir temp;
  const fs::path submission = kCorpus / "2022" / "reference";
  const CommandResult run = runCli(
      "grade '" + submission.string() + "' --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) +
      "' --results '" + temp.file("results.json") + "' --junit '" + temp.file("junit.xml") +
      "' --report '" + temp.file("report.md") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json results = readJson(temp.file("results.json"));
  bool found = false;
  for (const auto& test : results["tests"])
    if (test["name"].get<std::string>().find("whole run") != std::string::npos) {
      found = true;
      EXPECT_EQ(test["max_score"].get<double>(), 0.0);
      EXPECT_NE(test["output"].get<std::string>().find("identical"), std::string::npos)
          << test["output"];
    }
  EXPECT_TRUE(found);
  EXPECT_TRUE(fs::file_size(temp.file("junit.xml")) > 0);
  EXPECT_TRUE(fs::file_size(temp.file("report.md")) > 0);
}

// Load never costs a student points (issue 39): the course's reference, graded by two graders at
// once while four busy loops keep every core of the machine busy (each probe waits for a CPU much
// of its time), keeps full marks, at the default limits.
TEST(Load, TheReferenceKeepsFullMarksBesideTwoGradersAndFourBusyLoops) {
  TempDir temp;
  std::vector<pid_t> loops;
  for (int k = 0; k < 4; ++k) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const rlimit cpu{300, 300};  // ends by itself should the test die first
      setrlimit(RLIMIT_CPU, &cpu);
      volatile unsigned long spin = 0;
      for (;;) spin = spin + 1;
    }
    loops.push_back(pid);
  }
  const fs::path submission = kCorpus / "2024" / "reference";
  CommandResult runs[2];
  const auto grade = [&](int k) {
    runs[k] = runCli("grade '" + submission.string() + "' --no-whole-run --cache-dir '" +
                     std::string(CLOTHREF_GRADER_CACHE) + "' --results '" +
                     temp.file("results-" + std::to_string(k) + ".json") + "'");
  };
  std::thread first(grade, 0), second(grade, 1);
  first.join();
  second.join();
  // the loops were still running: the graders shared the machine with them to the end
  int still_running = 0;
  for (pid_t pid : loops) {
    still_running += waitpid(pid, nullptr, WNOHANG) == 0;
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  EXPECT_EQ(still_running, 4);
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(runs[k].exit_code, 0) << runs[k].output;
    const nlohmann::json results = readJson(temp.file("results-" + std::to_string(k) + ".json"));
    std::string failed;  // on a failure, which checks and why
    for (const auto& t : results["tests"])
      if (t.value("status", "") != "passed")
        failed += t.value("name", "?") + ": " + t.value("output", "").substr(0, 300) + "\n";
    double max = 0;  // the edition's code points (80)
    for (const auto& [stub, points] : results["extra_data"]["stub_max"].items())
      max += points.get<double>();
    EXPECT_GT(max, 0.0);
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), max) << "grader " << k << "\n" << failed;
  }
}

// Exit 0 whatever the score; non-zero only when nothing can be graded.
TEST(Exit, NoStudentFileIsBadInput) {
  TempDir temp;
  fs::create_directories(temp.path() / "empty");
  const CommandResult run = runCli("grade '" + (temp.path() / "empty").string() + "' --results '" +
                                   temp.file("results.json") + "'");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("none of cloth.cpp"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(temp.file("results.json")));
}

// ---- The realistic corpus (tests/grader/corpus): submissions combining several mistakes, with
// hand labels per stub; scored as a whole in corpus_test.cpp, used here one at a time.

const fs::path kRealCorpus = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "corpus";

// Results of grading `submission` with extra CLI arguments (`--no-whole-run`, cached objects).
nlohmann::json gradeResults(const fs::path& submission, const TempDir& temp,
                            const std::string& extra = "") {
  const CommandResult run = runCli("grade '" + submission.string() + "' --no-whole-run " + extra +
                                   " --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) +
                                   "' --results '" + temp.file("results.json") + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return readJson(temp.file("results.json"));
}

// The reference with ExplicitEuler::integrate's body replaced by `body`.
fs::path withExplicitBody(const TempDir& temp, const std::string& body) {
  const fs::path dir = temp.path() / "submission";
  fs::create_directories(dir);
  const fs::path reference = kCorpus / "2022" / "reference";
  for (const char* name : kFiles) fs::copy_file(corpusFile(reference, name), dir / name);
  std::ifstream in(dir / "integrator.cpp");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string head = "void ExplicitEuler::integrate(";
  const std::size_t at = text.find(head);
  const std::size_t open = text.find("{\n", at) + 2;
  const std::size_t close = text.find("\n}\n", open) + 1;
  EXPECT_NE(at, std::string::npos);
  text = text.substr(0, open) + body + text.substr(close);
  std::ofstream(dir / "integrator.cpp") << text;
  return dir;
}

double stubScore(const nlohmann::json& results, const std::string& stub) {
  return results["extra_data"]["stub_scores"][stub].get<double>();
}

// A crash on the small probe cloth is graded again on the course's cloth; a crash there too stays
// a crash, and both are quoted.
TEST(CourseCloth, CrashOnBothClothsStaysACrash) {
  TempDir temp;
  const fs::path submission =
      withExplicitBody(temp,
                       "  for (auto p : particles) {\n"
                       "    p->position() += p->velocity() * deltaTime;\n"
                       "    p->velocity() += p->acceleration() * deltaTime;\n"
                       "  }\n"
                       "  particles[0]->velocity(100000).setZero();\n");
  const nlohmann::json results = gradeResults(submission, temp);
  EXPECT_EQ(stubScore(results, "ExplicitEuler::integrate"), 0.0);
  EXPECT_EQ(results["extra_data"]["verdict"], "crashed");
  bool quoted = false;
  for (const auto& test : results["tests"])
    if (test["tags"][0] == "ExplicitEuler::integrate") {
      const std::string output = test["output"];
      // quoted once per stub: later tests of the stub refer to it (repeats are folded)
      quoted = quoted || (output.find("On the 4 x 4 probe cloth") != std::string::npos &&
                          output.find("On the course's cloth") != std::string::npos);
    }
  EXPECT_TRUE(quoted) << results.dump(1).substr(0, 3000);
}

// Code that only runs on the course's 25 x 25 cloth (corners pinned by index) gets full marks
// there, says why, and the submission's verdict stays `graded`.
TEST(CourseCloth, CourseOnlyCodeIsGradedOnTheCourseCloth) {
  TempDir temp;
  const fs::path submission = withExplicitBody(
      temp,
      "  for (auto p : particles) {\n"
      "    p->position() += p->velocity() * deltaTime;\n"
      "    p->velocity() += p->acceleration() * deltaTime;\n"
      "  }\n"
      "  particles[0]->velocity(particlesPerEdge * particlesPerEdge - 1).setZero();\n");
  const nlohmann::json results =
      gradeResults(submission, temp, "--keep-work '" + temp.file("work") + "'");
  EXPECT_EQ(stubScore(results, "ExplicitEuler::integrate"), 5.0);
  EXPECT_EQ(results["extra_data"]["verdict"], "graded");
  // Every folder a probe ran in, the course-size retry's among them, is one the sanitizer reads
  // (--sanitize quotes a crash from the folder's stderr) and names the stub it grades.
  std::map<std::string, std::string> known;
  for (const auto& [folder, stub] : grader::probeFolders()) known[folder] = stub;
  std::set<std::string> made;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(temp.path() / "work" / "probes", error))
    made.insert(entry.path().filename().string());
  EXPECT_TRUE(made.count(grader::integratorFolder(0, true))) << ::testing::PrintToString(made);
  for (const std::string& folder : made) {
    EXPECT_TRUE(known.count(folder)) << folder << " is not in probeFolders()";
  }
  EXPECT_EQ(known[grader::integratorFolder(0, true)], "ExplicitEuler::integrate");
  // The retry answered: the crash on the probe cloth was never explained, so no sanitizer build
  // was made (issue 39: it was, and its text was thrown away).
  for (const auto& entry : fs::directory_iterator(temp.path() / "work", error))
    EXPECT_NE(entry.path().filename().string().rfind("sanitize", 0), 0u)
        << entry.path() << ": a sanitizer build for a crash the retry replaced";
  for (const auto& test : results["tests"]) {
    if (test["tags"][0] == "ExplicitEuler::integrate") {
      EXPECT_NE(test["output"].get<std::string>().find("graded on the course's cloth"),
                std::string::npos)
          << test["output"];
    }
  }
}

// The symplectic predictor in implicit and midpoint is accepted by default and refused with the
// rubric switch off.
TEST(Variants, SymplecticPredictorIsARubricSwitch) {
  const fs::path submission =
      kRealCorpus / "2022" / "symplectic-both-sqrt2-normal-stage-current";  // midpoint: predictor
  TempDir on, off;
  EXPECT_EQ(stubScore(gradeResults(submission, on), "MidpointEuler::integrate"), 2.5);
  std::ofstream(off.file("rubric.json"))
      << R"({"accepted_variants": {"symplectic-predictor": false}})";
  const nlohmann::json refused =
      gradeResults(submission, off, "--rubric '" + off.file("rubric.json") + "'");
  EXPECT_LT(stubScore(refused, "MidpointEuler::integrate"), 2.5);
  // explicit-as-symplectic is its own switch: still accepted
  EXPECT_EQ(stubScore(refused, "ExplicitEuler::integrate"), 5.0);
}

// A probe the grader could not start (fork failed) is the grader's failure: its tests name
// `grader-error`, never `crashed`, whatever the student printed, and the submission's verdict says
// so before anything the student's code did. Verdicts travel as the enum, never read back from
// words: a probe stopped at the CPU limit (SIGXCPU) is timed-out in its cause too.
TEST(Verdict, AProbeTheGraderCouldNotStartIsAGraderError) {
  using grader::Verdict;
  grader::ChildRun run;
  run.status = grader::ChildStatus::NotStarted;
  run.stderr_head = "timed out\n";  // the student's stderr chooses nothing
  EXPECT_EQ(run.verdict(), Verdict::GraderError);
  EXPECT_EQ((grader::util::ProbeFailure{run.verdict(), run.describe()}.causeId()),
            grader::cause::kGraderError);
  run.status = grader::ChildStatus::Crashed;
  run.signal = SIGSEGV;
  run.stderr_head = "could not be started by the grader\n";
  EXPECT_EQ(run.verdict(), Verdict::Crashed);
  EXPECT_EQ((grader::util::ProbeFailure{run.verdict(), run.describe()}.causeId()),
            grader::cause::kCrashed);
  run.signal = SIGXCPU;
  EXPECT_EQ(run.verdict(), Verdict::TimedOut);
  EXPECT_EQ((grader::util::ProbeFailure{run.verdict(), run.describe()}.causeId()),
            grader::cause::kTimedOut);
  EXPECT_NE(run.describe().find("timed out"), std::string::npos) << run.describe();

  grader::GradeReport report;
  grader::UsedFile broken;
  broken.name = "cloth.cpp";
  broken.status = Verdict::CompileError;
  broken.problem = "error: expected ';'";
  report.files.push_back(broken);
  EXPECT_EQ(grader::submissionVerdict(report, {Verdict::Graded, Verdict::Crashed}),
            Verdict::CompileError);
  EXPECT_EQ(grader::submissionVerdict(report, {Verdict::Crashed, Verdict::GraderError}),
            Verdict::GraderError);
  report.files.clear();
  EXPECT_EQ(grader::submissionVerdict(report, {Verdict::Graded, Verdict::Graded}), Verdict::Graded);
}

// The table of verdicts is the one place their words are written: each word reads back as its
// verdict, in the table's order (the order a submission's verdict is chosen in).
TEST(Verdict, EveryWordReadsBackAsItsVerdict) {
  using grader::Verdict;
  ASSERT_EQ(grader::verdictTable().size(), std::size_t(Verdict::Graded) + 1);
  for (std::size_t k = 0; k < grader::verdictTable().size(); ++k) {
    const grader::VerdictInfo& info = grader::verdictTable()[k];
    EXPECT_EQ(std::size_t(info.verdict), k) << info.id;
    Verdict back = Verdict::Graded;
    EXPECT_TRUE(grader::verdictFromId(info.id, back)) << info.id;
    EXPECT_EQ(back, info.verdict) << info.id;
  }
  Verdict unchanged = Verdict::Crashed;
  EXPECT_FALSE(grader::verdictFromId("aborted", unchanged));
  EXPECT_EQ(unchanged, Verdict::Crashed);
}

}  // namespace
}  // namespace clothref::test
