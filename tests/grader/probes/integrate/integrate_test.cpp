// The integrator probe end to end (grader/grade/probes/integrate/integrate.cpp): the 2022 reference
// with one integrator rewritten, graded by the CLI. A wrong stub's first failed check carries the
// stage explanation in the course's terms (results.json and report.md alike), its later failed
// checks refer to it instead of repeating it, and the fit's cause is likely; a right stub shows
// none.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "corpus.h"
#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The 2022 reference with the body of `stub` ("ImplicitEuler::integrate") replaced by `body`.
fs::path withBody(const TempDir& temp, const std::string& stub, const std::string& body) {
  const fs::path dir = temp.path() / "submission";
  fs::create_directories(dir);
  for (const char* name : {"cloth.cpp", "sphere.cpp", "integrator.cpp"})
    fs::copy_file(corpusFile(corpusDir() / "2022" / "reference", name), dir / name);
  std::string text = readText(dir / "integrator.cpp");
  const std::size_t at = text.find("void " + stub + "(");
  EXPECT_NE(at, std::string::npos) << stub;
  const std::size_t open = text.find(" {\n", at) + 3;
  const std::size_t close = text.find("\n}\n", open) + 1;
  text = text.substr(0, open) + body + text.substr(close);
  std::ofstream(dir / "integrator.cpp") << text;
  return dir;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The example: a pointer-vector "backup" and simulateOneStep() at the start state make
// ImplicitEuler::integrate forward Euler.
TEST(IntegratorStages, TheExplanationReachesResultsAndReportOncePerStub) {
  TempDir temp;
  const fs::path submission =
      withBody(temp, "ImplicitEuler::integrate",
               "  auto tmp = particles;  // backup\n"
               "  simulateOneStep();\n"
               "  for (size_t i = 0; i < particles.size(); ++i) {\n"
               "    particles[i]->position() = tmp[i]->position() + tmp[i]->velocity() * "
               "deltaTime;\n"
               "    particles[i]->velocity() = tmp[i]->velocity() + tmp[i]->acceleration() * "
               "deltaTime;\n"
               "  }\n");
  const CommandResult run =
      runCli("grade '" + submission.string() + "' --no-whole-run --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --results '" + temp.file("results.json") +
             "' --report '" + temp.file("report.md") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(temp.file("results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  const std::string said =
      "This is forward Euler (the course's explicit Euler): "
      "simulateOneStep() once, at the start state.";
  const std::string where = "Evaluation 1 position: yours x0, the course's x0 + h·v0.";
  const std::string refer =
      "Your stages are compared with the course's under “one step on a random state” above.";
  int explained = 0, referred = 0, failed = 0;
  for (const auto& test : results["tests"]) {
    const std::string stub = test["tags"][0], output = test["output"];
    if (stub == "ExplicitEuler::integrate" || stub == "MidpointEuler::integrate" ||
        stub == "RungeKuttaFourth::integrate") {
      EXPECT_FALSE(contains(output, "Your stages")) << stub << ": " << output;
    }
    if (stub != "ImplicitEuler::integrate" || test["status"] != "failed") continue;
    ++failed;
    if (contains(output, said)) {
      ++explained;
      EXPECT_TRUE(contains(output, where)) << output;
      EXPECT_TRUE(contains(output, "**Likely cause** (`no-reevaluation`)")) << output;
      EXPECT_EQ(test["name"], "ImplicitEuler::integrate: one step on a random state");
    } else {
      EXPECT_TRUE(contains(output, refer)) << output;
      ++referred;
    }
  }
  EXPECT_EQ(explained, 1);
  EXPECT_GE(failed, 2) << "the one step and the convergence order fail";
  EXPECT_EQ(referred, failed - 1);
  const std::string report = readText(temp.file("report.md"));
  EXPECT_TRUE(contains(report, said)) << report.substr(0, 4000);
  EXPECT_TRUE(contains(report, where));
  EXPECT_TRUE(contains(report, "| evaluation 1 | x0 | v0 |")) << report.substr(0, 4000);
}

}  // namespace
}  // namespace clothref::test
