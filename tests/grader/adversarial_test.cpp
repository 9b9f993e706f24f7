// The adversarial suite (tests/grader/adversarial): every hostile or broken submission is graded
// (exit 0) with its expected one-word verdict, under bubblewrap and under the rlimits fallback
// (CLOTHREF_GRADER_ISOLATION=rlimits), and its attack fails: no process named by the case is
// alive after the grade, a results file next to ours is untouched and no forged one appears, a
// secret the compiler was asked to include is not quoted, and a submission that tried to read the
// reference still gets full marks and never gets what it read into any output. Whether that read
// succeeds depends on the host (a checkout under mode-700 /root is unreadable to uid 65534; the
// rlimits fallback on a world-readable checkout can read it): the test says which, and asserts the
// same outcome either way.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;
const fs::path kSuite = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "adversarial";
const fs::path kCorpus = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "submissions";
const char* kFiles[] = {"cloth.cpp", "sphere.cpp", "integrator.cpp"};

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}

// Processes whose name is `marker` and that are not zombies (a zombie runs nothing).
int liveProcessesNamed(const std::string& marker) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string stat = readText(entry.path() / "stat");
    const auto open = stat.find('('), close = stat.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close + 2 >= stat.size())
      continue;
    if (stat.substr(open + 1, close - open - 1) == marker && stat[close + 2] != 'Z') ++count;
  }
  return count;
}

// Whether uid 65534 (the uid student code runs as) can open `path` for reading on this host:
// tried in a forked child that drops to it when we are root.
bool readableByNobody(const fs::path& path) {
  const pid_t pid = fork();
  if (pid < 0) return false;
  if (pid == 0) {
    if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(2);
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    _exit(fd >= 0 ? 0 : 1);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

struct Case {
  std::string name;
  std::string isolation;  // "auto" (bubblewrap here) or "rlimits"
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name << " (" << c.isolation << ")"; }

std::vector<Case> suiteCases() {
  std::vector<Case> cases;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(kSuite, error))
    if (fs::exists(entry.path() / "expected.json"))
      for (const char* isolation : {"auto", "rlimits"})
        cases.push_back({entry.path().filename().string(), isolation});
  std::sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) {
    return a.name + a.isolation < b.name + b.isolation;
  });
  return cases;
}

class Adversarial : public ::testing::TestWithParam<Case> {};

