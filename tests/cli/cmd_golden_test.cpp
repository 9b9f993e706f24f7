// `clothref golden`: exit codes, the per-entry report, where the golden set is found, and that
// --update never creates a set unasked (tools/clothref/cmd_golden.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "clothref/golden/golden.h"
#include "test_util.h"

namespace clothref {
namespace {

// The CLI prints each mismatch and a count line and exits 1. A manifest that lists nothing makes
// every entry of the golden set a mismatch without simulating anything.
TEST(GoldenCli, MismatchExitsOneAndPrintsEachEntry) {
  const test::TempDir root;
  test::writeText(root.path() / "manifest.json", manifestText(GoldenSet{}));
  const test::CommandResult result = test::runCli("golden --golden " + root.path().string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  const std::string& out = result.output;
  auto has = [&out](const std::string& text) { return out.find(text) != std::string::npos; };
  EXPECT_TRUE(has("MISMATCH scene  scenes/course2022.json: golden scene file missing")) << out;
  EXPECT_TRUE(
      has("MISMATCH trace  traces/course2022.rk4.jsonl (course2022 rk4 float dt=0.0001 "
          "5000 steps stride 500): in the golden set this code defines but not in the "
          "manifest (run --update)"))
      << out;
  EXPECT_TRUE(
      has("MISMATCH hashes course2022 explicit float dt=0.0001 10000 steps: in the golden "
          "set this code defines but not in the manifest"))
      << out;
  const GoldenSet& set = goldenSet();
  const int entries = int(set.scenes.size() + set.traces.size() + set.hash_runs.size());
  EXPECT_TRUE(
      has(fmt::format("clothref golden: 0 of {} entries match, {} mismatch", entries, entries)))
      << out;
}

TEST(GoldenCli, BadInputExitsTwo) {
  const test::TempDir root;
  const test::CommandResult missing = test::runCli("golden --golden " + root.file("none"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("golden directory not found"), std::string::npos) << missing.output;

  test::writeText(root.path() / "manifest.json",
                  "{\"format\": \"clothref-golden\", \"version\": 1,");
  const test::CommandResult malformed = test::runCli("golden --golden " + root.path().string());
  EXPECT_EQ(malformed.exit_code, 2);
  EXPECT_NE(malformed.output.find("manifest.json: /version: not valid JSON (line 1, column 44)"),
            std::string::npos)
      << malformed.output;

  // --update --create under a path that is a regular file: one line, exit 2 (was an uncaught
  // filesystem_error, so an abort). --create: without it the missing set is refused before any
  // write, and the case would not reach the filesystem at all.
  test::writeText(root.path() / "plain-file", "x");
  const test::CommandResult under_file =
      test::runCli("golden --update --create --golden " + root.file("plain-file") + "/golden");
  EXPECT_EQ(under_file.exit_code, 2) << under_file.output;
  EXPECT_EQ(under_file.output.rfind("clothref: " + root.file("plain-file"), 0), 0u)
      << under_file.output;
  EXPECT_NE(under_file.output.find("golden: cannot create the directory: Not a directory"),
            std::string::npos)
      << under_file.output;
  EXPECT_EQ(std::count(under_file.output.begin(), under_file.output.end(), '\n'), 1)
      << under_file.output;

  // a number too large for a double in the tolerance file
  test::writeText(root.path() / "tolerances.json", "{\"default\": {\"abs\": 1e400}}");
  const test::CommandResult huge = test::runCli("golden --golden " + root.file("none") +
                                                " --tolerances " + root.file("tolerances.json"));
  EXPECT_EQ(huge.exit_code, 2) << huge.output;
  EXPECT_NE(huge.output.find("tolerances.json: /default/abs: not valid JSON"), std::string::npos)
      << huge.output;
}

// The golden directory defaults to the source tree's (recorded at configure time), so a run from
// any working directory checks the real data; --update never makes a new set without --create.
TEST(GoldenCli, DefaultDirectoryIsTheSourceTreesAndUpdateNeverCreatesASetUnasked) {
  const test::CommandResult help = test::runCli("golden --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find(std::string(CLOTHREF_SOURCE_DIR) + "/golden"), std::string::npos)
      << help.output;

  const test::TempDir root;
  const test::CommandResult update = test::runCli("golden --update --dir " + root.file("new"));
  EXPECT_EQ(update.exit_code, 2) << update.output;
  EXPECT_NE(update.output.find("--update --create"), std::string::npos) << update.output;
  EXPECT_FALSE(std::filesystem::exists(root.file("new")));
  const test::CommandResult alias = test::runCli("golden --update --golden " + root.file("new"));
  EXPECT_EQ(alias.exit_code, 2) << alias.output;
  EXPECT_FALSE(std::filesystem::exists(root.file("new")));

  const test::CommandResult create_alone =
      test::runCli("golden --create --dir " + root.file("new"));
  EXPECT_EQ(create_alone.exit_code, 2) << create_alone.output;
  EXPECT_FALSE(std::filesystem::exists(root.file("new")));
}

// manifest.json that is a directory or a FIFO is named as such (it was "no manifest.json"; a
// FIFO is never opened, so nothing blocks).
TEST(GoldenCli, ManifestThatIsNotAFileIsNamed) {
  const test::TempDir root;
  std::filesystem::create_directories(root.path() / "dir" / "manifest.json");
  std::filesystem::create_directories(root.path() / "fifo");
  ASSERT_EQ(::mkfifo((root.path() / "fifo" / "manifest.json").c_str(), 0600), 0);
  for (const auto& [sub, kind] : {std::pair{"dir", "a directory"}, std::pair{"fifo", "a FIFO"}}) {
    for (const std::string update : {"", " --update"}) {
      const test::CommandResult run = test::runCli("golden" + update + " --dir " + root.file(sub));
      EXPECT_EQ(run.exit_code, 2) << run.output;
      EXPECT_EQ(run.output, "clothref: " + root.file(sub) + "/manifest.json: " + kind +
                                ", not a regular file\n");
    }
  }
}

// `--update --create` that runs out of disk (a file-size limit in the child: writes fail with
// EFBIG) leaves no golden files without a manifest: it used to leave the scenes it had written.
TEST(GoldenCli, CreateOnAFullDiskLeavesNoSetWithoutAManifest) {
  const test::TempDir root;
  const test::ProcessResult run = test::runCliDirect(
      {"golden", "--update", "--create", "--dir", root.file("new")}, root.path(), "", 0, 100'000);
  EXPECT_EQ(run.exit_code, 2) << run.stderr_text;
  EXPECT_NE(run.stderr_text.find("write failed"), std::string::npos) << run.stderr_text;
  EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1) << run.stderr_text;
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root.path() / "new"))
    if (!entry.is_directory()) left.push_back(entry.path().string());
  EXPECT_EQ(left, std::vector<std::string>{});
}

// A manifest path with escape codes is printed escaped (it used to reach the terminal raw).
TEST(GoldenCli, ControlCharactersInManifestPathsAreEscaped) {
  const test::TempDir root;
  GoldenSet manifest;
  manifest.traces.push_back(goldenSet().traces.front());
  manifest.traces.back().file =
      "traces/\x1b[2J\xc2\x9b"
      "1m.jsonl";
  test::writeText(root.path() / "manifest.json", manifestText(manifest));
  const test::CommandResult run = test::runCli("golden --dir " + root.path().string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("MISMATCH trace  traces/\\x1b[2J\\u009b1m.jsonl ("), std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find('\x1b'), std::string::npos);
  EXPECT_EQ(run.output.find("\xc2\x9b"), std::string::npos);
}

}  // namespace
}  // namespace clothref
