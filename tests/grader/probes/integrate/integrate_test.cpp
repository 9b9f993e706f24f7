// The integrator probe end to end (grader/grade/probes/integrate/integrate.cpp): the 2022 reference
// with one integrator rewritten, graded by the CLI. A wrong stub's first failed check carries the
// stage explanation in the course's terms (results.json and report.md alike), its later failed
// checks refer to it instead of repeating it, and the fit's cause is likely; a right stub shows
// none.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "corpus.h"
#include "grader/grade/cause_ids.h"
#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;

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

// `submission` graded by the CLI into `temp` (results.json, report.md): its results, or null
// (with a failure) when the grade did not finish.
nlohmann::json graded(const TempDir& temp, const fs::path& submission) {
  const CommandResult run =
      runCli("grade '" + submission.string() + "' --no-whole-run --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --results '" + temp.file("results.json") +
             "' --report '" + temp.file("report.md") + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  if (run.exit_code != 0) return nullptr;
  std::ifstream in(temp.file("results.json"));
  return nlohmann::json::parse(in);
}

// A test's causes in results.json (a passed test has no extra_data).
nlohmann::json causesOf(const nlohmann::json& test) {
  const auto extra = test.find("extra_data");
  return extra == test.end() ? nlohmann::json::array()
                             : extra->value("causes", nlohmann::json::array());
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
  const nlohmann::json results = graded(temp, submission);
  ASSERT_FALSE(results.is_null());
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

// An RK4 that is explicit Euler (tung's, blind3: the cloth's stages undone) blows up in the
// stability run, where the course's RK4 does not: that overflow is the method's instability, not
// a NaN of the stub's, so the stub is not said to make non-finite numbers and the submission's
// verdict stays graded.
TEST(IntegratorStages, AnUnstableMethodsOverflowIsNotANonFiniteStub) {
  TempDir temp;
  const fs::path submission = withBody(temp, "RungeKuttaFourth::integrate",
                                       "  for (auto* p : particles) {\n"
                                       "    p->position() += deltaTime * p->velocity();\n"
                                       "    p->velocity() += deltaTime * p->acceleration();\n"
                                       "  }\n");
  const nlohmann::json results = graded(temp, submission);
  ASSERT_FALSE(results.is_null());
  EXPECT_EQ(results["extra_data"]["verdict"], "graded");
  bool unstable = false;
  for (const auto& test : results["tests"]) {
    if (test["tags"][0] != "RungeKuttaFourth::integrate") continue;
    const std::string name = test["name"], output = test["output"];
    if (contains(name, "stable below") && test["status"] == "failed")
      unstable = contains(output, "not finite");
    for (const auto& cause : causesOf(test))
      EXPECT_NE(cause["id"], grader::cause::kNonFinite) << name;
  }
  EXPECT_TRUE(unstable) << "the stability run overflows (else this test shows nothing)";
}

// A midpoint that halves the global deltaTime for the whole method and puts back a constant (blind3
// chai): its prediction x0 + h/2 v0 is the course's, its corrector takes h/2. The same numbers are
// implicit Euler at h/2, but the grader names what the code does, both causes proven together.
TEST(IntegratorStages, AHalvedDeltaTimeIsAHalfStepCorrectorNotAFullStepPrediction) {
  TempDir temp;
  const fs::path submission =
      withBody(temp, "MidpointEuler::integrate",
               "  std::vector<Eigen::Matrix4Xf> pos, vel;\n"
               "  for (auto p : particles) {\n"
               "    pos.push_back(p->position());\n"
               "    vel.push_back(p->velocity());\n"
               "  }\n"
               "  deltaTime = deltaTime / 2;  // midpoint = half step\n"
               "  for (auto p : particles) {\n"
               "    p->position() += p->velocity() * deltaTime;\n"
               "    p->velocity() += p->acceleration() * deltaTime;\n"
               "  }\n"
               "  simulateOneStep();\n"
               "  for (size_t i = 0; i < particles.size(); ++i) {\n"
               "    particles[i]->position() = pos[i] + particles[i]->velocity() * deltaTime;\n"
               "    particles[i]->velocity() = vel[i] + particles[i]->acceleration() * deltaTime;\n"
               "  }\n"
               "  deltaTime = 1e-4f;\n");
  const nlohmann::json results = graded(temp, submission);
  ASSERT_FALSE(results.is_null());
  std::set<std::string> likely;
  for (const auto& test : results["tests"])
    if (test["tags"][0] == "MidpointEuler::integrate")
      for (const auto& cause : causesOf(test))
        if (cause.value("likely", false)) likely.insert(cause["id"]);
  EXPECT_EQ(likely, (std::set<std::string>{grader::cause::kDeltatimeMutated,
                                           grader::cause::kHalfStepCorrector}));
  const std::string report = readText(temp.file("report.md"));
  EXPECT_TRUE(contains(report,
                       "Proven: the course's midpoint whose corrector takes h/2; and "
                       "leaving deltaTime at 0.0001 s after the call"))
      << report.substr(0, 6000);
}

}  // namespace
}  // namespace clothref::test
