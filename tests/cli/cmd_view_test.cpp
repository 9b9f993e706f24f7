// `clothref view`: the page it writes (self-contained, data embedded, names escaped), the first
// difference it marks against `clothref diff`'s, standard input and gzip, and bad input, from the
// outside (tools/clothref/cmd_view.cpp). The page in a real browser: tests/browser/.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

// The viewer data embedded in a page written by clothref view.
nlohmann::json pageData(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"viewer-data\">";
  const std::size_t begin = page.find(open);
  if (begin == std::string::npos) return nullptr;
  const std::size_t end = page.find("</script>", begin);
  if (end == std::string::npos) return nullptr;
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

std::string trace(const test::TempDir& dir, const std::string& name, const std::string& args) {
  const std::string path = dir.file(name);
  const auto result = test::runCli("trace -q " + args + " -o " + path);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return path;
}

TEST(ViewCli, OneTraceIsASelfContainedPage) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl.gz", "--steps 200 --stride 10");
  const auto result = test::runCli("view " + a + " -o " + dir.file("view.html"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("21 frames of 21 recorded steps"), std::string::npos)
      << result.output;
  const std::string page = test::readText(dir.file("view.html"));
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  // nothing fetched from anywhere: no URL and a policy that forbids every load
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_NE(page.find("default-src 'none'"), std::string::npos);
  EXPECT_NE(page.find("function mountViewer"), std::string::npos);
  const nlohmann::json data = pageData(page);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["recorded"], 21);
  ASSERT_EQ(data["frame_steps"].size(), 21u);
  EXPECT_EQ(data["frame_steps"][20], 200);
  EXPECT_EQ(data["cloth_mesh"]["grid"], 25);
  EXPECT_EQ(data["sphere_radii"].size(), 4u);
  ASSERT_EQ(data["positions"].size(), 1u);
  // 21 frames of 625 + 4 particles, 3 float32 each, in base64
  EXPECT_EQ(data["positions"][0].get<std::string>().size(),
            std::size_t((21 * 629 * 12 + 2) / 3 * 4));
  EXPECT_FALSE(data.contains("first_difference"));
}

TEST(ViewCli, MarksTheFirstDifferenceThatDiffReports) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --integrator rk4 --steps 1000");
  const std::string b = trace(dir, "b.jsonl", "--scene spring --integrator midpoint --steps 1000");
  const auto diff = test::runCli("diff --json " + a + " " + b, test::Capture::StdoutOnly);
  ASSERT_EQ(diff.exit_code, 1) << diff.output;
  const auto report = nlohmann::json::parse(diff.output);
  const auto result = test::runCli("view " + a + " " + b + " -o " + dir.file("view.html"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json data = pageData(test::readText(dir.file("view.html")));
  ASSERT_TRUE(data.is_object());
  ASSERT_TRUE(data["first_difference"].is_object()) << data.dump();
  EXPECT_EQ(data["first_difference"]["step"], report["first_beyond"]["step"]) << report.dump();
  EXPECT_NE(result.output.find("first difference at step " + report["first_beyond"]["step"].dump()),
            std::string::npos)
      << result.output;
  EXPECT_GT(data["largest_difference"].get<double>(), 0);
  EXPECT_EQ(data["difference"]["steps"].size(), 11u);
  EXPECT_EQ(data["cloth_mesh"]["springs"], nlohmann::json({0, 1}));
}

TEST(ViewCli, SameTraceTwiceHasNoDifference) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--steps 100 --stride 20");
  const auto result = test::runCli("view " + a + " " + a + " -o " + dir.file("view.html"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("the traces' states are identical"), std::string::npos);
  const nlohmann::json data = pageData(test::readText(dir.file("view.html")));
  ASSERT_TRUE(data.is_object());
  EXPECT_TRUE(data["first_difference"].is_null());
  EXPECT_EQ(data["largest_difference"], 0.0);
}

TEST(ViewCli, DecimatesToMaxFramesKeepingTheFirstDifference) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--steps 300 --stride 1");
  // explicit and symplectic Euler agree for the first steps, then part
  const std::string b = trace(dir, "b.jsonl", "--steps 300 --stride 1 --integrator symplectic");
  const auto diff = test::runCli("diff --json " + a + " " + b, test::Capture::StdoutOnly);
  const auto report = nlohmann::json::parse(diff.output);
  const auto result =
      test::runCli("view --max-frames 4 " + a + " " + b + " -o " + dir.file("view.html"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json data = pageData(test::readText(dir.file("view.html")));
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["recorded"], 301);
  const auto& steps = data["frame_steps"];
  ASSERT_GE(steps.size(), 4u);
  EXPECT_LE(steps.size(), 5u);
  EXPECT_EQ(steps.front(), 0);
  EXPECT_EQ(steps.back(), 300);
  const auto first = report["first_beyond"]["step"];
  EXPECT_NE(std::find(steps.begin(), steps.end(), first), steps.end())
      << "first difference " << first << " not among the frames " << steps.dump();
  EXPECT_EQ(data["first_difference"]["step"], first);
}

TEST(ViewCli, ReadsStandardInputAndEscapesNames) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --steps 50");
  const std::string out = dir.file("view.html");
  const auto result = test::runCli(
      "view - --labels '</script><script>alert(1)</script>' "
      "--title '<b>&' -q -o " +
      out + " < " + a);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output, "");
  const std::string page = test::readText(out);
  EXPECT_EQ(page.find("<script>alert(1)"), std::string::npos);
  EXPECT_EQ(page.find("<b>&"), std::string::npos);
  EXPECT_NE(page.find("&lt;b&gt;&amp;"), std::string::npos);
  const nlohmann::json data = pageData(page);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["traces"][0]["label"], "</script><script>alert(1)</script>");
  EXPECT_EQ(data["traces"][0]["path"], "standard input");
}

