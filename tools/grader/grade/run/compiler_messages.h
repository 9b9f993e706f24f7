// What the compiler and the linker said about a student's file, made fit to show: the first error
// with its context, scratch paths removed, host files named but never quoted.
#pragma once
#include <string>

namespace clothref::grader {

// The first compiler error of `log` with up to two following lines, scratch paths replaced by
// the file's name.
std::string firstCompilerError(const std::string& log, const std::string& file_name);

}  // namespace clothref::grader
