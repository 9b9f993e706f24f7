#include "grader/grade/run/sanitize.h"

#include <algorithm>
#include <regex>
#include <sstream>
#include <vector>

#include "clothref/io/files.h"
#include "grader/grade/probes/probes.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

bool isReportStart(const std::string& line) {
  return line.find("ERROR: AddressSanitizer") != std::string::npos ||
         line.find("ERROR: LeakSanitizer") != std::string::npos ||
         line.find("runtime error:") != std::string::npos;
}

// "/tmp/clothref-grade-Ab12/src-cloth/cloth.cpp:185" -> "cloth.cpp:185"; "==1234==" -> "==".
std::string cleanLine(std::string line) {
  static const std::regex scratch(R"((/[^\s:()]*)?/src-[a-z]+/)");
  static const std::regex pid(R"(==[0-9]+==)");
  line = std::regex_replace(line, scratch, "");
  return std::regex_replace(line, pid, "==");
}

}  // namespace

bool hasCrash(const GradeReport& report) {
  if (report.verdict == Verdict::Crashed) return true;
  return std::any_of(report.tests.begin(), report.tests.end(), [](const TestResult& t) {
    return t.names("crashed");
  });
}

std::string firstSanitizerReport(const std::string& stderr_text, int max_lines) {
  static const std::regex frame(R"(^\s+#[0-9]+ )");
  static const std::regex student_file(R"(/src-[a-z]+/)");
  std::istringstream in(stderr_text);
  std::string quote, line;
  int lines = 0, skipped_frames = 0;
  bool inside = false, object_list = false;
  const auto add = [&](const std::string& text) {
    // Eigen's expression types make lines of a thousand characters.
    quote += (text.size() > 300 ? text.substr(0, 300) + " ..." : text) + "\n";
    ++lines;
  };
  const auto flushSkipped = [&] {
    if (skipped_frames && lines < max_lines)
      add("    ... (" + std::to_string(skipped_frames) +
          (skipped_frames == 1 ? " frame" : " frames") + " outside the student's files)");
    skipped_frames = 0;
  };
  while (lines < max_lines && std::getline(in, line)) {
    if (!inside && !isReportStart(line)) continue;
    inside = true;
    if (std::regex_search(line, frame) && !std::regex_search(line, student_file)) {
      ++skipped_frames;  // Eigen, the standard library, the driver, libc
      continue;
    }
    flushSkipped();
    if (line.find("This frame has") != std::string::npos) object_list = true;
    if (line.empty() || (object_list && line.find("This frame has") == std::string::npos &&
                         line.find("<==") == std::string::npos))
      continue;  // of the frame's objects, only the one accessed
    if (lines < max_lines) add(cleanLine(line));
  }
  flushSkipped();
  return quote;
}

std::optional<SanitizerFinding> sanitizerFinding(const fs::path& dir, const GradeReport& report,
                                                 const GradeOptions& options) {
  ScratchDir work("clothref-sanitize");
  GradeOptions sanitized = options;
  sanitized.toolchain.sanitize = true;
  sanitized.whole_run = false;
  sanitized.keep_work = work.path() / "work";  // the children's stderr, read below
  // Instrumented code runs 2-5x slower; the shadow memory needs no address-space limit.
  sanitized.limits.wall_seconds = options.limits.wall_seconds * 3;
  sanitized.limits.cpu_seconds = options.limits.cpu_seconds * 3;
  sanitized.limits.address_space_bytes = ~std::uint64_t{0};  // RLIM_INFINITY
  sanitized.edition = report.edition;
  gradeSubmission(dir, sanitized);

  std::optional<SanitizerFinding> first;
  for (const auto& group_stub : probeFolders()) {
    // named copies: clang 14 cannot capture a structured binding in the lambda below
    const auto& group = group_stub.first;
    const auto& stub = group_stub.second;
    const fs::path log = sanitized.keep_work / "probes" / group / "child.stderr";
    std::error_code error;
    if (!fs::exists(log, error)) continue;
    std::string text;
    try {
      text = readFile(log, "probe stderr");
    } catch (const std::exception&) {
      continue;  // an enormous stderr: look at the other groups
    }
    const std::string quote = firstSanitizerReport(text);
    if (quote.empty()) continue;
    SanitizerFinding finding{group, stub, quote};
    const bool crashed_here =
        std::any_of(report.tests.begin(), report.tests.end(), [&](const TestResult& t) {
          return t.stub == stub && t.names("crashed");
        });
    if (crashed_here) return finding;
    if (!first) first = finding;
  }
  return first;
}

void addSanitizerFinding(GradeReport& report, const std::optional<SanitizerFinding>& finding) {
  if (!finding) {
    report.notes.push_back(
        "Sanitizer report (`--sanitize`): rebuilt with `" + std::string(kSanitizeFlag) +
        " -g -O1`; no sanitizer report (the crash may depend on optimisation or be outside "
        "memory and undefined-behaviour errors).");
    return;
  }
  const std::string block = "Sanitizer report (`--sanitize`: rebuilt with `" +
                            std::string(kSanitizeFlag) + " -g -O1`, the `" + finding->group +
                            "` probe again):\n\n```\n" + finding->quote + "```\n";
  report.notes.push_back(block);
  // Once more where the student reads about the crash: the stub's first failed test.
  for (TestResult& t : report.tests)
    if (!t.passed() && !finding->stub.empty() && t.stub == finding->stub) {
      t.output += "\n\n" + block;
      break;
    }
}

void diagnoseCrashWithSanitizers(const fs::path& dir, GradeReport& report,
                                 const GradeOptions& options) {
  if (!hasCrash(report)) return;
  try {
    addSanitizerFinding(report, sanitizerFinding(dir, report, options));
  } catch (const std::exception& error) {
    report.notes.push_back(std::string("--sanitize: the sanitized rebuild failed: ") +
                           error.what());
  }
}

}  // namespace clothref::grader
