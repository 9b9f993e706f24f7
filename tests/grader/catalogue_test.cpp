// The catalogue of causes: the generated cause-id constants (grader/grade/cause_ids.h) and the
// catalogue the grader loads are the same ids, one constant each, named k + CamelCase of the id;
// every entry explains itself (why, a two-line example); a malformed catalogue is refused in one
// line naming the file and the field; fillCauseTexts carries text, why and example to the causes.
#include "grader/grade/catalogue.h"

#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "clothref/io/error.h"
#include "grader/grade/cause_ids.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

const fs::path kCatalogue = fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/diagnoses.json";

// "hard-coded-n25" -> "kHardCodedN25", written here again so the generator is checked against it.
std::string constantName(const std::string& id) {
  std::string name = "k";
  bool upper = true;
  for (char c : id) {
    if (c == '-') {
      upper = true;
      continue;
    }
    name += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return name;
}

TEST(CauseIds, EveryConstantIsAnIdOfTheCatalogueAndEveryIdHasOne) {
  const Catalogue catalogue = loadCatalogue(kCatalogue);
  std::set<std::string> constants;
  for (const cause::NamedId& named : cause::namedIds()) {
    EXPECT_TRUE(catalogue.entries.count(named.id)) << named.name << " = \"" << named.id << "\"";
    EXPECT_EQ(named.name, constantName(named.id)) << named.id;
    EXPECT_TRUE(constants.insert(named.id).second) << "two constants for " << named.id;
  }
  for (const auto& [id, diagnosis] : catalogue.entries)
    EXPECT_TRUE(constants.count(id)) << id << " has no constant in cause_ids.h";
  EXPECT_EQ(constants.size(), catalogue.entries.size());
  EXPECT_STREQ(cause::kBackupAlias, "backup-alias");
  EXPECT_STREQ(cause::kHardCodedN25, "hard-coded-n25");
}

// Every cause says why it gives the numbers a student sees; an example is the mistaken line and
// its fix, two lines (none only where no line of the student's is at fault).
TEST(Catalogue, EveryEntryHasAWhyAndATwoLineExample) {
  const Catalogue catalogue = loadCatalogue(kCatalogue);
  const std::set<std::string> without_example = {cause::kGraderError, cause::kUnknown};
  for (const auto& [id, d] : catalogue.entries) {
    EXPECT_FALSE(d.why.empty()) << id;
    EXPECT_EQ(d.why.find('\n'), std::string::npos) << id << ": the why is one paragraph";
    if (without_example.count(id)) {
      EXPECT_TRUE(d.example.empty()) << id;
      continue;
    }
    const std::size_t newline = d.example.find('\n');
    ASSERT_NE(newline, std::string::npos) << id << ": " << d.example;
    EXPECT_EQ(d.example.find('\n', newline + 1), std::string::npos) << id << ": " << d.example;
    EXPECT_NE(d.example.find("mistake"), std::string::npos) << id << ": " << d.example;
    EXPECT_NE(d.example.substr(newline).find("fix"), std::string::npos) << id << ": " << d.example;
  }
}

// The causes other probes name (fitted constants, the integrators' known methods, the files that
// could not be used) are in the catalogue.
TEST(Catalogue, HasTheCausesOfTheFittingProbesAndOfUnusableFiles) {
  const Catalogue catalogue = loadCatalogue(kCatalogue);
  for (const char* id : {cause::kCorrectionFactor, cause::kSpringCoefficient,
                         cause::kDamperCoefficient, cause::kMissingFile, cause::kLinkError,
                         cause::kHeunMethod, cause::kHalfStepCorrector, cause::kVelocityDamped})
    EXPECT_TRUE(catalogue.entries.count(id)) << id;
  EXPECT_NE(catalogue.entries.at(cause::kCompileError).text.find("whole compile log"),
            std::string::npos);
}

// The real catalogue with the first `from` replaced by `to`, written in `temp`.
fs::path edited(const test::TempDir& temp, const std::string& from, const std::string& to) {
  std::string text = test::readText(kCatalogue);
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const fs::path path = temp.path() / "diagnoses.json";
  test::writeText(path, text);
  return path;
}

// The message of the InputError loading `path` throws ("" when it loads).
std::string refusal(const fs::path& path) {
  try {
    loadCatalogue(path);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(LoadCatalogue, RefusesAMalformedFileInOneLineNamingTheFileAndTheField) {
  test::TempDir temp;
  struct Case {
    const char* what;
    std::string from, to, field, problem;
  };
  const std::vector<Case> cases = {
      {"not JSON", "\"diagnoses\": [", "\"diagnoses\": [,", "", "not valid JSON"},
      {"no list", "\"diagnoses\": [", "\"entries\": [", "/diagnoses: ", "expected an array"},
      {"duplicate id", "\"id\": \"crashed\"", "\"id\": \"compile-error\"",
       "/diagnoses/3/id: ", "duplicate id \"compile-error\" (first at /diagnoses/0)"},
      {"unknown field", "\"why\": ", "\"reason\": ", "/diagnoses/0/reason: ", "unknown field"},
      {"missing field", ", \"example\": \"\"}\n  ]", "}\n  ]", "/example: ", "missing"},
      {"mistyped field", "\"id\": \"compile-error\", \"stub\": \"*\"",
       "\"id\": \"compile-error\", \"stub\": [\"*\"]", "/diagnoses/0/stub: ", "expected a string"},
      {"empty field", "\"id\": \"crashed\", \"stub\": \"*\"", "\"id\": \"crashed\", \"stub\": \"\"",
       "/diagnoses/3/stub: ", "empty"},
      {"id not words", "\"id\": \"unstable\"", "\"id\": \"Unstable \"",
       "/id: ", "\"Unstable \" is not lower-case words joined by '-'"},
      {"unknown way", "\"recognised_by\": \"guess\"", "\"recognised_by\": \"hunch\"",
       "/recognised_by: ", "unknown: \"hunch\""},
      {"mistyped deduction",
       "\"deduction\": null, \"proof\": \"read\", \"model\": null, \"text\": \"The file does",
       "\"deduction\": \"none\", \"proof\": \"read\", \"model\": null, \"text\": \"The file does",
       "/diagnoses/0/deduction: ", "expected a number or null"},
      {"no deduction", "\"deduction\": null, \"proof\": \"read\"", "\"proof\": \"read\"",
       "/diagnoses/0/deduction: ", "missing"},
      {"no proof", "\"proof\": \"read\", \"model\": null, \"text\": \"The file does",
       "\"model\": null, \"text\": \"The file does", "/diagnoses/0/proof: ", "missing"},
      {"no model", "\"model\": null, \"text\": \"The file does", "\"text\": \"The file does",
       "/diagnoses/0/model: ", "missing"},
      {"mistyped model", "\"model\": null, \"text\": \"The file does",
       "\"model\": 3, \"text\": \"The file does",
       "/diagnoses/0/model: ", "expected a string or null"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const fs::path path = edited(temp, c.from, c.to);
    const std::string message = refusal(path);
    ASSERT_FALSE(message.empty()) << "loaded";
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.field), std::string::npos) << message;
    EXPECT_NE(message.find(c.problem), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // the real one loads, and a missing file is refused by name
  EXPECT_EQ(refusal(kCatalogue), "");
  const std::string missing = refusal(temp.path() / "none.json");
  EXPECT_NE(missing.find((temp.path() / "none.json").string()), std::string::npos) << missing;
}

TEST(FillCauseTexts, GivesEachCauseItsTextWhyAndExampleAndMakesAGuessOfAGuessOnlyEntry) {
  const Catalogue catalogue = loadCatalogue(kCatalogue);
  TestResult t = makeTest("Cloth::computeSpringForce", "still state", 1);
  t.addCause(cause::kAssignNotAccumulate);
  t.addCause(cause::kUnknown);
  t.addCause("not-in-the-catalogue");
  std::vector<TestResult> tests = {t};
  fillCauseTexts(catalogue, tests);
  const Diagnosis& assign = catalogue.entries.at(cause::kAssignNotAccumulate);
  const Cause& named = tests[0].causes[0];
  EXPECT_EQ(named.text, assign.text);
  EXPECT_EQ(named.why, assign.why);
  EXPECT_EQ(named.example, assign.example);
  EXPECT_TRUE(named.likely);
  EXPECT_FALSE(tests[0].causes[1].likely);  // `unknown` is recognised by guessing only
  EXPECT_TRUE(tests[0].causes[2].text.empty() && tests[0].causes[2].why.empty());
}

}  // namespace
}  // namespace clothref::grader
