// `clothref trace`: the summary on stderr, --threads, bad flags and a dt the run's precision
// cannot hold, from the outside (tools/clothref/cmd_trace.cpp).
#include <gtest/gtest.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "clothref/scene/scene.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

TEST(TraceCli, DefaultRunSummarisesOnStderr) {
  const test::TempDir dir;
  const auto result = test::runCli("trace --steps 20 --stride 10 -o " + dir.file("out.jsonl"));
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("clothref trace: course2022 explicit float dt=0.0001: 20 steps"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("state stayed finite"), std::string::npos);
}

// -q: nothing on stderr (no progress, no summary) and the same trace.
TEST(TraceCli, QuietPrintsNothing) {
  const test::TempDir dir;
  const auto result = test::runCli("trace -q --steps 20 --stride 10 -o " + dir.file("out.jsonl"));
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.output, "");
  EXPECT_GT(fs::file_size(dir.file("out.jsonl")), 0u);
}

TEST(TraceCli, ThreadsGiveTheSameBytes) {
  // a 100 x 100 cloth: big enough that the spring sweeps really are split over the threads
  Scene scene = *findBuiltinScene("course2022");
  scene.name = "course2022-100";
  scene.cloth->grid->particles_per_edge = 100;
  scene.cloth->fixed = {0, 99};
  const test::TempDir dir;
  {
    std::ofstream file(dir.file("big.json"));
    file << sceneToJson(scene).dump();
  }
  std::string traces[2];
  for (int threads : {1, 2}) {
    const std::string out = dir.file("t" + std::to_string(threads) + ".jsonl");
    const auto result = test::runCli("trace -q --scene " + dir.file("big.json") +
                                     " --steps 30 --stride 10 --integrator rk4 --threads " +
                                     std::to_string(threads) + " -o " + out);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    std::ifstream in(out);
    traces[threads - 1].assign(std::istreambuf_iterator<char>(in), {});
  }
  EXPECT_GT(traces[0].size(), 100000u);
  EXPECT_TRUE(traces[0] == traces[1]) << "the 2-thread trace differs from the 1-thread one";
  EXPECT_EQ(test::runCli("trace --threads 0 -o " + dir.file("x.jsonl")).exit_code, 2);
}

TEST(TraceCli, BadFlagsExit2WithOneLine) {
  const test::TempDir dir;
  for (const char* args : {"--integrator euler", "--precision half", "--steps -1", "--stride 0",
                           "--dt -1", "--dt nan"}) {
    const auto result = test::runCli(std::string("trace ") + args + " -o " + dir.file("out.jsonl"));
    EXPECT_EQ(result.exit_code, 2) << args;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.jsonl"))) << args;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  }
}

// A dt that is 0 or infinite in the run's precision, and a step count that does not fit, are bad
// input; a run whose t overflows writes a trace clothref reads back.
TEST(TraceCli, RunPrecisionDtAndHugeStepsAreBadInput) {
  const test::TempDir dir;
  const std::string out = " -o " + dir.file("out.jsonl");
  for (const std::string args :
       {"--scene spring --steps 2 --dt 1e39", "--scene spring --steps 2 --dt 1e-50",
        "--scene spring --steps 99999999999999999999", "--scene spring --steps 2000000000000"}) {
    const test::CommandResult run = test::runCli("trace " + args + out);
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_EQ(run.output.rfind("clothref: --", 0), 0u) << run.output;
    EXPECT_FALSE(fs::exists(dir.file("out.jsonl")));
  }
  // in double, 1e39 is fine, and t overflows to infinity at step 2 with dt 1e308
  ASSERT_EQ(
      test::runCli("trace --scene spring --steps 2 --stride 1 --precision double --dt 1e308" + out)
          .exit_code,
      0);
  const test::CommandResult diff =
      test::runCli("diff " + dir.file("out.jsonl") + " " + dir.file("out.jsonl"));
  EXPECT_EQ(diff.exit_code, 0) << diff.output;
}

}  // namespace
}  // namespace clothref
