// `clothref view`: the page it writes (self-contained, data embedded, names escaped), the first
// difference it marks against `clothref diff`'s, standard input and gzip, and bad input, from the
// outside (tools/clothref/cmd_view.cpp). The page in a real browser: tests/browser/.
#include <gtest/gtest.h>

#include <filesystem>
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

}  // namespace
}  // namespace clothref
