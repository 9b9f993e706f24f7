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

// The contents of every ordinary string literal of C++ `source` outside comments (raw strings,
// character literals and comments skipped), with the line each starts on.
std::vector<std::pair<int, std::string>> stringLiterals(const std::string& source) {
  std::vector<std::pair<int, std::string>> literals;
  int line = 1;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const char c = source[i];
    if (c == '\n') ++line;
    if (source.compare(i, 2, "//") == 0) {
      while (i < source.size() && source[i] != '\n') ++i;
      ++line;
    } else if (source.compare(i, 2, "/*") == 0) {
      const std::size_t end = source.find("*/", i + 2);
      for (; i < source.size() && i < end; ++i) line += source[i] == '\n';
      ++i;
    } else if (c == 'R' && source.compare(i + 1, 1, "\"") == 0) {  // R"delim( ... )delim"
      const std::size_t open = source.find('(', i);
      const std::string close = ")" + source.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = source.find(close, open);
      for (; i < source.size() && i < end + close.size() - 1; ++i) line += source[i] == '\n';
    } else if (c == '\'' && i + 2 < source.size()) {
      i += source[i + 1] == '\\' ? 3 : 2;
    } else if (c == '"') {
      std::string text;
      for (++i; i < source.size() && source[i] != '"'; ++i) {
        if (source[i] == '\\') text += source[i++];
        text += source[i];
      }
      literals.push_back({line, text});
    }
  }
  return literals;
}

// The grader names a cause only by its constant: a cause id written as a string in its C++ is a
// list kept by hand (and a typo that builds). Checked: tools/grader and the CLI, and the grader's
// tests but this one (which checks the generator against written ids) and those of run/ and
// report/ (their words are verdicts and the child's own text, and their issues rewrite them). A
// line naming a Verdict holds verdict words (verdictTable()), some of which are also cause ids.
TEST(CatalogueIds, NoCauseIdIsWrittenAsAStringInTheGraderOrItsTests) {
  std::set<std::string> ids;
  for (const cause::NamedId& named : cause::namedIds()) ids.insert(named.id);
  const fs::path root = CLOTHREF_SOURCE_DIR;
  int files = 0;
  for (const char* tree : {"tools/grader", "tools/clothref", "tests/grader"})
    for (const auto& entry : fs::recursive_directory_iterator(root / tree)) {
      const std::string path = fs::relative(entry.path(), root).string();
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      bool skipped = false;
      for (const char* part :
           {"tools/grader/course/", "tools/grader/reference/", "tests/grader/submissions/",
            "tests/grader/corpus/", "tests/grader/handwritten/", "tests/grader/adversarial/",
            "tests/grader/run/", "tests/grader/report/", "tests/grader/catalogue_test.cpp"})
        skipped = skipped || path.rfind(part, 0) == 0;
      if (skipped) continue;
      ++files;
      const std::string source = test::readText(entry.path());
      std::vector<std::string> lines;
      std::istringstream in(source);
      for (std::string l; std::getline(in, l);) lines.push_back(l);
      for (const auto& [line, text] : stringLiterals(source)) {
        if (!ids.count(text)) continue;
        const std::string& where = lines[std::size_t(line - 1)];
        if (where.find("Verdict::") != std::string::npos ||
            where.find("verdict") != std::string::npos)
          continue;
        ADD_FAILURE() << path << ":" << line << ": \"" << text << "\" (write cause::"
                      << "k... of grader/grade/cause_ids.h)";
      }
    }
  EXPECT_GT(files, 100);
  // The scan finds one: a literal in code, not in a comment, a raw string or a character.
  const auto found = stringLiterals(
      "f('\"'); // \"crashed\"\nR\"x(\"unknown\")x\";\n"
      "t.addCause(\"backup-alias\");\n");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], (std::pair<int, std::string>{3, "backup-alias"}));
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
      {"mistyped deduction", "\"deduction\": null, \"model\": null, \"text\": \"The file does",
       "\"deduction\": \"none\", \"model\": null, \"text\": \"The file does",
       "/diagnoses/0/deduction: ", "expected a number or null"},
      {"no model", "\"model\": null, \"text\": \"The file does", "\"text\": \"The file does",
       "/diagnoses/0/model: ", "missing"}};
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
