// Compiles and links as child processes (grader/grade/run/tools.h): results in command order,
// time, memory and file-size limits, and the fallback's confinement (the tool uid, our folders
// covered).
#include "grader/grade/run/tools.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

TEST(RunTools, ResultsInCommandOrder) {
  test::TempDir temp;
  const auto runs =
      runTools({{"/bin/sh", "-c", "sleep 0.2; echo one"}, {"/bin/sh", "-c", "echo two; exit 1"}},
               temp.path(), 2, 10);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_TRUE(runs[0].ok);
  EXPECT_EQ(runs[0].output, "one\n");
  EXPECT_FALSE(runs[1].ok);
}

// A compile bomb (a 10 GB constexpr table, `#include "/dev/zero"`) meets these limits.
TEST(RunTools, CompilesHaveTimeAndMemoryLimits) {
  test::TempDir temp;
  const auto runs =
      runTools({{"/bin/sh", "-c", "ulimit -v; ulimit -t; ulimit -f"}}, temp.path(), 1, 30);
  ASSERT_TRUE(runs[0].ok) << runs[0].output;
  EXPECT_EQ(runs[0].output, std::to_string(kToolAddressSpace >> 10) + "\n31\n" +
                                std::to_string(kToolFileSize >> 9) + "\n");  // KiB, s, blocks
  const auto slow = runTools({{"/bin/sh", "-c", "sleep 30"}}, temp.path(), 1, 0.3);
  EXPECT_FALSE(slow[0].ok);
  EXPECT_NE(slow[0].output.find("stopped after"), std::string::npos);
}

// A failed compile whose log looks empty at its start (a #line that renames the file to thousands
// of newlines) is the compiler's verdict on the student's code, judged by its exit status and the
// raw bytes of its log, never a silent failure of ours (issue 36: the grade stopped with
// "unexpected error"). A tool that fails without writing a byte is ours, tried again, then ours.
TEST(RunTools, AFailedCompileWithALogOfBlankLinesIsTheStudents) {
  test::TempDir temp;
  test::writeText(temp.path() / "renamed.cpp",
                  "#line 1 \"" + std::string(6000, 'N') + "cloth.cpp\"\nint x = 1 int y;\n");
  std::string renamed = test::readText(temp.path() / "renamed.cpp");
  for (std::size_t at = 0; (at = renamed.find('N', at)) != std::string::npos;)
    renamed.replace(at, 1, "\\n");
  test::writeText(temp.path() / "renamed.cpp", renamed);
  const auto runs = runTools({{"g++", "-c", (temp.path() / "renamed.cpp").string(), "-o",
                               (temp.path() / "renamed.o").string()},
                              {"/bin/sh", "-c", "exit 1"}},
                             temp.path(), 1, 60);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_FALSE(runs[0].ok);
  EXPECT_FALSE(runs[0].ours) << runs[0].output.substr(0, 300);
  EXPECT_NE(runs[0].output.find("error: expected"), std::string::npos)
      << runs[0].output.substr(0, 300);
  EXPECT_FALSE(runs[1].ok);
  EXPECT_TRUE(runs[1].ours);
}

// In the fallback (no bubblewrap) a compile runs as the tool uid in a private mount namespace:
// `.incbin` of a host file only root may read fails, and so does an #include from one of the
// grader's hidden folders (our reference) the command does not name. Without the confinement the
// same two commands compile, so the test sees the difference.
TEST(RunTools, FallbackCompilesCannotReadHostFilesNorHiddenFolders) {
  if (geteuid() != 0) GTEST_SKIP() << "the compile uid drop needs root";
  test::TempDir temp;
  const fs::path secret = temp.path() / "secret.txt";
  test::writeText(secret, "SECRET-HOST-BYTES\n");
  fs::permissions(secret, fs::perms::owner_read | fs::perms::owner_write);
  const fs::path hidden = temp.path() / "reference";
  fs::create_directories(hidden);
  test::writeText(hidden / "ref.h", "int reference_value = 1;\n");
  const fs::path work = temp.path() / "work";
  fs::create_directories(work);
  test::writeText(work / "incbin.cpp", "asm(\".incbin \\\"" + secret.string() + "\\\"\");\n");
  test::writeText(work / "include.cpp", "#include \"" + (hidden / "ref.h").string() + "\"\n");
  const std::vector<std::vector<std::string>> commands = {
      {"g++", "-c", (work / "incbin.cpp").string(), "-o", (work / "incbin.o").string()},
      {"g++", "-c", (work / "include.cpp").string(), "-o", (work / "include.o").string()}};
  const auto open = runTools(commands, work, 2, 60);
  ASSERT_EQ(open.size(), 2u);
  EXPECT_TRUE(open[0].ok) << open[0].output;
  EXPECT_TRUE(open[1].ok) << open[1].output;
  Isolation isolation;
  isolation.kind = IsolationKind::Rlimits;
  const UidLease lease = leaseUids();
  isolation.tool_uid = lease.tool_uid;
  isolation.private_mounts = whyNoPrivateMountNamespace().empty();
  isolation.ours = {hidden};
  fs::remove(work / "incbin.o");
  fs::remove(work / "include.o");
  const auto confined = runTools(commands, work, 2, 60, &isolation);
  ASSERT_EQ(confined.size(), 2u);
  EXPECT_FALSE(confined[0].ok);
  // The assembler says "file not found" for a file it may not open.
  EXPECT_NE(confined[0].output.find("secret.txt"), std::string::npos) << confined[0].output;
  const std::string no_private_mounts = whyNoPrivateMountNamespace();
  if (!no_private_mounts.empty())
    GTEST_SKIP() << "the hidden-folder half needs a private mount namespace: " << no_private_mounts;
  EXPECT_FALSE(confined[1].ok);
  EXPECT_NE(confined[1].output.find("No such file"), std::string::npos) << confined[1].output;
  EXPECT_FALSE(fs::exists(work / "incbin.o"));
}

}  // namespace
}  // namespace clothref::grader
