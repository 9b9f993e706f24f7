// The number of course stubs the documents state is the grader's: a stub counts in an edition
// when the course gives it points there (stubTable(), tools/grader/grade/results.h), eight in 2022
// and seven in 2024 today. README.md says both ("The eight course stubs (seven in 2024)"), and
// every "the N stubs" or "N course stubs" of a document of the repository is the 2022 count, or
// the 2024 count with 2024 named beside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

constexpr std::array<const char*, 13> kWords = {"zero", "one",    "two",   "three", "four",
                                                "five", "six",    "seven", "eight", "nine",
                                                "ten",  "eleven", "twelve"};

int stubsIn(int edition) {
  int n = 0;
  for (const grader::StubInfo& info : grader::stubTable())
    n += (edition == 2024 ? info.points_2024 : info.points_2022) > 0;
  return n;
}

// "eight" -> 8, "8" -> 8; -1 for anything else.
int countOf(std::string word) {
  std::transform(word.begin(), word.end(), word.begin(), ::tolower);
  for (std::size_t k = 0; k < kWords.size(); ++k)
    if (word == kWords[k]) return static_cast<int>(k);
  if (word.empty() || word.size() > 3 || !std::all_of(word.begin(), word.end(), ::isdigit))
    return -1;
  return std::stoi(word);
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string out;
  for (char c : text.str()) out += c == '\n' ? ' ' : c;  // a sentence wrapped in the source
  return out;
}

// The stated counts of `text` that are wrong, as "the seven stubs (...)".
std::vector<std::string> wrongCounts(const std::string& text, int n2022, int n2024) {
  static const std::regex kCount(
      R"(\b(?:the|all|of the|each of the)\s+(\w+)\s+(?:course\s+|graded\s+)?stubs\b|\b(\w+)\s+course\s+stubs\b)",
      std::regex::icase);
  std::vector<std::string> wrong;
  for (std::sregex_iterator m(text.begin(), text.end(), kCount), end; m != end; ++m) {
    const std::string word = (*m)[1].matched ? (*m)[1].str() : (*m)[2].str();
    const int n = countOf(word);
    // "the course stubs"; "the 30 stubs that changed" counts something else
    if (n < 0 || n >= static_cast<int>(kWords.size())) continue;
    // the words around it (40 characters each way, within its sentence) name the edition of the
    // 2024 count
    const std::size_t at = static_cast<std::size_t>(m->position(0));
    const std::size_t after = at + static_cast<std::size_t>(m->length(0));
    std::size_t from = at < 40 ? 0 : at - 40;
    const std::size_t stop = text.rfind(". ", at);
    if (stop != std::string::npos && stop + 2 > from) from = stop + 2;
    std::string around = text.substr(from, after - from + 40);
    around = around.substr(0, std::min(around.size(), around.find(". ", after - from)));
    const bool ok = n == n2022 || (n == n2024 && around.find("2024") != std::string::npos);
    if (!ok) wrong.push_back(m->str(0));
  }
  return wrong;
}

TEST(StubCounts, TheCodeCountsEightIn2022AndSevenIn2024) {
  // what the documents are held to: a change of the table shows here first
  EXPECT_EQ(stubsIn(2022), 8);
  EXPECT_EQ(stubsIn(2024), 7);
}

TEST(StubCounts, TheReadmeStatesBothCountsFromTheCode) {
  const int n2022 = stubsIn(2022), n2024 = stubsIn(2024);
  ASSERT_LT(n2022, static_cast<int>(kWords.size()));
  const std::string readme = readFile(fs::path(CLOTHREF_SOURCE_DIR) / "README.md");
  const std::string both =
      std::string(kWords[n2022]) + " course stubs (" + kWords[n2024] + " in 2024)";
  EXPECT_NE(readme.find(both), std::string::npos) << "README.md does not say '" << both << "'";
}

TEST(StubCounts, EveryDocumentStatesTheCountsOfTheCode) {
  const fs::path root = CLOTHREF_SOURCE_DIR;
  const int n2022 = stubsIn(2022), n2024 = stubsIn(2024);
  int documents = 0;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind("build", 0) == 0 || name.rfind(".", 0) == 0)) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->path().extension() != ".md") continue;
    ++documents;
    for (const std::string& wrong : wrongCounts(readFile(it->path()), n2022, n2024))
      ADD_FAILURE() << fs::relative(it->path(), root).string() << ": '" << wrong
                    << "': the grader has " << n2022 << " stubs in 2022, " << n2024
                    << " in 2024 (a count of 2024 names the edition)";
  }
  EXPECT_GE(documents, 15);
}

// The TA's quick start (docs/grading.md) is short, states both counts as the README does, and its
// table of default points is the code's (stubTable()), with their sum.
TEST(StubCounts, TheQuickStartStatesTheCountsAndPointsOfTheCode) {
  const fs::path guide = fs::path(CLOTHREF_SOURCE_DIR) / "docs" / "grading.md";
  std::ifstream in(guide);
  ASSERT_TRUE(in) << guide;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  EXPECT_LE(lines.size(), 300u) << "docs/grading.md is a quick start: the rest goes to "
                                   "docs/grading-reference.md";
  const std::string text = readFile(guide);
  const std::string both =
      std::string(kWords[stubsIn(2022)]) + " course stubs (" + kWords[stubsIn(2024)] + " in 2024)";
  EXPECT_NE(text.find(both), std::string::npos) << "docs/grading.md does not say '" << both << "'";
  // "| `Cloth::initializeSpring` | 15 | 10 |": a row per stub, "—" where the edition has none
  const auto shown = [](double points) {
    if (points == 0) return std::string("\xE2\x80\x94");
    std::ostringstream out;
    out << points;
    return out.str();
  };
  double total_2022 = 0, total_2024 = 0;
  for (const grader::StubInfo& info : grader::stubTable()) {
    const std::string row = std::string("| `") + info.name + "` | " + shown(info.points_2022) +
                            " | " + shown(info.points_2024) + " |";
    EXPECT_EQ(std::count(lines.begin(), lines.end(), row), 1) << "docs/grading.md lacks " << row;
    total_2022 += info.points_2022;
    total_2024 += info.points_2024;
  }
  ASSERT_EQ(total_2022, total_2024);
  std::ostringstream sum;
  sum << "code part, " << total_2022 << " in both editions";
  EXPECT_NE(text.find(sum.str()), std::string::npos)
      << "docs/grading.md does not say '" << sum.str() << "'";
}

// The checker: a wrong count, the 2024 count without its edition, is caught; the right ones and
// counts of something else are not.
TEST(StubCounts, TheCheckerCatchesAWrongCount) {
  EXPECT_EQ(wrongCounts("It probes each of the seven stubs. The eight course stubs (seven in "
                        "2024) are ours. Three stubs had a cause. The 30 stubs changed. Of the "
                        "seven stubs of 2024, two failed. The course stubs.",
                        8, 7),
            (std::vector<std::string>{"each of the seven stubs"}));
}

}  // namespace
}  // namespace clothref
