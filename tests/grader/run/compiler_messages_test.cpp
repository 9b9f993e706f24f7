// Quoting the compiler: the first error with its context and the whole log of the student's own
// file, without scratch paths; what may be quoted is decided on the resolved path, whatever the
// spelling (`..`, relative to the compile's folder), so a host file included by a relative path is
// named and never quoted.
#include "grader/grade/run/compiler_messages.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

CompileSite site(const std::string& work, const std::string& file = "cloth.cpp") {
  return CompileSite{work, fs::path(work) / ("src-" + file.substr(0, file.find('.'))) / file, file,
                     courseHeaderDirs("/opt/course", 2022, "/usr/include/eigen3")};
}

TEST(FirstCompilerError, QuotesTheFirstErrorWithoutScratchPaths) {
  const std::string log =
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp: In member function 'void Cloth::x()':\n"
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp:12:3: error: 'addSpring' was not declared\n"
      "   12 |   addSpring(1, 2);\n"
      "      |   ^~~~~~~~~\n"
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp:20:1: error: second\n";
  const std::string quote = firstCompilerError(log, site("/tmp/clothref-grade-1-2"));
  EXPECT_EQ(quote.find("/tmp/"), std::string::npos) << quote;
  EXPECT_EQ(quote.rfind("cloth.cpp:12:3: error: 'addSpring' was not declared", 0), 0u) << quote;
  EXPECT_NE(quote.find("addSpring(1, 2);"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("second"), std::string::npos) << quote;
}

// `#line 1 "<5000 newlines>cloth.cpp"` renames the student's own file: gcc prints 5000 empty lines
// before each message, and the message is located in a file that does not exist. It is still the
// student's compile error, quoted with its real message (issue 36; before: "error in cloth.cpp,
// which is not a course header (not quoted)", and the compile taken for a silent failure of ours).
TEST(FirstCompilerError, ALineDirectiveThatRenamesTheFileIsTheStudentsErrorWithItsMessage) {
  test::TempDir temp;
  const fs::path work = temp.path() / "scratch";
  fs::create_directories(work / "src-cloth");
  std::string name;
  for (int k = 0; k < 5000; ++k) name += "\\n";
  test::writeText(work / "src-cloth" / "cloth.cpp",
                  "#line 1 \"" + name + "cloth.cpp\"\nvoid f() { int x = 1 int y; }\n");
  const std::string blank(5000, '\n');
  const std::string log = blank + "cloth.cpp: In function 'void f()':\n" + blank +
                          "cloth.cpp:1:22: error: expected ',' or ';' before 'int'\n";
  const std::string quote = firstCompilerError(log, site(work.string()));
  EXPECT_NE(quote.find("error: expected ',' or ';' before 'int'"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("not quoted"), std::string::npos) << quote;
  EXPECT_LT(quote.size(), 200u);
  // An existing file by that name stays named and unquoted: the excerpt would be its text.
  const std::string host = firstCompilerError(
      "/etc/passwd:1:1: error: 'root' does not name a type\n    1 | root:x:0:0\n",
      site(work.string()));
  EXPECT_EQ(host.find("root:x"), std::string::npos) << host;
}

TEST(FirstCompilerError, LinkErrors) {
  const std::string quote = firstCompilerError(
      "/usr/bin/ld: /tmp/g/cloth.o: in function `main':\n"
      "driver.cpp:(.text+0x1): undefined reference to `Cloth::computeNormal()'\n",
      CompileSite{"/tmp/g", {}, "cloth.cpp", {}});
  EXPECT_NE(quote.find("undefined reference to `Cloth::computeNormal()'"), std::string::npos)
      << quote;
}

// Course headers are shown by their names, system headers as they are; any other file, whatever
// its spelling, is named by its resolved path and never quoted.
TEST(FirstCompilerError, QuotesOnlyTheStudentsFileAndHeadersWhateverTheSpelling) {
  const std::string work = "/tmp/clothref-grade-1-2";
  const auto first = [&](const std::string& location) {
    return firstCompilerError("In file included from " + work + "/src-cloth/cloth.cpp:1:\n" +
                                  location +
                                  ":1:1: error: 'root' does not name a type\n"
                                  "    1 | root:x:0:0:root:/root:/bin/bash\n",
                              site(work));
  };
  EXPECT_EQ(first("/opt/course/2022/include/cloth.h"),
            "cloth.h:1:1: error: 'root' does not name a type\n"
            "    1 | root:x:0:0:root:/root:/bin/bash\n");
  EXPECT_NE(first("/usr/include/eigen3/Eigen/Core").find("    1 | root"), std::string::npos);
  for (const std::string& spelling :
       {work + "/src-cloth/../../../../etc/passwd", std::string("/usr/../etc/passwd"),
        std::string("src-cloth/../../../../../../../etc/passwd"),
        std::string("/usr/include/../../etc/passwd")}) {
    const std::string quote = first(spelling);
    EXPECT_EQ(quote, "error in /etc/passwd, which is not a course header (not quoted)\n")
        << spelling;
  }
  // a file of the scratch folder that is not the student's is named without the folder
  EXPECT_EQ(first(work + "/src-sphere/sphere.cpp"),
            "error in src-sphere/sphere.cpp, which is not a course header (not quoted)\n");
}

TEST(CompilerLog, EveryMessageOfTheStudentsFileAndNoOtherFile) {
  const std::string work = "/tmp/clothref-grade-1-2";
  const std::string log =
      work + "/src-cloth/cloth.cpp: In member function 'void Cloth::x()':\n" + work +
      "/src-cloth/cloth.cpp:12:3: error: 'addSpring' was not declared\n"
      "   12 |   addSpring(1, 2);\n"
      "      |   ^~~~~~~~~\n"
      "In file included from " +
      work + "/src-cloth/cloth.cpp:1:\n" + work +
      "/src-cloth/../../../etc/secret.h:3:1: error: 'SECRET_TEXT' does not name a type\n"
      "    3 | SECRET_TEXT\n" +
      work +
      "/src-cloth/cloth.cpp:20:7: error: expected ';' before '}' token\n"
      "   20 |   x = 1\n";
  const std::string whole = compilerLog(log, site(work));
  EXPECT_EQ(whole.find(work), std::string::npos) << whole;
  EXPECT_EQ(whole.find("SECRET"), std::string::npos) << whole;
  EXPECT_NE(whole.find("cloth.cpp:12:3: error: 'addSpring'"), std::string::npos) << whole;
  EXPECT_NE(whole.find("cloth.cpp:20:7: error: expected ';'"), std::string::npos) << whole;
  EXPECT_NE(whole.find("   20 |   x = 1"), std::string::npos) << whole;
  EXPECT_NE(whole.find("(2 lines about other files"), std::string::npos) << whole;
  // a log that says no more than its first error adds nothing
  EXPECT_EQ(compilerLog(work + "/src-cloth/cloth.cpp:1:1: error: x\n", site(work)), "");
}

// The real compiler on a real file: `#include "../../../../../..<host file>"` (the spelling that
// once passed as the student's own file because it contains "/src-") is named, never quoted, in
// the first error and in the whole log.
TEST(CompilerLog, ARelativeIncludeOfAHostFileIsNamedNeverQuoted) {
  test::TempDir temp;
  const fs::path host = temp.path() / "host" / "world-readable.txt";
  fs::create_directories(host.parent_path());
  test::writeText(host, "HOST_SECRET_LINE one two;\n");
  fs::permissions(host, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const fs::path work = temp.path() / "scratch";
  fs::create_directories(work / "src-cloth");
  std::string up;
  for (int k = 0; k < 12; ++k) up += "../";
  test::writeText(work / "src-cloth" / "cloth.cpp",
                  "#include \"" + up.substr(0, up.size() - 1) + host.string() + "\"\nint x = ;\n");
  const std::string command = "cd '" + work.string() + "' && g++ -fsyntax-only '" +
                              (work / "src-cloth" / "cloth.cpp").string() + "' 2> '" +
                              (work / "log").string() + "'";
  ASSERT_NE(std::system(command.c_str()), 0);
  const std::string log = test::readText(work / "log");
  ASSERT_NE(log.find("HOST_SECRET_LINE"), std::string::npos) << log;  // gcc did read it
  ASSERT_NE(log.find("/src-cloth/../"), std::string::npos) << log;    // the spelling of the attack
  const CompileSite where{work, work / "src-cloth" / "cloth.cpp", "cloth.cpp",
                          courseHeaderDirs("/opt/course", 2022, "/usr/include/eigen3")};
  const std::string first = firstCompilerError(log, where);
  const std::string whole = compilerLog(log, where);
  EXPECT_EQ(first.find("HOST_SECRET"), std::string::npos) << first;
  EXPECT_NE(first.find("error in " + host.string() + ", which is not a course header"),
            std::string::npos)
      << first;
  EXPECT_EQ(whole.find("HOST_SECRET"), std::string::npos) << whole;
  EXPECT_NE(whole.find("cloth.cpp:2:9: error"), std::string::npos) << whole;  // its own error
  EXPECT_EQ(whole.find(work.string()), std::string::npos) << whole;
}

// The same attack through a whole grade in the rlimits fallback, where the compile can read the
// file (under bubblewrap it cannot): no byte of it in any output.
TEST(CompilerLog, ARelativeIncludeOfAHostFileIsNotQuotedInAGrade) {
  if (geteuid() != 0) GTEST_SKIP() << "the fallback's compile uid needs root";
  test::TempDir temp;
  const fs::path host = temp.path() / "host.txt";
  test::writeText(host, "HOST_SECRET_LINE\n");
  fs::permissions(temp.path(),
                  fs::perms::owner_all | fs::perms::others_exec | fs::perms::group_exec);
  fs::permissions(host, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const fs::path reference = fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022";
  const fs::path submission = temp.path() / "sub";
  fs::create_directories(submission);
  for (const char* file : {"sphere.cpp", "integrator.cpp"})
    fs::copy_file(reference / file, submission / file);
  std::string up;
  for (int k = 0; k < 16; ++k) up += "../";
  test::writeText(submission / "cloth.cpp", "#include \"" + up.substr(0, up.size() - 1) +
                                                host.string() + "\"\n" +
                                                test::readText(reference / "cloth.cpp"));
  setenv("CLOTHREF_GRADER_ISOLATION", "rlimits", 1);
  const test::CommandResult run = test::runCli(
      "grade '" + submission.string() + "' --results '" + temp.file("r.json") + "' --report '" +
      temp.file("r.md") + "' --junit '" + temp.file("r.xml") +
      "' --no-whole-run --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'");
  unsetenv("CLOTHREF_GRADER_ISOLATION");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string results = test::readText(temp.file("r.json"));
  EXPECT_NE(results.find("compile-error"), std::string::npos) << results.substr(0, 3000);
  for (const char* output : {"r.json", "r.md", "r.xml"})
    EXPECT_EQ(test::readText(temp.file(output)).find("HOST_SECRET"), std::string::npos) << output;
  EXPECT_EQ(run.output.find("HOST_SECRET"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace clothref::grader
