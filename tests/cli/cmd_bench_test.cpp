// `clothref bench`: the --json schema (the keys, medians as numbers, the SIMD path it ran)
// on a short run, one-line errors with exit 2 for bad input, and a shipped binary that replaces no
// allocator. The figures themselves are measured, never asserted.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "clothref/fast/simd_path.h"
#include "test_util.h"

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
  }
  EXPECT_GT(out.at("spring_ns").get<double>(), 0);
  EXPECT_GT(out.at("collide_ns_per_pair").get<double>(), 0);
  for (const char* n : {"25", "50", "100", "200"}) EXPECT_GT(out.at("spring_ns_by_n").at(n), 0);
  fast::SimdPath path;
  EXPECT_TRUE(fast::parseSimdPath(out.at("simd").get<std::string>(), path));
  EXPECT_EQ(out.at("threads"), 1);
  EXPECT_GE(out.at("threads_n200").at("threads").get<int>(), 2);
  EXPECT_FALSE(out.contains("allocations_per_step"));  // counted by tests, not the shipped binary
}

// An executable that defines malloc (or its relatives) exports it to the dynamic symbol table, so
// glibc and every library of the process call it: `nm -D --defined-only` shows such a hook.
TEST(BenchCommand, TheShippedBinaryReplacesNoAllocator) {
  if (std::system("nm --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "nm (binutils) not found";
  std::string symbols;
  FILE* pipe = ::popen((std::string("nm -D --defined-only '") + CLOTHREF_BIN + "'").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    symbols.append(buffer, n);
  ASSERT_EQ(::pclose(pipe), 0) << symbols;
  ASSERT_FALSE(symbols.empty()) << "nm listed no defined symbols";
  for (const char* name : {"malloc", "calloc", "realloc", "free", "_Znwm", "_ZdlPv"})
    EXPECT_EQ(symbols.find(std::string(" ") + name + "\n"), std::string::npos)
        << name << " is defined";
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