TEST_P(Adversarial, GetsItsVerdictAndTheAttackFails) {
  const Case& c = GetParam();
  if (c.isolation == "rlimits" && geteuid() != 0)
    GTEST_SKIP() << "the fallback's expectations are for a grader running as root (uid drop)";
  TempDir temp;
  const fs::path case_dir = kSuite / c.name;
  const nlohmann::json expected = nlohmann::json::parse(readText(case_dir / "expected.json"));
  // A name of at most 15 characters (the kernel's limit), unique per case and isolation.
  std::string marker = "adv-" + c.name.substr(0, 8) + (c.isolation == "auto" ? "-b" : "-r");
  const fs::path results_dir = temp.path() / "results";
  fs::create_directories(results_dir);
  writeText(results_dir / "previous.json", "{\"score\": 12}\n");
  // A file only root may read, for a case that tries to get the grader to copy it.
  const fs::path secret_file = temp.path() / "secret.txt";
  writeText(secret_file, "ROOT-ONLY-SECRET-" + marker + "\n");
  fs::permissions(secret_file, fs::perms::owner_read | fs::perms::owner_write,
                  fs::perm_options::replace);

  // The base submission with the case's changed file, placeholders filled in.
  const fs::path submission = temp.path() / "submission" / "src";
  fs::create_directories(submission);
  for (const char* name : kFiles) {
    const fs::path own = case_dir / name;
    std::string text = readText(
        fs::exists(own) ? own : kCorpus / expected["base"].get<std::string>() / "src" / name);
    // the base is a copy of our reference: its header line is what a reference read would leak
    replaceAll(text, "clothref's reference solution", "a student's solution");
    replaceAll(text, "@MARKER@", marker);
    replaceAll(text, "@SECRET_FILE@", secret_file.string());
    replaceAll(text, "@SOURCE_DIR@", CLOTHREF_SOURCE_DIR);
    replaceAll(text, "@RESULTS_DIR@", results_dir.string());
    writeText(submission / name, text);
  }

  setenv("CLOTHREF_GRADER_ISOLATION", c.isolation.c_str(), 1);
  const fs::path keep = temp.path() / "keep";
  // A short limit keeps the endless cases quick; the others get room for a loaded machine (CI
  // saw nan-results, output-flood and read-reference time out at 3 s while the suite ran).
  const bool ends_by_time = expected.value("verdict", "") == "timed-out" ||
                            expected.value("verdict_rlimits", "") == "timed-out";
  const std::string timeout = expected.contains("timeout")
                                  ? std::to_string(expected["timeout"].get<int>())
                              : ends_by_time ? "3"
                                             : "30";
  const CommandResult run =
      runCli("grade '" + submission.parent_path().string() + "' --no-whole-run --timeout " +
             timeout + " --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "' --results '" +
             (results_dir / "results.json").string() + "' --report '" +
             (results_dir / "report.md").string() + "'" +
             (expected.value("keep_work", false) ? " --keep-work '" + keep.string() + "'" : ""));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json results = nlohmann::json::parse(readText(results_dir / "results.json"));
  const std::string isolation = results["extra_data"]["isolation"];
  const bool boxed = isolation.rfind("bubblewrap", 0) == 0;
  if (c.isolation == "auto" && !boxed)
    GTEST_SKIP() << "bubblewrap does not work here: " << isolation;
  EXPECT_EQ(boxed, c.isolation == "auto") << isolation;

  const std::string want = c.isolation == "rlimits" && expected.contains("verdict_rlimits")
                               ? expected["verdict_rlimits"]
                               : expected["verdict"];
  EXPECT_EQ(results["extra_data"]["verdict"], want) << results["output"];
  const std::string report = readText(results_dir / "report.md");
  EXPECT_NE(report.find("Verdict: **" + want + "**"), std::string::npos);
  EXPECT_NE(report.find("Student code ran with: " + isolation), std::string::npos);
  for (const auto& stub : expected.value("loses", nlohmann::json::array())) {
    EXPECT_LT(results["extra_data"]["stub_scores"][stub.get<std::string>()].get<double>(),
              results["extra_data"]["stub_max"][stub.get<std::string>()].get<double>())
        << stub;
  }
  if (expected.value("full_marks", false) && want == expected["verdict"].get<std::string>()) {
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), 80.0) << results.dump(1).substr(0, 3000);
  }

  // Contained: nothing of the run is alive. The grader waits for a sandbox's pid namespace to
  // be gone; in the fallback the killed process group may still be on its way out, so poll.
  if (expected.value("marker", false)) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    int alive = liveProcessesNamed(marker);
    while (alive > 0 && !boxed && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      alive = liveProcessesNamed(marker);
    }
    EXPECT_EQ(alive, 0) << "processes named " << marker << " survived the grade";
  }
  EXPECT_EQ(readText(results_dir / "previous.json"), "{\"score\": 12}\n");
  EXPECT_FALSE(fs::exists(results_dir / "forged.json"));
  if (expected.contains("secret_text")) {
    const std::string secret = expected["secret_text"];
    ASSERT_FALSE(secret.empty());
    EXPECT_EQ(readText(results_dir / "results.json").find(secret), std::string::npos);
    EXPECT_EQ(report.find(secret), std::string::npos);
  }
  if (expected.contains("reports_readable")) {
    std::string path = expected["reports_readable"];
    replaceAll(path, "@SOURCE_DIR@", CLOTHREF_SOURCE_DIR);
    // Informational: the assertions above hold whatever this says.
    const bool readable = !boxed && readableByNobody(path);
    RecordProperty("student_could_read_reference", readable ? "yes" : "no");
    std::cout << "[ info     ] the student process " << (readable ? "could" : "could not")
              << " read " << path << " (" << isolation << ")\n";
  }
  if (expected.contains("secret_file")) {
    std::string path = expected["secret_file"];
    replaceAll(path, "@SECRET_FILE@", secret_file.string());
    std::string secret;
    std::getline(std::ifstream(path), secret);
    if (!secret.empty()) {
      EXPECT_EQ(readText(results_dir / "results.json").find(secret), std::string::npos);
      EXPECT_EQ(report.find(secret), std::string::npos);
      // nor in the scratch folder the grader kept: it copied no link a probe made
      std::uintmax_t kept_bytes = 0;
      std::error_code error;
      for (auto it = fs::recursive_directory_iterator(keep, error);
           it != fs::recursive_directory_iterator(); it.increment(error)) {
        if (!it->is_regular_file(error) || it->is_symlink(error)) continue;
        kept_bytes += it->file_size(error);
        EXPECT_EQ(readText(it->path()).find(secret), std::string::npos) << it->path();
      }
      if (expected.value("keep_work", false)) {
        // Where the probe's folder is a bounded filesystem of its own (bubblewrap, a private mount
        // namespace) the links go with it; where it is a host folder they are listed, not copied.
        EXPECT_TRUE(fs::exists(keep / "skipped.txt") ||
                    !fs::exists(keep / "probes" / "integrate-0" / "sandbox" / "leak"));
        EXPECT_LT(kept_bytes, 64u << 20) << "a linked host folder was copied";
        EXPECT_EQ(report.find("could not copy"), std::string::npos);
      }
    }
  }
  if (expected.contains("quoted")) {
    // The student's own words (a compile error), in the output the student reads.
    EXPECT_NE(results.dump().find(expected["quoted"].get<std::string>()), std::string::npos)
        << results.dump(1).substr(0, 3000);
  }
  if (expected.contains("score")) {
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), expected["score"].get<double>());
  }
  if (expected.value("no_files_left", false)) {
    for (const char* shared : {"/tmp", "/var/tmp", "/dev/shm", "/run/lock"}) {
      std::error_code error;
      for (const auto& entry : fs::directory_iterator(shared, error)) {
        EXPECT_NE(entry.path().filename().string().rfind(marker, 0), 0u)
            << entry.path() << " outlived the grade";
      }
    }
  }
}

