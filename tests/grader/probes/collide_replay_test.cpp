// Contact models replayed (grader/grade/probes/collide_replay.cpp), end to end: the 2022
// reference's Spheres::collide(Cloth*) with two mistakes of blind3's hu, a correction of 0.2 and
// friction added to the accelerations, graded by the CLI. The correction's model gives every
// position and velocity; the accelerations differ only where the call changed them, which no
// contact model does: both causes are proven, the read one on the checks whose accelerations
// changed, and per-mistake points follow.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "corpus.h"
#include "grader/grade/cause_ids.h"
#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;

void replace(std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
}

// The causes proven on the reference with Spheres::collide(Cloth*) changed by `edit`, and the
// report.
std::set<std::string> provenInCollide(const TempDir& temp,
                                      const std::function<void(std::string&)>& edit,
                                      std::string& report) {
  const fs::path dir = temp.path() / "submission";
  fs::create_directories(dir);
  const fs::path reference = corpusDir() / "2022" / "reference";
  for (const char* name : {"cloth.cpp", "sphere.cpp", "integrator.cpp"})
    fs::copy_file(corpusFile(reference, name), dir / name);
  std::string sphere = readText(dir / "sphere.cpp");
  const std::size_t stub = sphere.find("void Spheres::collide(Cloth* cloth) {");
  EXPECT_NE(stub, std::string::npos);
  std::string body = sphere.substr(stub);
  edit(body);
  std::ofstream(dir / "sphere.cpp") << sphere.substr(0, stub) + body;
  const CommandResult run =
      runCli("grade '" + dir.string() + "' --no-whole-run --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --results '" + temp.file("results.json") +
             "' --report '" + temp.file("report.md") + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::set<std::string> proven;
  if (run.exit_code != 0) return proven;
  std::ifstream in(temp.file("results.json"));
  const nlohmann::json results = nlohmann::json::parse(in);
  for (const auto& test : results["tests"]) {
    if (test["tags"][0] != "Spheres::collide(Cloth*)" || test["status"] != "failed") continue;
    const auto extra = test.find("extra_data");
    if (extra == test.end()) continue;
    for (const auto& cause : extra->value("causes", nlohmann::json::array()))
      if (cause.value("proven", false)) proven.insert(cause["id"]);
  }
  report = readText(temp.file("report.md"));
  return proven;
}

const std::string kFriction =
    "      Eigen::Vector4f slide = relativeVelocity - normal * approach;  // friction\n"
    "      _particles.acceleration(i) -= 0.3f * slide * _particles.inverseMass(i);\n"
    "      clothParticles.acceleration(j) += 0.3f * slide * clothParticles.inverseMass(j);\n"
    "      // Push them apart";

TEST(ContactReplay, AModelRightButForTheAccelerationsProvesItsCauseBesideTheReadOne) {
  TempDir temp;
  std::string report;
  const std::set<std::string> proven = provenInCollide(
      temp,
      [](std::string& body) {
        replace(body, "(penetration * normal) * 0.15f", "(penetration * normal) * 0.2f");
        replace(body, "      // Push them apart", kFriction);
      },
      report);
  EXPECT_EQ(proven, (std::set<std::string>{grader::cause::kCorrectionFactor,
                                           grader::cause::kCollideChangesAcceleration}));
  EXPECT_NE(report.find("2 proven mistakes (`correction-factor`, `collide-changes-acceleration`) "
                        "explain every failed check"),
            std::string::npos)
      << report.substr(0, 5000);
}

// Friction alone (blind3 liang, blind peng): the course's collide gives every position and
// velocity, so the read is the whole explanation, and no fitted constant equal to the course's
// (a restitution of 0) is named beside it.
TEST(ContactReplay, FrictionAloneIsTheReadOnTheCoursesCollide) {
  TempDir temp;
  std::string report;
  const std::set<std::string> proven = provenInCollide(
      temp, [](std::string& body) { replace(body, "      // Push them apart", kFriction); },
      report);
  EXPECT_EQ(proven, (std::set<std::string>{grader::cause::kCollideChangesAcceleration}));
  EXPECT_NE(report.find("Proven: the course's collide (and the accelerations as your call "
                        "changed them"),
            std::string::npos)
      << report.substr(0, 5000);
}

}  // namespace
}  // namespace clothref::test
