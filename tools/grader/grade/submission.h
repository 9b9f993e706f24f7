// Finding a student's three files in a submission directory of any shape, and the course edition
// they were written for.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace clothref::grader {

inline const std::vector<std::string>& studentFileNames() {
  static const std::vector<std::string> names = {"cloth.cpp", "sphere.cpp", "integrator.cpp"};
  return names;
}

struct SubmissionFiles {
  std::map<std::string, std::filesystem::path> found;  // file name -> path (missing: absent)
  std::vector<std::string> notes;  // one line each: choices made, encodings seen
};

// Searches below `dir` (recursively, names compared case-insensitively, macOS "__MACOSX" and
// "._*" entries skipped). Several candidates: one under a folder named `src` wins, then the
// shallowest, then the first in path order; the others are listed in the notes. Notes also name
// a UTF-8 byte-order mark, CRLF line ends and bytes that are not UTF-8 (e.g. Big5): the bytes are
// passed to the compiler unchanged. Throws InputError when `dir` is not a directory.
SubmissionFiles findSubmissionFiles(const std::filesystem::path& dir);

// 2024 when sphere.cpp defines Spheres::setVelocity (or cloth.cpp uses textureBuffer), 2022 when
// sphere.cpp defines Spheres::collide(); 0 when neither is found. `why` says what decided.
int detectEdition(const SubmissionFiles& files, std::string& why);

}  // namespace clothref::grader
