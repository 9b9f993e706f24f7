// The probe protocol's names are one list each (bridge/probe_keys.h, group::kAll and key::kAll):
// every name distinct, the per-case form, and no key written as a string literal in the files that
// exchange messages.
#include "grader/bridge/probe_keys.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace key = probe::key;
namespace group = probe::group;

// Every name is distinct within its list (a group is sent under key::kGroup, so groups and keys
// never meet), and its identifier is its own: the lists declare what they list.
TEST(ProbeKeys, EveryKeyAndGroupIsDistinct) {
  for (const auto& list : {std::vector<probe::Name>(std::begin(group::kAll), std::end(group::kAll)),
                           std::vector<probe::Name>(std::begin(key::kAll), std::end(key::kAll))}) {
    std::set<std::string> texts, identifiers;
    for (const probe::Name& name : list) {
      EXPECT_TRUE(texts.insert(name.text).second) << name.identifier << " repeats " << name.text;
      EXPECT_TRUE(identifiers.insert(name.identifier).second) << name.identifier;
      EXPECT_FALSE(std::string(name.text).empty()) << name.identifier;
    }
  }
  EXPECT_STREQ(group::kAll[0].identifier, "kSprings");
  EXPECT_STREQ(group::kAll[0].text, group::kSprings);
}

// A key "<k>.<digits>" would be read as case <digits> of key <k>: no key may look like that, and
// no key's per-case form may be another key.
TEST(ProbeKeys, NoKeyIsAnotherKeysPerCaseForm) {
  const std::regex case_suffix(R"(\.[0-9]+$)");
  std::set<std::string> texts;
  for (const probe::Name& name : key::kAll) texts.insert(name.text);
  for (const probe::Name& name : key::kAll) {
    EXPECT_FALSE(std::regex_search(std::string(name.text), case_suffix)) << name.identifier;
    for (int k : {0, 1, 10}) EXPECT_FALSE(texts.count(key::perCase(name.text, k))) << name.text;
  }
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
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"driver", "grade/probes"})
    for (const auto& entry : std::filesystem::recursive_directory_iterator(grader / folder))
      if (entry.is_regular_file()) files.push_back(entry.path());
  // the driver, its support and five groups; probes.h/.cpp, util.h, four probes, whole_run
  ASSERT_GE(files.size(), 16u);
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
