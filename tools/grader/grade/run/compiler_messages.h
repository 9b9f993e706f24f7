// What the compiler and the linker said about a student's file, made fit to show: the first error
// with its context and the whole log of the student's own file, scratch paths removed, other files
// named but never quoted.
//
// What may be quoted is decided on the path gcc printed, resolved first: relative to the
// compile's working directory, `..` and links followed (`#include "../../../../etc/passwd"` is
// printed as `<scratch>/src-cloth/../../../../etc/passwd` and resolves to /etc/passwd). Only
// messages located in the student's own file or in a header folder we name are quoted; a message
// located anywhere else is named by its resolved path, never quoted (the compile may read host
// files the student may not).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace clothref::grader {

// Where one compile or link ran and what it may quote.
struct CompileSite {
  std::filesystem::path work_dir;      // the compiler's working directory
  std::filesystem::path student_file;  // the student's file as compiled; empty for a link
  std::string file_name;               // how the student's file is named in quotes: "cloth.cpp"
  // Folders whose files may be quoted (the course's stand-in headers, the system's), each with the
  // prefix that replaces it in quotes ("" shows a course header by its name, as the student's own
  // project does; "/usr/include/" keeps a system path as it is).
  std::vector<std::pair<std::filesystem::path, std::string>> header_dirs;
};

// The folders a course compile may quote: the edition's stand-in headers (shown by their names)
// and the system's include folders (shown as they are).
std::vector<std::pair<std::filesystem::path, std::string>> courseHeaderDirs(
    const std::filesystem::path& course_dir, int edition,
    const std::filesystem::path& eigen_include);

// The first error of `log` (a compile error, or a link error such as an undefined reference) with
// up to two lines of its source excerpt, paths cut to what the student knows; an error located in
// a file that is neither the student's nor a header of `site` is named, never quoted.
std::string firstCompilerError(const std::string& log, const CompileSite& site);

// Every message of `log` located in the student's own file (or made by the linker), with their
// source excerpts, paths cut as above; messages about other files are left out and counted in a
// last line. At most 200 lines. Empty when the log says nothing more than its first error.
std::string compilerLog(const std::string& log, const CompileSite& site);

}  // namespace clothref::grader