// NaN and garbage never earn a mistake's points (issue 36): every stub of an edition written as a
// body that only writes NaN into what the stub may change earns no more than the same stub left
// as the course hands it out (empty, or for Cloth::initializeSpring the template's one example
// loop). Before the fix a NaN computeSpringForce got 15 / 20 in 2022 (its corners "moved"), and
// a NaN RK4 7.5 where an empty one got 6.375.
struct StubBody {
  const char* file;
  const char* head;  // the definition's first characters: the body follows its first '{'
  const char* empty;
  const char* nan;
};

const std::vector<StubBody>& stubBodies() {
  static const std::string template_loop =
      "  float length = (_particles.position(0) - _particles.position(1)).norm();\n"
      "  for (int i = 0; i < particlesPerEdge; ++i)\n"
      "    for (int j = 0; j < particlesPerEdge - 1; ++j)\n"
      "      _springs.emplace_back(i * particlesPerEdge + j, i * particlesPerEdge + j + 1, "
      "LENGTH,\n"
      "                            Spring::Type::STRUCTURAL);\n";
  static const std::string empty_springs = [] {
    std::string text = template_loop;
    replaceAll(text, "LENGTH", "length");
    return text;
  }();
  static const std::string nan_springs = [] {
    std::string text = template_loop;
    replaceAll(text, "LENGTH", "std::numeric_limits<float>::quiet_NaN() + 0 * length");
    return text;
  }();
  static const char* const integrate_nan =
      "  for (Particles *p : particles) {\n"
      "    p->position().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
      "    p->velocity().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
      "  }\n";
  static const std::vector<StubBody> bodies = {
      {"cloth.cpp", "void Cloth::initializeSpring()", empty_springs.c_str(), nan_springs.c_str()},
      {"cloth.cpp", "void Cloth::computeSpringForce()", "",
       "  _particles.acceleration().setConstant(std::numeric_limits<float>::quiet_NaN());\n"},
      {"sphere.cpp", "void Spheres::collide(Cloth*", "",
       "  cloth->particles().position().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
       "  cloth->particles().velocity().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
       "  _particles.position().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
       "  _particles.velocity().setConstant(std::numeric_limits<float>::quiet_NaN());\n"},
      {"sphere.cpp", "void Spheres::collide() {", "",
       "  _particles.position().setConstant(std::numeric_limits<float>::quiet_NaN());\n"
       "  _particles.velocity().setConstant(std::numeric_limits<float>::quiet_NaN());\n"},
      {"integrator.cpp", "void ExplicitEuler::integrate(", "", integrate_nan},
      {"integrator.cpp", "void ImplicitEuler::integrate(", "", integrate_nan},
      {"integrator.cpp", "void MidpointEuler::integrate(", "", integrate_nan},
      {"integrator.cpp", "void RungeKuttaFourth::integrate(", "", integrate_nan}};
  return bodies;
}

