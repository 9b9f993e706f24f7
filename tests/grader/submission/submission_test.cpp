// Finding the three files in submissions of any shape, and detecting the edition.
#include "grader/grade/submission/submission.h"
#include "grader/grade/submission/source_text.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "clothref/io/error.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(FindSubmissionFiles, PrefersSrcThenShallowestAndListsTheOthers) {
  test::TempDir temp;
  const fs::path root = temp.path();
  write(root / "old" / "cloth.cpp", "// old\n");
  write(root / "HW1" / "src" / "cloth.cpp", "// new\n");
  write(root / "HW1" / "src" / "Sphere.cpp", "// case differs\n");
  write(root / "a" / "b" / "integrator.cpp", "// deep\n");
  write(root / "integrator.cpp", "// shallow\n");
  write(root / "__MACOSX" / "src" / "cloth.cpp", "junk\n");
  write(root / "HW1" / "src" / "._cloth.cpp", "junk\n");
  const SubmissionFiles files = findSubmissionFiles(root);
  EXPECT_EQ(files.found.at("cloth.cpp"), root / "HW1" / "src" / "cloth.cpp");
  EXPECT_EQ(files.found.at("sphere.cpp"), root / "HW1" / "src" / "Sphere.cpp");
  EXPECT_EQ(files.found.at("integrator.cpp"), root / "integrator.cpp");
  bool listed_old = false;
  for (const auto& note : files.notes)
    listed_old |= note.find("old/cloth.cpp") != std::string::npos;
  EXPECT_TRUE(listed_old);
}

