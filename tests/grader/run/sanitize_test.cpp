// The sanitizer run (grader/grade/run/sanitize.h): finding and cleaning the first sanitizer
// report, and the corpus mutant whose `auto` Eigen expression dangles, rebuilt with ASan by
// itself, quoted in its report.
#include "grader/grade/run/sanitize.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "corpus.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;
using test::readText;
using test::runCli;
using test::TempDir;

int countLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(FirstReport, StartsAtTheErrorLineCutsPathsAndPidsAndStopsAtTheLimit) {
  // The shape of an ASan report, with a scratch path and a process id that must not be quoted.
  std::string log = "probe: starting\n";
  log += "=================================================================\n";
  log += "==4242==ERROR: AddressSanitizer: stack-use-after-scope on address 0x7ffc00 at pc 0x55\n";
  log += "READ of size 16 at 0x7ffc00 thread T0\n";
  for (int k = 0; k < 20; ++k)
    log += "    #" + std::to_string(k) +
           " 0x55 in Cloth::computeSpringForce() /tmp/clothref-grade-Xy12/src-cloth/cloth.cpp:" +
           std::to_string(180 + k) + "\n";
  const std::string quote = firstSanitizerReport(log, 6);
  EXPECT_EQ(countLines(quote), 6) << quote;
  EXPECT_EQ(quote.rfind("==ERROR: AddressSanitizer: stack-use-after-scope", 0), 0u) << quote;
  EXPECT_NE(quote.find("in Cloth::computeSpringForce() cloth.cpp:180\n"), std::string::npos)
      << quote;
  EXPECT_EQ(quote.find("/tmp/"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("4242"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("probe: starting"), std::string::npos) << quote;
}

TEST(FirstReport, AddressesAreNotQuotedSoTwoRunsQuoteTheSameText) {
  // Two runs of one crash differ only in their addresses (address-space layout).
  const auto report = [](const std::string& address, const std::string& pc) {
    return "==1==ERROR: AddressSanitizer: stack-use-after-scope on address " + address + " at pc " +
           pc + "\n    #16 " + pc +
           " in Cloth::computeSpringForce() /tmp/clothref-grade-a/src-cloth/cloth.cpp:194\n";
  };
  const std::string first = firstSanitizerReport(report("0x7ffc985ec210", "0x56368fed9830"), 6);
  const std::string second = firstSanitizerReport(report("0x7fff319fb350", "0x55cee057c830"), 6);
  EXPECT_EQ(first, second);
  EXPECT_NE(first.find("on address 0x... at pc 0x..."), std::string::npos) << first;
  EXPECT_EQ(first.find("7ffc"), std::string::npos) << first;
}

TEST(FirstReport, FramesOutsideTheStudentsFilesAndTheFramesObjectsAreSummarised) {
  std::string log = "==7==ERROR: AddressSanitizer: heap-use-after-free on address 0x6020\n";
  log += "READ of size 4 at 0x6020 thread T0\n";
  for (int k = 0; k < 3; ++k)
    log += "    #" + std::to_string(k) + " 0x55 in Eigen::f() /usr/include/eigen3/Eigen/x.h:1\n";
  log += "    #3 0x55 in Spheres::collide() /tmp/clothref-grade-q/src-sphere/sphere.cpp:40\n";
  log += "    #4 0x55 in main (/tmp/clothref-grade-q/probe+0x1)\n\n";
  log += "  This frame has 3 object(s):\n    [32, 48) 'a'\n";
  log += "    [64, 80) 'b' <== Memory access at offset 64 is inside this variable\n";
  EXPECT_EQ(firstSanitizerReport(log),
            "==ERROR: AddressSanitizer: heap-use-after-free on address 0x6020\n"
            "READ of size 4 at 0x6020 thread T0\n"
            "    ... (3 frames outside the student's files)\n"
            "    #3 0x55 in Spheres::collide() sphere.cpp:40\n"
            "    ... (1 frame outside the student's files)\n"
            "  This frame has 3 object(s):\n"
            "    [64, 80) 'b' <== Memory access at offset 64 is inside this variable\n");
}

TEST(FirstReport, FindsUndefinedBehaviourAndNothingInCleanOutput) {
  const std::string ubsan =
      "hello\n/tmp/clothref-grade-ab/src-integrator/integrator.cpp:12:9: runtime error: signed "
      "integer overflow: 2147483647 + 1 cannot be represented in type 'int'\n";
  EXPECT_EQ(firstSanitizerReport(ubsan),
            "integrator.cpp:12:9: runtime error: signed integer overflow: 2147483647 + 1 cannot be "
            "represented in type 'int'\n");
  EXPECT_EQ(firstSanitizerReport("all tests passed\nSegmentation fault\n"), "");
}

// The corpus mutant force-dangling-auto crashes at -O2: the grader rebuilds it with the
// sanitizers by itself (nothing to ask for) and names the error and the line.
TEST(Sanitize, DanglingAutoExpressionIsQuotedFromAddressSanitizer) {
  TempDir temp;
  const fs::path submission =
      test::materialiseCase("2022/force-dangling-auto", temp.path() / "submission");
  const auto run =
      runCli("grade '" + submission.string() + "' --no-whole-run --timeout 20 --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --report '" + temp.file("report.md") +
             "' --results '" + temp.file("results.json") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string report = readText(temp.file("report.md"));
  EXPECT_NE(report.find("ERROR: AddressSanitizer: stack-use-after-scope"), std::string::npos)
      << report;
  EXPECT_NE(report.find("cloth.cpp:"), std::string::npos) << report;
  EXPECT_EQ(report.find("/src-cloth/"), std::string::npos) << report;
  // In the failed tests of the stub that crashed, where the student reads.
  std::ifstream results_in(temp.file("results.json"));
  const nlohmann::json results = nlohmann::json::parse(results_in);
  bool quoted = false;
  for (const auto& test : results["tests"])
    if (test["tags"][0] == "Cloth::computeSpringForce" && test["status"] == "failed")
      quoted =
          quoted || test["output"].get<std::string>().find("AddressSanitizer") != std::string::npos;
  EXPECT_TRUE(quoted);
}

}  // namespace
}  // namespace clothref::grader