// `source` with the body of the definition starting at `head` replaced (it must be there once;
// absent is fine: 2024 has no Spheres::collide()).
std::string withBody(std::string source, const std::string& head, const std::string& body) {
  const std::size_t at = source.find(head);
  if (at == std::string::npos) return source;
  EXPECT_EQ(source.find(head, at + 1), std::string::npos) << head;
  const std::size_t open = source.find('{', at);
  const std::size_t close = source.find("\n}\n", open);
  if (open == std::string::npos || close == std::string::npos) {
    ADD_FAILURE() << "no body after " << head;
    return source;
  }
  return source.substr(0, open + 1) + "\n" + body + source.substr(close + 1);
}

// Grades the edition's reference with every stub's body replaced (`nan` or empty), and returns
// results.json.
nlohmann::json gradeWithBodies(const fs::path& where, const std::string& edition, bool nan) {
  const fs::path submission = where / (nan ? "nan" : "empty");
  fs::create_directories(submission);
  for (const char* name : kFiles) {
    std::string text = readText(kCorpus / edition / "reference" / "src" / name);
    text = "#include <limits>\n" + text;
    for (const StubBody& stub : stubBodies())
      if (std::string(stub.file) == name)
        text = withBody(text, stub.head, nan ? stub.nan : stub.empty);
    writeText(submission / name, text);
  }
  const fs::path results = where / (std::string(nan ? "nan" : "empty") + ".json");
  const CommandResult run =
      runCli("grade '" + submission.string() + "' --edition " + edition +
             " --no-whole-run --timeout 30 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) +
             "' --results '" + results.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  if (run.exit_code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(readText(results));
}

class NanStubs : public ::testing::TestWithParam<const char*> {};

TEST_P(NanStubs, EarnNoMoreThanEmptyBodies) {
  const std::string edition = GetParam();
  TempDir temp;
  const nlohmann::json nan = gradeWithBodies(temp.path(), edition, true);
  const nlohmann::json empty = gradeWithBodies(temp.path(), edition, false);
  ASSERT_TRUE(nan.contains("extra_data") && empty.contains("extra_data"));
  const nlohmann::json& nan_scores = nan["extra_data"]["stub_scores"];
  const nlohmann::json& empty_scores = empty["extra_data"]["stub_scores"];
  ASSERT_EQ(nan_scores.size(), edition == "2022" ? 8u : 7u) << nan_scores.dump();
  ASSERT_EQ(empty_scores.size(), nan_scores.size());
  for (const auto& [stub, points] : nan_scores.items()) {
    ASSERT_TRUE(empty_scores.contains(stub)) << stub;
    const double of_nan = points.get<double>(), of_empty = empty_scores[stub].get<double>();
    std::cout << "[ info     ] " << edition << " " << stub << ": NaN " << of_nan << ", empty "
              << of_empty << " of " << nan["extra_data"]["stub_max"][stub] << "\n";
    RecordProperty(edition + " " + stub,
                   std::to_string(of_nan) + " (NaN) vs " + std::to_string(of_empty) + " (empty)");
    EXPECT_LE(of_nan, of_empty) << stub << " written as NaN earns more than an empty body";
  }
}

INSTANTIATE_TEST_SUITE_P(Editions, NanStubs, ::testing::Values("2022", "2024"));

INSTANTIATE_TEST_SUITE_P(Suite, Adversarial, ::testing::ValuesIn(suiteCases()),
                         [](const auto& info) {
                           std::string name = info.param.name + "_" + info.param.isolation;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace clothref::test
