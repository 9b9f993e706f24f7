// Helpers shared by the tests: bit comparison of floats and running the CLI.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clothref/record/record.h"

namespace clothref::test {

// The lines (without newlines) of a trace of `scene` run with `settings`.
inline std::vector<std::string> traceLines(const Scene& scene, const TraceSettings& settings) {
  std::stringstream text;
  writeTrace(scene, settings, text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

// Writes `lines` to `path`, each followed by a newline (the last one only if `final_newline`).
inline void writeLines(const std::string& path, const std::vector<std::string>& lines,
                       bool final_newline = true) {
  std::ofstream out(path, std::ios::binary);
  for (std::size_t i = 0; i < lines.size(); ++i)
    out << lines[i] << (i + 1 < lines.size() || final_newline ? "\n" : "");
}

// A method's name as a GoogleTest parameter name (letters, digits and '_' only).
inline std::string methodTestName(Method method) {
  std::string name(methodName(method));
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// A fresh directory named after the running test, removed when this goes out of scope.
class TempDir {
 public:
  TempDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "clothref-" + std::string(test ? test->test_suite_name() : "test") + "." +
                       (test ? test->name() : "none") + "-" + std::to_string(::getpid());
    for (char& c : name)  // parameterised suites and tests have '/' in their names
      if (c == '/') c = '_';
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The path of `name` inside the directory.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The bytes of the file at `path` ("" when it cannot be read).
inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Replaces the file at `path` with `text`.
inline void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// True when `path` is a FIFO (not followed if it is a link).
inline bool isFifo(const std::string& path) {
  struct stat info {};
  return ::lstat(path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
}

inline std::uint32_t bits(float value) { return std::bit_cast<std::uint32_t>(value); }
inline std::uint64_t bits(double value) { return std::bit_cast<std::uint64_t>(value); }

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved (stdout only when asked)
};

enum class Capture { StdoutAndStderr, StdoutOnly };

// Runs `clothref ARGS` (ARGS is shell syntax) and captures its output and exit code.
inline CommandResult runCli(const std::string& args, Capture capture = Capture::StdoutAndStderr) {
  CommandResult result;
  const std::string command =
      std::string(CLOTHREF_BIN) + " " + args + (capture == Capture::StdoutAndStderr ? " 2>&1" : "");
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace clothref::test
