// Finding a student's three files in a submission directory of any shape, and the course edition
// they were written for.
#pragma once
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "grader/grade/results.h"

namespace clothref::grader {

inline const std::vector<std::string>& studentFileNames() {
  static const std::vector<std::string> names = {"cloth.cpp", "sphere.cpp", "integrator.cpp"};
  return names;
}

struct SubmissionFiles {
  std::map<std::string, std::filesystem::path> found;  // file name -> path (missing: absent)
  // file name -> its bytes, read once through a descriptor that was checked to be a regular
  // file inside the submission: the only copy of the student's text anything else sees.
  std::map<std::string, std::string> bytes;
  // One line of Markdown each (names in code spans): choices made, encodings seen, refusals.
  std::vector<std::string> notes;
  std::vector<FileChoice> choices;  // every name found more than once, and which copy was used
};

// Student files are small; a larger one is refused rather than read (`--max-file-bytes`).
inline constexpr std::size_t kDefaultMaxSourceBytes = 16u << 20;

// Searches below `dir` (recursively, names compared case-insensitively, macOS "__MACOSX" and
// "._*" entries skipped). Several candidates: one under a folder named `src` wins, then the
// shallowest, then the first in path order; the others are listed in the notes. Notes also name
// a UTF-8 byte-order mark, CRLF line ends and bytes that are not UTF-8 (e.g. Big5): the bytes are
// passed to the compiler unchanged.
// Only regular files inside `dir` are read: the walk follows no symbolic link (not even to a
// folder), and a candidate that is a link, FIFO, socket, device or folder is refused with a note
// and counts as missing. Every open goes through openBeneath. Throws InputError when `dir` is
// not a directory or a chosen file is larger than `max_file_bytes`.
SubmissionFiles findSubmissionFiles(const std::filesystem::path& dir,
                                    std::size_t max_file_bytes = kDefaultMaxSourceBytes);

// The folders directly below `dir` that each hold a whole submission (cloth.cpp, sphere.cpp and
// integrator.cpp somewhere below them), sorted, when there are two or more of them and `dir`
// itself holds none of the three files at its top: `dir` is then a folder of submissions, not
// one (grading it would silently grade one of them). Empty otherwise, or when `dir` cannot be
// opened. Walked as findSubmissionFiles walks: no link followed.
std::vector<std::string> submissionsBelow(const std::filesystem::path& dir);
// The one line that refuses such a folder: "3 submissions below subs (a, b, c): give them as
// subs/* with --out BATCHDIR, or --one-submission to grade subs as one".
std::string severalSubmissionsProblem(const std::filesystem::path& dir,
                                      const std::vector<std::string>& names);

// Opens `relative` (no "..", no leading '/') below the open directory `root_fd` without
// following any symbolic link on the way: openat2(RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS), or
// where the kernel lacks openat2 (or `use_openat2` is false, for tests) one openat(O_NOFOLLOW)
// per component. Returns the descriptor (O_CLOEXEC added) or -1 with errno set (ELOOP for a
// link).
int openBeneath(int root_fd, const std::string& relative, int flags, bool use_openat2 = true);

// The bytes of the regular file at `relative` below `root_fd` (opened with openBeneath and
// O_NONBLOCK, so a FIFO never blocks, then fstat'ed): false with `why` ("a symbolic link", "a
// FIFO", "larger than N bytes", ...) otherwise.
bool readRegularFileBeneath(int root_fd, const std::string& relative, std::size_t max_bytes,
                            std::string& bytes, std::string& why, bool use_openat2 = true);

// 2024 when sphere.cpp defines Spheres::setVelocity (or cloth.cpp uses textureBuffer), 2022 when
// sphere.cpp defines Spheres::collide(); 0 when neither is found. `why` says what decided.
int detectEdition(const SubmissionFiles& files, std::string& why);

}  // namespace clothref::grader
