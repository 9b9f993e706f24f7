// clothref_grader_prebuild OUT_DIR: run by the build (and the install) so that grading never
// repeats work that does not depend on a student's bytes: the precompiled stand-in headers of
// every edition and our reference objects, for the default compiler and flags, into OUT_DIR.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "grader/grade/run/build.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc != 2) {
    std::fprintf(stderr, "usage: clothref_grader_prebuild OUT_DIR\n");
    return 2;
  }
  std::string pattern = (fs::temp_directory_path() / "clothref-prebuild-XXXXXX").string();
  if (!mkdtemp(pattern.data())) {
    std::perror("clothref_grader_prebuild: temporary folder");
    return 1;
  }
  std::error_code error;
  fs::create_directories(argv[1], error);
  clothref::grader::CourseToolchain toolchain = clothref::grader::defaultToolchain();
  std::string problem;
  const bool ok =
      clothref::grader::prebuildCourse(toolchain, {2022, 2024}, argv[1], pattern, &problem);
  fs::remove_all(pattern, error);
  if (!ok) std::fprintf(stderr, "clothref_grader_prebuild: %s\n", problem.c_str());
  return ok ? 0 : 1;
}
