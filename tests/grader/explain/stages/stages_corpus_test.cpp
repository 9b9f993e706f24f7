// The stage explanation end to end: `clothref grade --keep-work` on each hand-written submission
// (tests/grader/handwritten, written by someone who never read the grader), then each integrator's
// stages.json, the fit of what the student's stub handed to simulateOneStep(), against the hand
// labels. Every stub labelled full is the course's method or an accepted variant stage by stage;
// no likely cause lies outside the label's causes and "also". Prints one table row per stub.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "grader/grade/probes/probes.h"
#include "test_util.h"

namespace clothref::test {
namespace {

namespace fs = std::filesystem;
const fs::path kHandwritten = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "handwritten";
const char* kStubs[] = {"ExplicitEuler::integrate", "ImplicitEuler::integrate",
                        "MidpointEuler::integrate", "RungeKuttaFourth::integrate"};

std::vector<std::string> submissions() {
  std::vector<std::string> names;
  for (const char* edition : {"2022", "2024"}) {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(kHandwritten / edition, error))
      if (fs::exists(entry.path() / "labels.json"))
        names.push_back(std::string(edition) + "/" + entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::string joined(const std::set<std::string>& ids) {
  std::string out;
  for (const auto& id : ids) out += (out.empty() ? "" : ", ") + id;
  return out.empty() ? "-" : out;
}

class Handwritten : public ::testing::TestWithParam<std::string> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Handwritten);

TEST_P(Handwritten, StageExplanationsAgreeWithTheLabels) {
  TempDir temp;
  const fs::path submission = kHandwritten / GetParam();
  const nlohmann::json labels = readJson(submission / "labels.json");
  const fs::path work = temp.path() / "work";
  const CommandResult run =
      runCli("grade '" + submission.string() + "' --no-whole-run --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --keep-work '" + work.string() +
             "' --report '" + temp.file("report.md") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::string table;
  for (int method = 0; method < 4; ++method) {
    const nlohmann::json& label = labels["stubs"][kStubs[method]];
    const bool full = label["verdict"] == "full";
    std::set<std::string> allowed;
    for (const char* field : {"causes", "also"})
      if (label.contains(field))
        for (const auto& id : label[field]) allowed.insert(id.get<std::string>());
    fs::path file = work / "probes" / grader::integratorFolder(method, true) / "stages.json";
    if (!fs::exists(file))
      file = work / "probes" / grader::integratorFolder(method, false) / "stages.json";
    std::string planted = full ? "full" : joined(allowed);
    if (label.contains("why")) planted += " (" + label["why"].get<std::string>() + ")";
    if (!fs::exists(file)) {  // the probe did not answer (a crash): nothing recorded
      table += "| " + GetParam() + " | " + kStubs[method] + " | " + planted +
               " | (no record: the probe did not answer) | - | - |\n";
      EXPECT_FALSE(full) << kStubs[method] << ": a correct stub without a stage record";
      continue;
    }
    const nlohmann::json stages = readJson(file);
    std::set<std::string> likely, possible;
    for (const auto& cause : stages["causes"])
      (cause["likely"].get<bool>() ? likely : possible).insert(cause["id"].get<std::string>());
    std::string said;
    if (stages["course"].get<bool>())
      said = "the course's method, stage by stage";
    else if (!stages["accepted"].get<std::string>().empty())
      said = "accepted variant `" + stages["accepted"].get<std::string>() + "`";
    else {
      const auto& d = stages["departure"];
      const int state = d["state"], recorded = stages["recorded"];
      const std::string where = state > recorded ? "result" : "evaluation " + std::to_string(state);
      said = where + " " + d["what"].get<std::string>() + ": yours " +
             d["yours"].get<std::string>() + ", course's " + d["course"].get<std::string>();
      if (!stages["equals"].get<std::string>().empty())
        said += "; equals `" + stages["equals"].get<std::string>() + "`";
      if (stages["scale"].get<double>() != 1.0)
        said += "; step " + std::to_string(stages["scale"].get<double>()) + "·h";
    }
    said += " [" + std::to_string(stages["calls"].get<int>()) + " calls]";
    table += "| " + GetParam() + " | " + kStubs[method] + " | " + planted + " | " + said + " | " +
             joined(likely) + " | " + joined(possible) + " |\n";
    if (full)
      EXPECT_TRUE(stages["course"].get<bool>() || !stages["accepted"].get<std::string>().empty())
          << kStubs[method] << ": labelled full\n"
          << stages["text"].get<std::string>();
    else
      EXPECT_FALSE(stages["course"].get<bool>() || !stages["accepted"].get<std::string>().empty())
          << kStubs[method] << ": labelled as losing points\n"
          << stages["text"].get<std::string>();
    for (const auto& id : likely)
      EXPECT_TRUE(!full && allowed.count(id))
          << kStubs[method] << ": likely " << id << " contradicts the label\n"
          << stages["text"].get<std::string>();
  }
  std::cout << "| submission | stub | label | stage explanation | likely | possible |\n"
               "|---|---|---|---|---|---|\n"
            << table;
}

INSTANTIATE_TEST_SUITE_P(Submissions, Handwritten, ::testing::ValuesIn(submissions()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace clothref::test
