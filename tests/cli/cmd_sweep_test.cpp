// `clothref sweep`: CSV and JSON outputs, and no output on bad input
// (tools/clothref/cmd_sweep.cpp).
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "test_util.h"

namespace clothref {
namespace {

TEST(SweepCli, WritesCsvAndJson) {
  test::TempDir dir;
  const std::string csv = dir.file("sweep.csv"), json = dir.file("sweep.json");
  const test::CommandResult result = test::runCli(
      "sweep --scene spring --method rk4 --method backward-euler --precision double "
      "--repeats 2 --substeps 10 --substeps 20 --quiet --csv " +
      csv + " --json " + json);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream csv_in(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv_in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);  // header + 2 methods x 2 dts
  EXPECT_EQ(lines[0].rfind("scene,method,precision,dt,", 0), 0u);
  std::ifstream json_in(json);
  const auto data = nlohmann::json::parse(json_in);
  EXPECT_EQ(data["format"], "clothref-sweep");
  ASSERT_EQ(data["points"].size(), 4u);
  EXPECT_EQ(data["points"][0]["runs"], 2);
  EXPECT_TRUE(data["points"][2]["cg_iterations"].is_number());
  EXPECT_TRUE(data.contains("machine"));
  EXPECT_TRUE(data.contains("compiler"));
}

// --peer adds Boost.Odeint's stepper beside each chosen method that has one (rk4 here, not
// backward-euler), on the same ladder
TEST(SweepCli, PeerAddsOdeintBesideItsCounterpart) {
  test::TempDir dir;
  const std::string json = dir.file("sweep.json");
  const test::CommandResult result = test::runCli(
      "sweep --scene spring --method rk4 --method backward-euler --precision double "
      "--repeats 1 --substeps 10 --substeps 20 --peer --quiet --json " +
      json);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream json_in(json);
  const auto data = nlohmann::json::parse(json_in);
  ASSERT_EQ(data["points"].size(), 6u);  // (2 methods + 1 peer) x 2 dts
  for (int k = 0; k < 2; ++k) {
    const auto& ours = data["points"][k];
    const auto& peer = data["points"][4 + k];
    EXPECT_EQ(ours["method"], "rk4");
    EXPECT_EQ(peer["method"], "odeint-rk4");
    EXPECT_EQ(peer["dt"], ours["dt"]);
    EXPECT_EQ(peer["evaluations"], ours["evaluations"]);
    EXPECT_NEAR(peer["error_final"].get<double>(), ours["error_final"].get<double>(), 1e-12);
  }
}

TEST(SweepCli, BadInputLeavesNoOutput) {
  test::TempDir dir;
  const std::string csv = dir.file("sweep.csv");
  for (const std::string& args :
       {"sweep --scene spring --method leapfrog --csv " + csv,
        "sweep --scene spring --repeats 0 --csv " + csv,
        "sweep --scene spring --substeps 0 --csv " + csv,
        "sweep --scene spring --csv " + dir.file("missing/dir/out.csv")}) {
    const test::CommandResult result = test::runCli(args + " --quiet");
    EXPECT_EQ(result.exit_code, 2) << args << ": " << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
    EXPECT_FALSE(std::filesystem::exists(csv)) << args;
  }
}

}  // namespace
}  // namespace clothref