TEST(FindSubmissionFiles, NamesBomCrlfAndNonUtf8Bytes) {
  test::TempDir temp;
  write(temp.path() / "cloth.cpp", "\xEF\xBB\xBF// bom\r\nint a;\r\n");
  write(temp.path() / "sphere.cpp", "// \xB3\\\xA5\xBB Big5 comment\nint b;\n");
  write(temp.path() / "integrator.cpp", "int c;\n");
  const SubmissionFiles files = findSubmissionFiles(temp.path());
  std::string notes;
  for (const auto& note : files.notes) notes += note + "\n";
  EXPECT_NE(notes.find("cloth.cpp: UTF-8 byte-order mark; CRLF line ends;"), std::string::npos)
      << notes;
  EXPECT_NE(notes.find("sphere.cpp: bytes that are not UTF-8"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("integrator.cpp"), std::string::npos) << notes;
}

TEST(FindSubmissionFiles, NotADirectoryIsBadInput) {
  test::TempDir temp;
  EXPECT_THROW(findSubmissionFiles(temp.path() / "missing"), InputError);
}

std::string allNotes(const SubmissionFiles& files) {
  std::string notes;
  for (const auto& note : files.notes) notes += note + "\n";
  return notes;
}

// A symbolic link is never followed, wherever it points: to a file of the host this test
// creates outside the submission, to /etc/passwd, or to our own reference file. It is refused
// with a note naming it and the file counts as missing.
TEST(FindSubmissionFiles, RefusesSymbolicLinksToHostAndReferenceFiles) {
  test::TempDir temp;
  const fs::path secret = temp.path() / "outside" / "secret.txt";
  write(secret, "SECRET-HOST-BYTES\n");
  const fs::path root = temp.path() / "submission";
  fs::create_directories(root);
  fs::create_symlink(secret, root / "cloth.cpp");
  fs::create_symlink("/etc/passwd", root / "sphere.cpp");
  const fs::path reference =
      fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022/integrator.cpp";
  ASSERT_TRUE(fs::is_regular_file(reference));
  fs::create_symlink(reference, root / "integrator.cpp");
  const SubmissionFiles files = findSubmissionFiles(root);
  EXPECT_TRUE(files.found.empty());
  EXPECT_TRUE(files.bytes.empty());
  const std::string notes = allNotes(files);
  for (const char* name : {"cloth.cpp", "sphere.cpp", "integrator.cpp"})
    EXPECT_NE(notes.find(std::string(name) + ": refused `" + name + "`: a symbolic link"),
              std::string::npos)
        << notes;
  EXPECT_EQ(notes.find("SECRET"), std::string::npos);
}

// A FIFO named like a student file must not block the grader (nobody ever writes to it), and a
// folder named cloth.cpp is not a file; the real file in a sibling folder is still found.
TEST(FindSubmissionFiles, AFifoDoesNotHangAndAFolderIsNotAFile) {
  test::TempDir temp;
  const fs::path root = temp.path();
  ASSERT_EQ(mkfifo((root / "sphere.cpp").c_str(), 0644), 0);
  fs::create_directories(root / "cloth.cpp");
  write(root / "src" / "integrator.cpp", "int i;\n");
  const auto start = std::chrono::steady_clock::now();
  const SubmissionFiles files = findSubmissionFiles(root);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(files.found.count("sphere.cpp"), 0u);
  EXPECT_EQ(files.found.count("cloth.cpp"), 0u);
  ASSERT_EQ(files.bytes.count("integrator.cpp"), 1u);
  EXPECT_EQ(files.bytes.at("integrator.cpp"), "int i;\n");
  const std::string notes = allNotes(files);
  EXPECT_NE(notes.find("sphere.cpp: refused `sphere.cpp`: a FIFO"), std::string::npos) << notes;
  EXPECT_NE(notes.find("cloth.cpp: refused `cloth.cpp`: a folder"), std::string::npos) << notes;
}

// A symbolic link to a folder (inside or outside the submission) is not entered: files reached
// only through it are missing, and the link is named in a note.
TEST(FindSubmissionFiles, DoesNotEnterASymlinkedFolder) {
  test::TempDir temp;
  write(temp.path() / "elsewhere" / "cloth.cpp", "int elsewhere;\n");
  const fs::path root = temp.path() / "submission";
  write(root / "sphere.cpp", "int s;\n");
  fs::create_symlink(temp.path() / "elsewhere", root / "src");
  const SubmissionFiles files = findSubmissionFiles(root);
  EXPECT_EQ(files.found.count("cloth.cpp"), 0u);
  EXPECT_EQ(files.found.count("sphere.cpp"), 1u);
  const std::string notes = allNotes(files);
  EXPECT_NE(notes.find("1 symbolic link(s) not followed: `src`"), std::string::npos) << notes;
}

// Both ways of opening below a folder refuse a link on the way and a way out: openat2 and the
// per-component O_NOFOLLOW walk used where the kernel lacks openat2.
TEST(OpenBeneath, RefusesLinksAndEscapesWithAndWithoutOpenat2) {
  test::TempDir temp;
  write(temp.path() / "outside.txt", "outside\n");
  const fs::path root = temp.path() / "root";
  write(root / "dir" / "file.cpp", "inside\n");
  fs::create_symlink(temp.path() / "outside.txt", root / "dir" / "link.cpp");
  fs::create_symlink(root / "dir", root / "dirlink");
  const int root_fd = open(root.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(root_fd, 0);
  for (const bool openat2 : {true, false}) {
    std::string bytes, why;
    EXPECT_TRUE(readRegularFileBeneath(root_fd, "dir/file.cpp", 1000, bytes, why, openat2));
    EXPECT_EQ(bytes, "inside\n");
    EXPECT_FALSE(readRegularFileBeneath(root_fd, "dir/link.cpp", 1000, bytes, why, openat2));
    EXPECT_NE(why.find("symbolic link"), std::string::npos) << why;
    EXPECT_FALSE(readRegularFileBeneath(root_fd, "dirlink/file.cpp", 1000, bytes, why, openat2));
    EXPECT_NE(why.find("symbolic link"), std::string::npos) << why;
    EXPECT_FALSE(readRegularFileBeneath(root_fd, "../outside.txt", 1000, bytes, why, openat2));
    EXPECT_EQ(why, "outside the submission");
    EXPECT_FALSE(readRegularFileBeneath(root_fd, "dir/file.cpp", 3, bytes, why, openat2));
    EXPECT_NE(why.find("larger than 3 bytes"), std::string::npos) << why;
  }
  close(root_fd);
}

// --max-file-bytes: a file over the limit is refused (and named) but the others are graded.
TEST(FindSubmissionFiles, AFileOverTheLimitIsRefusedTheOthersAreFound) {
  test::TempDir temp;
  write(temp.path() / "cloth.cpp", std::string(2000, 'x'));
  write(temp.path() / "sphere.cpp", "int s;\n");
  const SubmissionFiles small = findSubmissionFiles(temp.path(), 1000);
  EXPECT_EQ(small.found.count("cloth.cpp"), 0u);
  EXPECT_EQ(small.found.count("sphere.cpp"), 1u);
  EXPECT_NE(allNotes(small).find("cloth.cpp: refused `cloth.cpp`: larger than 1000 bytes (raise "
                                 "the limit with --max-file-bytes)"),
            std::string::npos)
      << allNotes(small);
  EXPECT_EQ(findSubmissionFiles(temp.path(), 2000).bytes.at("cloth.cpp").size(), 2000u);
}

// Names a student chose are escaped in notes: no terminal escape reaches a report or stderr.
TEST(FindSubmissionFiles, ControlCharactersInNamesAreEscaped) {
  test::TempDir temp;
  write(temp.path() / "a\x1b[31mred" / "cloth.cpp", "int c;\n");
  write(temp.path() / "b" / "cloth.cpp", "int d;\n");
  const std::string notes = allNotes(findSubmissionFiles(temp.path()));
  EXPECT_EQ(notes.find('\x1b'), std::string::npos) << notes;
  EXPECT_NE(notes.find("a\\x1B[31mred/cloth.cpp"), std::string::npos) << notes;
}

// Through the CLI, single grade and batch: a submission whose files are links to a host file the
// test made, /etc/passwd and our own reference gets none of them read: no byte of them in any
// output, the three files refused and missing (0 points, not the reference's 80).
TEST(GradeThroughTheCli, LinkedFilesAreRefusedInASingleGradeAndInABatch) {
  test::TempDir temp;
  temp.closeToOthers();
  write(temp.path() / "host" / "secret.cpp", "SECRET-HOST-BYTES-4711\n");
  const fs::path submission = temp.path() / "linked";
  fs::create_directories(submission / "src");
  fs::create_symlink(temp.path() / "host" / "secret.cpp", submission / "src" / "cloth.cpp");
  fs::create_symlink("/etc/passwd", submission / "sphere.cpp");
  fs::create_symlink(fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022/integrator.cpp",
                     submission / "integrator.cpp");
  const std::string common =
      " --no-whole-run --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'";
  const test::CommandResult single = test::runCli(
      "grade '" + submission.string() + "' --results '" + temp.file("r.json") + "' --junit '" +
      temp.file("j.xml") + "' --report '" + temp.file("r.md") + "'" + common);
  // Nothing found at all: not gradable, one line, nothing written.
  EXPECT_EQ(single.exit_code, 2) << single.output;
  EXPECT_NE(single.output.find("none of cloth.cpp, sphere.cpp, integrator.cpp found"),
            std::string::npos)
      << single.output;
  EXPECT_FALSE(fs::exists(temp.file("r.json")));
  // With one real file the others are refused, named and graded as missing.
  write(submission / "extra" / "sphere.cpp",
        test::readText(fs::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022/sphere.cpp"));
  const test::CommandResult graded = test::runCli(
      "grade '" + submission.string() + "' --results '" + temp.file("r.json") + "' --junit '" +
      temp.file("j.xml") + "' --report '" + temp.file("r.md") + "'" + common);
  ASSERT_EQ(graded.exit_code, 0) << graded.output;
  const test::CommandResult batch = test::runCli("grade '" + submission.string() + "' --out '" +
                                                 temp.file("batch") + "' --quiet" + common);
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  const std::string passwd_line = test::readText("/etc/passwd").substr(0, 12);
  for (const std::string& file :
       {temp.file("r.json"), temp.file("j.xml"), temp.file("r.md"),
        temp.file("batch/linked/results.json"), temp.file("batch/linked/report.md"),
        temp.file("batch/linked/row.json"), temp.file("batch/grades.csv")}) {
    const std::string text = test::readText(file);
    ASSERT_FALSE(text.empty()) << file;
    EXPECT_EQ(text.find("SECRET-HOST-BYTES"), std::string::npos) << file;
    EXPECT_EQ(text.find(passwd_line), std::string::npos) << file;
  }
  for (const std::string& file : {temp.file("r.json"), temp.file("batch/linked/results.json")}) {
    const nlohmann::json results = nlohmann::json::parse(test::readText(file));
    const std::string output = results["output"].get<std::string>();
    EXPECT_NE(output.find("cloth.cpp: refused <code>src/cloth.cpp</code>: a symbolic link"),
              std::string::npos)
        << output;
    EXPECT_NE(output.find("integrator.cpp: refused <code>integrator.cpp</code>: a symbolic link"),
              std::string::npos)
        << output;
    const auto& scores = results["extra_data"]["stub_scores"];
    EXPECT_EQ(scores["RungeKuttaFourth::integrate"].get<double>(), 0.0) << scores;
    EXPECT_EQ(scores["Cloth::computeSpringForce"].get<double>(), 0.0) << scores;
    EXPECT_GT(scores["Spheres::collide(Cloth*)"].get<double>(), 0.0) << scores;
  }
}

TEST(DetectEdition, FromTheDefinitionsNotFromComments) {
  test::TempDir temp;
  SubmissionFiles files;
  files.found["sphere.cpp"] = temp.path() / "sphere.cpp";
  auto& sphere = files.bytes["sphere.cpp"];
  sphere = "void Spheres::collide(Cloth* c) {}\nvoid Spheres::collide() {}\n";
  std::string why;
  EXPECT_EQ(detectEdition(files, why), 2022);
  sphere =
      "// Spheres::collide() was removed\n"
      "void Spheres::setVelocity(int i, const Eigen::Vector4f v) {}\n";
  EXPECT_EQ(detectEdition(files, why), 2024);
  sphere = "/* void Spheres::setVelocity(int) */ void Spheres::collide ( ) {}\n";
  EXPECT_EQ(detectEdition(files, why), 2022);
  sphere = "int nothing;\n";
  EXPECT_EQ(detectEdition(files, why), 0);
}

TEST(StubCode, TheBodyWithCommentsAndLiteralsBlankedAndDeclarationsSkipped) {
  const std::string source =
      "void MidpointEuler::integrate(const std::vector<Particles*>&, std::function<void()>) "
      "const;\n"
      "// MidpointEuler::integrate(x) { in a comment }\n"
      "void MidpointEuler :: integrate(const std::vector<Particles*>& ps,\n"
      "                               std::function<void()> f) const {\n"
      "  float h = 1 / 2;  // step 1/6\n"
      "  const char* s = \"{ 1 / 6 }\"; /* } */\n"
      "}\n"
      "void RungeKuttaFourth::integrate() const {}\n";
  const std::string body = stubCode(source, "MidpointEuler::integrate");
  EXPECT_EQ(body.front(), '{');
  EXPECT_EQ(body.back(), '}');
  EXPECT_NE(body.find("float h = 1 / 2;"), std::string::npos) << body;
  for (const char* gone : {"1/6", "{ 1 / 6 }", "step", "/*"})
    EXPECT_EQ(body.find(gone), std::string::npos) << gone << " in\n" << body;
  EXPECT_EQ(std::count(body.begin(), body.end(), '\n'), 3) << "newlines kept";
  const StubLines lines = stubLines(source, "MidpointEuler::integrate");
  EXPECT_EQ(lines.first, 4);
  EXPECT_EQ(lines.last, 7);
  EXPECT_EQ(stubCode(source, "RungeKuttaFourth::integrate"), "{}");
  EXPECT_EQ(stubCode(source, "ImplicitEuler::integrate"), "");
  const std::string blanked = blankedCode("a // b\n'c' \"d\" /* e */ f");
  EXPECT_EQ(blanked, "a" + std::string(5, ' ') + "\n" + std::string(16, ' ') + "f");
}

}  // namespace
}  // namespace clothref::grader
