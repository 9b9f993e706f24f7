#include "grader/grade/run/sanitize.h"

#include <algorithm>
#include <chrono>
#include <regex>
#include <sstream>
#include <vector>

#include "clothref/io/files.h"
#include "grader/bridge/probe_keys.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

bool isReportStart(const std::string& line) {
  return line.find("ERROR: AddressSanitizer") != std::string::npos ||
         line.find("ERROR: LeakSanitizer") != std::string::npos ||
         line.find("runtime error:") != std::string::npos;
}

// "/tmp/clothref-grade-Ab12/src-cloth/cloth.cpp:185" -> "cloth.cpp:185"; "==1234==" -> "==";
// "0x7ffc985ec210" -> "0x...": addresses change from run to run, and a grade must not.
std::string cleanLine(std::string line) {
  static const std::regex scratch(R"((/[^\s:()]*)?/src-[a-z]+/)");
  // Any other path (the course kit's headers, the probe, a library) by its file name only.
  static const std::regex host_path(R"((^|[\s(])/[^\s:()]*/([^/\s:()]+))");
  static const std::regex pid(R"(==[0-9]+==)");
  static const std::regex address(R"(0x[0-9a-f]{6,})");
  line = std::regex_replace(line, scratch, "");
  line = std::regex_replace(line, host_path, "$1$2");
  line = std::regex_replace(line, address, "0x...");
  return std::regex_replace(line, pid, "==");
}

}  // namespace

std::string firstSanitizerReport(const std::string& stderr_text, int max_lines) {
  static const std::regex frame(R"(^\s+#[0-9]+ )");
  static const std::regex student_file(R"(/src-[a-z]+/)");
  std::istringstream in(stderr_text);
  std::string quote, line;
  int lines = 0, skipped_frames = 0;
  bool inside = false, object_list = false, students = false;
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
    students = students || std::regex_search(line, student_file);
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
  // A report with no line in the student's files (the framework's Cloth::~Cloth(), the driver)
  // is not the student's to read: the rest of it is looked through before saying so.
  while (inside && !students && std::getline(in, line)) {
    if (isReportStart(line)) break;
    students = std::regex_search(line, student_file);
  }
  return students ? quote : std::string();
}

std::string lastSanitizerReport(const std::string& channel, int max_lines) {
  std::size_t start = std::string::npos;
  std::istringstream in(channel);
  std::size_t at = 0;
  for (std::string line; std::getline(in, line); at += line.size() + 1)
    if (isReportStart(line)) start = at;
  return start == std::string::npos ? std::string()
                                    : firstSanitizerReport(channel.substr(start), max_lines);
}

ChildLimits sanitizerLimits(const ChildLimits& probe) {
  ChildLimits limits = probe;
  limits.slot_wait_seconds = slotWait(probe);
  limits.wall_seconds = probe.wall_seconds * kSanitizerSlowdown;
  limits.cpu_seconds = static_cast<std::uint64_t>(double(probe.cpu_seconds) * kSanitizerSlowdown);
  limits.address_space_bytes = ~std::uint64_t{0};  // RLIM_INFINITY
  const std::uint64_t bounded =
      std::min(probe.address_space_bytes,
               probe.memory_bytes > 0 ? probe.memory_bytes : probe.address_space_bytes);
  limits.memory_bytes = (bounded + bounded / 8 + kSanitizerRuntimeBytes);
  limits.sanitizer_channel = true;
  limits.log = nullptr;  // it explains; it never decides a verdict
  limits.answers = nullptr;
  limits.keep_files = false;
  limits.fixed_layout = false;
  const std::string channel = std::string("log_path=") + kSanitizerReportName;
  limits.environment = {
      "ASAN_OPTIONS=" + channel + ":detect_leaks=0:halt_on_error=1:quarantine_size_mb=64" +
          ":hard_rss_limit_mb=" + std::to_string(limits.memory_bytes >> 20),
      "UBSAN_OPTIONS=" + channel + ":halt_on_error=1:print_stacktrace=1",
      // read by the sanitized probe's own options (build.cpp): GCC's libubsan keeps a report
      // file of its own, which UBSAN_OPTIONS' log_path does not reach
      std::string("CLOTHREF_SANITIZER_LOG=") + kSanitizerReportName};
  return limits;
}

std::vector<std::string> filesRunBy(const std::string& group) {
  namespace g = probe::group;
  if (group == g::kSprings || group == g::kForces) return {"cloth.cpp"};
  if (group == g::kCollideCloth || group == g::kCollideSpheres) return {"cloth.cpp", "sphere.cpp"};
  if (group == g::kIntegrate) return {"integrator.cpp"};
  return studentFileNames();
}

SanitizedProbes::SanitizedProbes(const SubmissionFiles& files, int edition,
                                 CourseToolchain toolchain, const GradeScratch& scratch,
                                 ChildLimits limits, const ProbeBuild& base)
    : scratch_(scratch), limits_(sanitizerLimits(limits)) {
  toolchain.sanitize = true;
  rebuilder_ = std::make_unique<ProbeRebuilder>(
      base, files, edition, toolchain,
      [&scratch](const std::string& set) { return scratch.extraBuild("sanitize-" + set); });
}

double SanitizedProbes::seconds() const {
  const std::lock_guard lock(seconds_mutex_);
  return seconds_;
}

std::string SanitizedProbes::explain(const probe::ProbeMessage& request, const fs::path& folder) {
  const auto start = std::chrono::steady_clock::now();
  struct Timed {
    SanitizedProbes& self;
    std::chrono::steady_clock::time_point start;
    ~Timed() {
      const std::lock_guard lock(self.seconds_mutex_);
      self.seconds_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } timed{*this, start};
  fs::path instrumented;
  try {
    const std::vector<std::string> files = filesRunBy(request.text(probe::key::kGroup));
    const fs::path built = rebuilder_->probe(files);
    const std::lock_guard lock(mutex_);
    const auto [at, added] = published_.try_emplace(built.filename().string());
    if (added && !built.empty())
      at->second = scratch_.publish(built, built.filename().string() + "-sanitize");
    instrumented = at->second;
  } catch (const std::exception&) {
    instrumented.clear();  // no explanation; the grade stands
  }
  if (instrumented.empty()) return "";
  std::error_code error;
  fs::create_directories(folder, error);
  const ChildRun run = runProbe(instrumented, request, folder, limits_);
  // Only the run that ended at a report: one that answered first reported after the probe's
  // work (a destructor at exit), and the student's stderr is never read for a report.
  if (run.answered ||
      (run.status != ChildStatus::Crashed && run.status != ChildStatus::ExitedNonZero))
    return "";
  return lastSanitizerReport(run.sanitizer_report);
}

}  // namespace clothref::grader