TEST(ViewCli, BadInputIsOneLineAndNoPage) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --steps 50");
  const std::string c = trace(dir, "c.jsonl", "--steps 10");
  const std::string out = dir.file("view.html");
  const struct {
    std::string args, message;
  } cases[] = {
      {dir.file("missing.jsonl"), "missing.jsonl"},
      {a + " " + c, "c.jsonl: bodies (cloth 625, spheres 4) differ from"},
      {"- -", "standard input can be read once"},
      {a + " --labels x y", "--labels: give one label per trace"},
      {a + " --max-frames 1", "--max-frames: must be 0 (automatic) or >= 2"},
      {a, "-o: an output file is required"},
  };
  for (const auto& c : cases) {
    const bool has_output = c.message.rfind("-o:", 0) != 0;
    const auto result =
        test::runCli("view " + c.args + (has_output ? " -o " + out : "") + " < /dev/null");
    EXPECT_EQ(result.exit_code, 2) << c.args << ": " << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

// Two traces whose steps are not the same times (dt 1e-3 and 2e-3) are refused, not compared
// step by step: step 10 is 0.01 s in one and 0.02 s in the other.
TEST(ViewCli, TracesWithDifferentDtAreRefused) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --steps 20 --dt 0.001");
  const std::string b = trace(dir, "b.jsonl", "--scene spring --steps 20 --dt 0.002");
  const auto result = test::runCli("view " + a + " " + b + " -o " + dir.file("view.html"));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("b.jsonl: dt 0.002 s differs from"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("not the same time"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(dir.file("view.html")));
}

// A 1 kB trace whose header claims 10^12 steps: refused at once where the file ends ("trace ends
// after step 0", diff's rule), within an address space of 1 GB; nothing is allocated for the
// claim (it was: out of memory after 9 s).
TEST(ViewCli, BoundedByWhatItReadsNotByTheHeadersClaim) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --steps 10");
  std::istringstream in(test::readText(a));
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  nlohmann::json json = nlohmann::json::parse(header);
  json["steps"] = 1000000000000LL;
  json["stride"] = 1;
  test::writeText(dir.file("claim.jsonl"), json.dump() + "\n" + first + "\n");
  ASSERT_LT(fs::file_size(dir.file("claim.jsonl")), 2000u);
  for (const std::string& pair : {std::string(), dir.file("claim.jsonl")}) {
    std::vector<std::string> args = {"view", dir.file("claim.jsonl")};
    if (!pair.empty()) args.push_back(pair);
    args.insert(args.end(), {"-o", dir.file("view.html")});
    const auto start = std::chrono::steady_clock::now();
    const test::ProcessResult run = test::runCliDirect(args, dir.path(), "", 1ull << 30);
    EXPECT_EQ(run.exit_code, 2) << run.stderr_text;
    EXPECT_NE(run.stderr_text.find("trace ends after step 0"), std::string::npos)
        << run.stderr_text;
    EXPECT_EQ(run.stderr_text.find("out of memory"), std::string::npos) << run.stderr_text;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    EXPECT_LT(run.max_rss_kb, 200 * 1024) << "KiB";
  }
  EXPECT_FALSE(fs::exists(dir.file("view.html")));
}

// Strides 3 and 2 over 10 steps meet at steps 0, 6 and 10 (the last step is always recorded):
// the frames counted from the headers are the steps the files hold.
TEST(ViewCli, DifferentStridesMeetAtTheirCommonSteps) {
  const test::TempDir dir;
  const std::string a = trace(dir, "a.jsonl", "--scene spring --steps 10 --stride 3");
  const std::string b = trace(dir, "b.jsonl", "--scene spring --steps 10 --stride 2");
  for (const char* frames : {"0", "2"}) {
    const auto result = test::runCli("view --max-frames " + std::string(frames) + " " + a + " " +
                                     b + " -o " + dir.file("view.html"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json data = pageData(test::readText(dir.file("view.html")));
    ASSERT_TRUE(data.is_object());
    EXPECT_EQ(data["recorded"], 3);
    EXPECT_EQ(data["difference"]["steps"], nlohmann::json({0, 6, 10}));
    EXPECT_EQ(data["frame_steps"],
              std::string(frames) == "2" ? nlohmann::json({0, 10}) : nlohmann::json({0, 6, 10}));
  }
}

}  // namespace
}  // namespace clothref
