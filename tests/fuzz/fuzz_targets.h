// The fuzz targets: one function per parser, each taking arbitrary bytes. A target may throw
// InputError (bad input, the expected outcome) and nothing else; anything else, and every crash,
// leak or undefined behaviour the sanitizers see, is a finding. Valid input (the seed corpora)
// throws nothing. Used by the libFuzzer binaries
// (fuzz_main.cpp, -DCLOTHREF_FUZZ=ON) and by fuzz_regression_test.cpp, which replays the
// committed corpora and crash inputs in the normal build.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>

#include "clothref/diff/diff.h"
#include "clothref/golden/golden.h"
#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/reader.h"
#include "grader/grade/rubric.h"
#include "grader/grade/submission/submission.h"
#include "grader/grade/text.h"

namespace clothref::fuzz {

// A valid header for one body of two particles, used in front of a fuzzed step line.
inline constexpr std::string_view kStepLineHeader =
    R"({"format":"clothref-trace","version":1,"scene":{},"integrator":"explicit",)"
    R"("precision":"float","dt":0.001,"steps":4,"stride":2,)"
    R"("bodies":[{"name":"cloth","particles":2}],"hash":"h","build":{}})";

inline void sceneJson(std::string_view input) {
  const Scene scene = sceneFromJson(parseJson(input, "scene.json"));
  validateScene(scene);
}

inline void traceHeader(std::string_view input) {
  std::istringstream in{std::string(input)};
  TraceReader reader(in, "trace.jsonl");
  TraceStep step;
  while (reader.next()) reader.parseStep(step);
}

inline void stepLine(std::string_view input) {
  std::istringstream in(std::string(kStepLineHeader) + "\n" + std::string(input));
  TraceReader reader(in, "trace.jsonl");
  TraceStep step;
  while (reader.next()) {
    reader.parseStep(step);
    stateHashOf(reader.header(), step);
  }
}

inline void toleranceFile(std::string_view input) {
  toleranceOptionsFromJson(parseJson(input, "tolerances.json"), "tolerances.json");
}

inline void goldenManifest(std::string_view input) {
  manifestFromJson(parseJson(input, "manifest.json"), "manifest.json");
}

// The grader's rubric file, over the 2022 defaults (the edition with every stub).
inline void rubric(std::string_view input) {
  grader::rubricFromJson(parseJson(input, "rubric.json"), "rubric.json",
                         grader::defaultRubric(2022));
}

// A trace read through the gzip decoder (the seeds are gzip-compressed traces: one member, several,
// empty ones): multi-member streams, trailing bytes, truncation, bombs. The line limits are
// lowered for the call, so a bomb costs at most a few MiB per execution.
inline void gzipTrace(std::string_view input) {
  struct Lowered {
    InputLimits saved = inputLimits();
    Lowered() {
      inputLimits().header_bytes = std::size_t(1) << 16;
      inputLimits().line_bytes = std::size_t(1) << 20;
    }
    ~Lowered() { inputLimits() = saved; }
  } lowered;
  std::istringstream in{std::string(input)};
  TraceReader reader(in, "trace.jsonl.gz");
  TraceStep step;
  while (reader.next()) reader.parseStep(step);
}

// Two traces separated by a line "----": diff them both ways and render every report.
inline void diffTwo(std::string_view input) {
  const std::size_t split = input.find("\n----\n");
  // A keeps its last newline; B is the rest after the separator line
  const std::string a(input.substr(0, split == std::string_view::npos ? split : split + 1));
  const std::string b(split == std::string_view::npos ? "" : input.substr(split + 6));
  for (int order = 0; order < 2; ++order) {
    std::istringstream in_a(order ? b : a), in_b(order ? a : b);
    DiffOptions options;
    options.common_steps = order == 1;
    const DiffReport report = diffTraces(in_a, "a.jsonl", in_b, "b.jsonl", options);
    formatReport(report);
    reportToJson(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    observedTolerances(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  }
}

// The grader's file finder over a submission folder the input describes, one entry per line:
// "f PATH<tab>CONTENT" a file, "d PATH" a folder, "l PATH<tab>TARGET" a symbolic link (any
// target, "/etc/passwd" or "../.." included), "p PATH" a FIFO. PATH is kept relative ("", "."
// and ".." components dropped); at most 64 entries. The tree is built one component at a time from
// descriptors (openat, mkdirat, symlinkat, mkfifoat), never following a link and never waiting on
// a FIFO: an entry whose path crosses a link, a FIFO or a file described before it is skipped, so
// "l x<tab>/etc" then "f x/passwd" writes nothing outside the scratch folder (it used to write
// through the link, as root), and "p x.cpp" then "f x.cpp" does not block in open (it used to,
// until libFuzzer's alarm: an 11 s slow unit). Whatever the tree, a file the finder returns
// must be a regular file reached from the folder without a link, with exactly its bytes, and the
// notes valid UTF-8: anything else aborts (a finding).
namespace detail {
// The folder that holds `relative` (below the folder open at `root_fd`), its missing folders made,
// or -1 if a component is not a folder (a link, a FIFO, a file) or cannot be made.
inline int openParentBeneath(int root_fd, const std::filesystem::path& relative) {
  int fd = dup(root_fd);
  const std::filesystem::path parent = relative.parent_path();
  for (const std::filesystem::path& part : parent) {
    if (fd < 0) return -1;
    mkdirat(fd, part.c_str(), 0755);  // EEXIST is fine: the open below decides
    const int next = openat(fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    close(fd);
    fd = next;
  }
  return fd;
}
}  // namespace detail

inline void fileFinder(std::string_view input) {
  namespace fs = std::filesystem;
  char scratch[] = "/tmp/clothref-fuzz-finder-XXXXXX";
  if (!mkdtemp(scratch)) return;
  const fs::path root = fs::path(scratch) / "submission";
  std::error_code error;
  fs::create_directories(root, error);
  const int root_fd = open(root.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (root_fd < 0) {
    fs::remove_all(scratch, error);
    return;
  }
  std::istringstream lines{std::string(input)};
  int entries = 0;
  for (std::string line; entries < 64 && std::getline(lines, line); ++entries) {
    if (line.size() < 3 || line[1] != ' ') continue;
    const std::size_t tab = line.find('\t');
    const std::string raw = line.substr(2, tab == std::string::npos ? tab : tab - 2);
    const std::string rest = tab == std::string::npos ? "" : line.substr(tab + 1, 4096);
    fs::path relative;
    for (const fs::path& part : fs::path(raw))
      if (part != "/" && part != "." && part != ".." && !part.empty()) relative /= part;
    if (relative.empty()) continue;
    const int parent_fd = detail::openParentBeneath(root_fd, relative);
    if (parent_fd < 0) continue;
    const std::string name = relative.filename().string();
    switch (line[0]) {
      case 'f': {
        // O_NOFOLLOW: not through a link; O_NONBLOCK: a FIFO without a reader fails (ENXIO)
        const int fd =
            openat(parent_fd, name.c_str(),
                   O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
        if (fd >= 0) {
          for (std::size_t done = 0; done < rest.size();) {
            const ssize_t n = write(fd, rest.data() + done, rest.size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
          }
          close(fd);
        }
        break;
      }
      case 'd':
        mkdirat(parent_fd, name.c_str(), 0755);
        break;
      case 'l':
        symlinkat(rest.c_str(), parent_fd, name.c_str());
        break;
      case 'p':
        mkfifoat(parent_fd, name.c_str(), 0644);
        break;
      default:
        break;
    }
    close(parent_fd);
  }
  close(root_fd);
  const grader::SubmissionFiles files = grader::findSubmissionFiles(root, 1 << 16);
  for (const auto& [name, found] : files.found) {
    fs::path walked = root;
    const fs::path relative = found.lexically_relative(root);
    if (relative.empty() || *relative.begin() == "..") std::abort();
    for (const fs::path& part : relative) {
      walked /= part;
      struct stat st {};
      if (lstat(walked.c_str(), &st) != 0 || S_ISLNK(st.st_mode)) std::abort();
      if (walked != found && !S_ISDIR(st.st_mode)) std::abort();
      if (walked == found && !S_ISREG(st.st_mode)) std::abort();
    }
    std::ifstream in(found, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (files.bytes.count(name) == 0 || files.bytes.at(name) != bytes) std::abort();
  }
  for (const std::string& note : files.notes)
    if (!grader::isValidUtf8(note)) std::abort();
  fs::remove_all(scratch, error);
}

}  // namespace clothref::fuzz
