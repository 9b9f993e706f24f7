// The probe protocol's names are one table (bridge/probe_keys.h): every key distinct, the per-case
// form, and no key written as a string literal in the files that exchange messages.
#include "grader/bridge/probe_keys.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace key = probe::key;
namespace group = probe::group;

TEST(ProbeKeys, EveryKeyAndGroupIsDistinct) {
  const std::vector<std::string> keys = {
      key::kGroup,      key::kCases,      key::kMethod,        key::kClothPos,
      key::kClothVel,   key::kClothAcc,   key::kClothMass,     key::kSpherePos,
      key::kSphereVel,  key::kSphereMass, key::kSphereRadius,  key::kSpringStart,
      key::kSpringEnd,  key::kSpringType, key::kSpringRest,    key::kParticlesPerEdge,
      key::kSpringCoef, key::kDamperCoef, key::kParams,        key::kFlags,
      key::kDt,         key::kSteps,      key::kStride,        key::kDtAfter,
      key::kCalls,      key::kTrajectory, key::kSphereCapacity, key::kRecordStages,
      key::kStartClothPos, key::kStartClothVel, key::kStartClothAcc, key::kStartSpherePos,
      key::kStartSphereVel, key::kStartSphereAcc, key::kEvalClothPos, key::kEvalClothVel,
      key::kEvalClothAcc, key::kEvalSpherePos, key::kEvalSphereVel, key::kEvalSphereAcc};
  EXPECT_EQ(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size());
  const std::vector<std::string> groups = {group::kSprings,      group::kForces,
                                           group::kCollideCloth, group::kCollideSpheres,
                                           group::kIntegrate,    group::kWholeRun};
  EXPECT_EQ(std::set<std::string>(groups.begin(), groups.end()).size(), groups.size());
}

TEST(ProbeKeys, PerCaseAppendsTheCaseIndex) {
  EXPECT_EQ(key::perCase(key::kClothPos, 0), "cloth.pos.0");
  EXPECT_EQ(key::perCase(key::kTrajectory, 12), "trajectory.12");
  EXPECT_NE(key::perCase(key::kClothPos, 1), key::perCase(key::kClothPos, 11));
}

// A literal key in a message access (`floats["x"]`, `.f("x")`, ...) bypasses the table: the two
// sides could drift apart with no compiler error.
TEST(ProbeKeys, NoKeyLiteralInTheFilesThatExchangeMessages) {
  const std::filesystem::path grader = std::filesystem::path(CLOTHREF_SOURCE_DIR) / "tools/grader";
  std::vector<std::filesystem::path> files = {grader / "driver/probe_driver.cpp"};
  for (const auto& entry : std::filesystem::directory_iterator(grader / "grade/probes"))
    files.push_back(entry.path());
  ASSERT_GE(files.size(), 9u);  // the driver, probes.h/.cpp, util.h, four probes, whole_run
  const std::regex literal_key(
      R"re(\b(floats|ints|texts)\s*\[\s*"|[.>](f|i|scalar|scalarInt|text)\s*\(\s*")re");
  for (const auto& file : files) {
    std::ifstream in(file);
    ASSERT_TRUE(in) << file;
    int number = 0;
    for (std::string line; std::getline(in, line);) {
      ++number;
      EXPECT_FALSE(std::regex_search(line, literal_key))
          << file.filename().string() << ":" << number << ": " << line;
    }
  }
}

}  // namespace
