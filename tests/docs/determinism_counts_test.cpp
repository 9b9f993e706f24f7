// The counts docs/determinism.md states for the golden set are the golden manifest's, so they
// cannot go stale when the set grows: the sentence "N scene files, N float traces, N hash runs
// (N step hashes in all), N entries" and every "X of Y match" of the section "## Measured" (before
// its first "###" subsection, which keeps measurements of earlier sets) are read from the document
// and compared with golden/manifest.json.
#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

namespace clothref {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Line breaks and runs of spaces as one space, so a sentence wrapped in the source still matches.
std::string oneLine(const std::string& text) {
  std::string out;
  for (char c : text) {
    const char d = (c == '\n' || c == '\t') ? ' ' : c;
    if (d == ' ' && !out.empty() && out.back() == ' ') continue;
    out += d;
  }
  return out;
}

// "168 090" -> 168090 (the document groups digits with spaces).
std::size_t number(std::string digits) {
  std::erase(digits, ' ');
  return std::stoul(digits);
}

struct Counts {
  std::size_t scenes = 0, traces = 0, float_traces = 0, hash_runs = 0, hashes = 0;
  std::size_t entries() const { return scenes + traces + hash_runs; }
};

Counts manifestCounts() {
  const std::string path = std::string(CLOTHREF_SOURCE_DIR) + "/golden/manifest.json";
  const nlohmann::json manifest = nlohmann::json::parse(readFile(path));
  Counts counts;
  counts.scenes = manifest.at("scenes").size();
  counts.traces = manifest.at("traces").size();
  for (const auto& trace : manifest.at("traces"))
    if (trace.at("precision").get<std::string>() == "float") ++counts.float_traces;
  counts.hash_runs = manifest.at("hash_runs").size();
  for (const auto& run : manifest.at("hash_runs")) counts.hashes += run.at("hashes").size();
  return counts;
}

class DeterminismDoc : public ::testing::Test {
 protected:
  void SetUp() override {
    counts_ = manifestCounts();
    // a set this small would mean the manifest was not read: the checks below would be vacuous
    ASSERT_GE(counts_.scenes, 1u);
    ASSERT_GE(counts_.traces, 1u);
    ASSERT_GE(counts_.hash_runs, 1u);
    text_ = oneLine(readFile(std::string(CLOTHREF_SOURCE_DIR) + "/docs/determinism.md"));
    ASSERT_FALSE(text_.empty());
  }
  Counts counts_;
  std::string text_;
};

TEST_F(DeterminismDoc, StatesTheGoldenSetsCountsFromTheManifest) {
  // the sentence names float traces only: a double trace in the set needs the sentence to say so
  EXPECT_EQ(counts_.float_traces, counts_.traces) << "the manifest has non-float traces";
  const std::regex sentence(
      R"((\d+) scene files, (\d+) float traces, (\d+) hash runs \(([\d ]+) step hashes in all\), (\d+) entries)");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(text_, match, sentence))
      << "docs/determinism.md does not state the golden set's counts in the expected form";
  ASSERT_EQ(match.size(), 6u);
  EXPECT_EQ(number(match[1]), counts_.scenes) << "scene files";
  EXPECT_EQ(number(match[2]), counts_.float_traces) << "float traces";
  EXPECT_EQ(number(match[3]), counts_.hash_runs) << "hash runs";
  EXPECT_EQ(number(match[4]), counts_.hashes) << "step hashes";
  EXPECT_EQ(number(match[5]), counts_.entries()) << "entries";
}

TEST_F(DeterminismDoc, MeasuredRowsCountTheWholeCurrentSet) {
  const std::size_t begin = text_.find("## Measured");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = text_.find("### ", begin);
  const std::string section = text_.substr(begin, end == std::string::npos ? end : end - begin);
  const std::regex result(R"((\d+) of (\d+) match)");
  int rows = 0;
  for (auto it = std::sregex_iterator(section.begin(), section.end(), result);
       it != std::sregex_iterator(); ++it, ++rows)
    EXPECT_EQ(number((*it)[2]), counts_.entries()) << (*it)[0];
  EXPECT_GE(rows, 3) << "the section lists fewer results than expected";
}

}  // namespace
}  // namespace clothref
