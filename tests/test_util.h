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

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clothref/io/error.h"
#include "clothref/io/gzip_stream.h"
#include "clothref/record/record.h"
#include "clothref/trace/format.h"
#include "clothref/trace/hash.h"
#include "clothref/trace/reader.h"

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

// Step line `index` of `lines` with its hash recomputed from its values, as the writer would
// have written it, so an edit reads as a changed value and not as a corrupt record (the reader
// checks every hash it parses). A line that does not parse is returned as it is.
inline std::string rehashed(const std::vector<std::string>& lines, std::size_t index) {
  std::string header = lines[0];
  const std::string ours(kTraceHashDescription);
  header.replace(header.find(ours), ours.size(), "not checked");  // read the edit unchecked
  std::string text = header + "\n";
  for (std::size_t i = 1; i <= index; ++i) text += lines[i] + "\n";
  std::istringstream in(text);
  try {
    TraceReader reader(in, "edited");
    while (reader.lineNumber() <= std::int64_t(index) && reader.next()) {
    }
    TraceStep step;
    reader.parseStep(step);
    std::string line = lines[index];
    line.replace(line.find("\"hash\":\"") + 8, 16, hashToHex(stateHashOf(reader.header(), step)));
    return line;
  } catch (const InputError&) {
    return lines[index];
  }
}

// `text` as one gzip member, by the library's own writer (concatenate several for a multi-member
// stream).
inline std::string gzipMember(const std::string& text) {
  std::stringbuf sink;
  GzipOutputBuffer gzip(sink);
  std::ostream out(&gzip);
  out << text;
  out.flush();
  EXPECT_TRUE(gzip.finish());
  return sink.str();
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
  TempDir() : TempDir(std::filesystem::temp_directory_path()) {}
  // Under `base` instead of the temporary folder: for a test whose files must lie where a
  // grader's private /tmp does not cover them (a TA's folder of hand-ins).
  explicit TempDir(const std::filesystem::path& base) {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "clothref-" + std::string(test ? test->test_suite_name() : "test") + "." +
                       (test ? test->name() : "none") + "-" + std::to_string(::getpid());
    for (char& c : name)  // parameterised suites and tests have '/' in their names
      if (c == '/') c = '_';
    path_ = base / name;
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
  // Closes the directory to other users (0700), as a grading machine keeps its submissions and
  // outputs: without bubblewrap and without a private mount namespace (a chroot, Gradescope) a
  // batch refuses folders student code could read.
  void closeToOthers() const {
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::replace);
  }
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

struct ProcessResult {
  int exit_code = -1;   // -1 when ended by a signal
  long max_rss_kb = 0;  // peak resident memory of the process (getrusage), KiB
  std::string stdout_text, stderr_text;
};

// Runs `clothref ARGS...` without a shell (so its own peak memory is measured), stdin from
// `stdin_path` ("" for /dev/null), under an address-space limit `address_space_bytes` and a
// file-size limit `file_size_bytes` (0: none), set in the forked child only. Output goes through
// files in `scratch`.
inline ProcessResult runCliDirect(const std::vector<std::string>& args,
                                  const std::filesystem::path& scratch,
                                  const std::string& stdin_path = "",
                                  unsigned long long address_space_bytes = 0,
                                  unsigned long long file_size_bytes = 0) {
  const std::string out = (scratch / "direct.stdout").string();
  const std::string err = (scratch / "direct.stderr").string();
  std::vector<std::string> argv_text = {CLOTHREF_BIN};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : argv_text) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ProcessResult result;
  const pid_t pid = ::fork();
  if (pid < 0) return result;
  if (pid == 0) {
    const int in = ::open(stdin_path.empty() ? "/dev/null" : stdin_path.c_str(), O_RDONLY);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || o < 0 || e < 0 || ::dup2(in, 0) < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0)
      ::_exit(127);
    if (address_space_bytes) {
      const struct rlimit limit = {address_space_bytes, address_space_bytes};
      if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    }
    if (file_size_bytes) {  // a full disk, as a write past the limit fails with EFBIG
      const struct rlimit limit = {file_size_bytes, file_size_bytes};
      if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
      ::signal(SIGXFSZ, SIG_IGN);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage {};
  if (::wait4(pid, &status, 0, &usage) != pid) return result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.max_rss_kb = usage.ru_maxrss;
  result.stdout_text = readText(out);
  result.stderr_text = readText(err);
  return result;
}

}  // namespace clothref::test
