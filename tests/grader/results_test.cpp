// The stub table (grade/results.h, stubTable()) is the one list of the graded stubs: the files
// outside C++ that list them by hand (the expected.json schema, the corpus scripts, the browser
// test's fixture) must list exactly its names, in its order.
#include "grader/grade/results.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace clothref::grader {
namespace {

const std::filesystem::path kRoot = CLOTHREF_SOURCE_DIR;

std::string read(const std::filesystem::path& relative) {
  std::ifstream in(kRoot / relative, std::ios::binary);
  EXPECT_TRUE(in) << relative;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The quoted strings of `text` (either quote), in order.
std::vector<std::string> quotedStrings(const std::string& text) {
  static const std::regex string(R"re("([^"]*)"|'([^']*)')re");
  std::vector<std::string> found;
  for (std::sregex_iterator it(text.begin(), text.end(), string), end; it != end; ++it)
    found.push_back((*it)[1].matched ? (*it)[1].str() : (*it)[2].str());
  return found;
}

// The text from `start` up to the first `close` after it ("" when `start` is not found).
std::string between(const std::string& text, const std::string& start, const std::string& close) {
  const std::size_t at = text.find(start);
  if (at == std::string::npos) return "";
  const std::size_t from = at + start.size();
  return text.substr(from, text.find(close, from) - from);
}

// The names of the stubs an edition gives points to (0: every stub), in the table's order.
std::vector<std::string> namesOf(int edition) {
  std::vector<std::string> names;
  for (const StubInfo& info : stubTable())
    if (edition == 0 || (edition == 2024 ? info.points_2024 : info.points_2022) > 0)
      names.push_back(info.name);
  return names;
}

TEST(StubTable, TheExpectedJsonSchemaListsItsNames) {
  const nlohmann::json schema = nlohmann::json::parse(read("tools/grader/expected.schema.json"));
  EXPECT_EQ(schema.at("properties").at("stubs_losing_points").at("items").at("enum"),
            nlohmann::json(namesOf(0)));
}

TEST(StubTable, TheSubmissionCorpusScriptListsItsNames) {
  const std::string script = read("tests/grader/submissions/make_corpus.py");
  // STUBS["2022"] by hand; STUBS["2024"] as 2022's without the stubs 2024 does not grade
  EXPECT_EQ(quotedStrings(between(script, "\"2022\": [", "]")), namesOf(2022));
  const std::vector<std::string> graded_2024 = namesOf(2024);
  std::vector<std::string> dropped;
  for (const std::string& name : namesOf(2022))
    if (std::find(graded_2024.begin(), graded_2024.end(), name) == graded_2024.end())
      dropped.push_back(name);
  const std::vector<std::string> line =
      quotedStrings(between(script, "STUBS[\"2024\"] = [s for s in STUBS[\"2022\"] if", "\n"));
  EXPECT_EQ(line, dropped);
  // STUB_HEAD: each stub's file and head, keyed by its name
  std::vector<std::string> heads;
  std::istringstream block(between(script, "STUB_HEAD = {", "\n}"));
  for (std::string entry; std::getline(block, entry);)
    if (!quotedStrings(entry).empty()) heads.push_back(quotedStrings(entry).front());
  EXPECT_EQ(heads, namesOf(0));
}

TEST(StubTable, TheGeneratedCorpusScriptListsItsNames) {
  const std::string script = read("tests/grader/corpus/make_corpus.py");
  // the S_* constants: four lines of two names each
  static const std::regex constants(R"(\nS_[A-Z]+, S_[A-Z]+ = ([^\n]*))");
  std::vector<std::string> names;
  for (std::sregex_iterator it(script.begin(), script.end(), constants), end; it != end; ++it)
    for (const std::string& name : quotedStrings((*it)[1].str())) names.push_back(name);
  EXPECT_EQ(names, namesOf(0));
}

TEST(StubTable, TheClassPageTestListsItsNames) {
  EXPECT_EQ(quotedStrings(between(read("tests/browser/class_page_test.py"), "\nSTUBS = [", "]")),
            namesOf(0));
}

}  // namespace
}  // namespace clothref::grader
