// Finding the three files in submissions of any shape, and detecting the edition.
#include "grader/grade/submission.h"

#include <gtest/gtest.h>

#include <fstream>

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

TEST(DetectEdition, FromTheDefinitionsNotFromComments) {
  test::TempDir temp;
  SubmissionFiles files;
  files.found["sphere.cpp"] = temp.path() / "sphere.cpp";
  write(files.found["sphere.cpp"],
        "void Spheres::collide(Cloth* c) {}\nvoid Spheres::collide() {}\n");
  std::string why;
  EXPECT_EQ(detectEdition(files, why), 2022);
  write(files.found["sphere.cpp"],
        "// Spheres::collide() was removed\n"
        "void Spheres::setVelocity(int i, const Eigen::Vector4f v) {}\n");
  EXPECT_EQ(detectEdition(files, why), 2024);
  write(files.found["sphere.cpp"],
        "/* void Spheres::setVelocity(int) */ void Spheres::collide ( ) {}\n");
  EXPECT_EQ(detectEdition(files, why), 2022);
  write(files.found["sphere.cpp"], "int nothing;\n");
  EXPECT_EQ(detectEdition(files, why), 0);
}

}  // namespace
}  // namespace clothref::grader
