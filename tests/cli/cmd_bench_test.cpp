// `clothref bench`: the --json schema (the keys, medians as numbers, zero allocations per
// step, the SIMD path it ran) on a short run, and one-line errors with exit 2 for bad input. The
// figures themselves are measured, never asserted.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "clothref/fast/simd_path.h"
#include "test_util.h"

// A sanitizer build keeps its own malloc, and the bench then reports -1 (not measured).
#if defined(__SANITIZE_ADDRESS__)
#define CLOTHREF_BENCH_COUNTS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLOTHREF_BENCH_COUNTS 0
#endif
#endif
#ifndef CLOTHREF_BENCH_COUNTS
#define CLOTHREF_BENCH_COUNTS 1
#endif

namespace clothref {
namespace {

TEST(BenchCommand, JsonHasTheSchema) {
  const test::CommandResult result = test::runCli("bench --json --repetitions 2 --seconds 0.02");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json out = nlohmann::json::parse(result.output);
  EXPECT_EQ(out.at("scene"), "course2022");
  for (const char* method : {"explicit", "implicit", "midpoint", "rk4", "symplectic"}) {
    EXPECT_GT(out.at("step_us").at(method).get<double>(), 0) << method;
    EXPECT_GT(out.at("oracle").at("step_us").at(method).get<double>(), 0) << method;
    EXPECT_EQ(out.at("allocations_per_step").at(method).get<double>(),
              CLOTHREF_BENCH_COUNTS ? 0 : -1)
        << method;
  }
  EXPECT_GT(out.at("spring_ns").get<double>(), 0);
  EXPECT_GT(out.at("collide_ns_per_pair").get<double>(), 0);
  for (const char* n : {"25", "50", "100", "200"}) EXPECT_GT(out.at("spring_ns_by_n").at(n), 0);
  fast::SimdPath path;
  EXPECT_TRUE(fast::parseSimdPath(out.at("simd").get<std::string>(), path));
  EXPECT_EQ(out.at("threads"), 1);
  EXPECT_GE(out.at("threads_n200").at("threads").get<int>(), 2);
}

TEST(BenchCommand, RunsTheRequestedPath) {
  const test::CommandResult result =
      test::runCli("bench --json --repetitions 1 --seconds 0.01 --simd sse2");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(nlohmann::json::parse(result.output).at("simd"), "sse2");
}

TEST(BenchCommand, BadInputIsOneLineAndExitTwo) {
  for (const char* args : {"bench --simd avx9", "bench --repetitions 0", "bench --threads 0",
                           "bench --threads 65", "bench --threads 2000", "bench --seconds -1",
                           "bench --seconds nan", "bench --scene no-such-scene"}) {
    const test::CommandResult result = test::runCli(args);
    EXPECT_EQ(result.exit_code, 2) << args;
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << args << ":\n" << result.output;
  }
}

TEST(BenchCommand, BadSimdEnvironmentIsOneLineAndExitTwo) {
  ::setenv("CLOTHREF_SIMD", "mmx", 1);
  const test::CommandResult result = test::runCli("scenes");
  ::unsetenv("CLOTHREF_SIMD");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("CLOTHREF_SIMD"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find('\n'), result.output.size() - 1) << result.output;
}

TEST(BenchCommand, VersionNamesThePath) {
  const test::CommandResult result = test::runCli("--version");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_NE(result.output.find("simd " + std::string(fast::simdPathName(fast::defaultSimdPath()))),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace clothref
