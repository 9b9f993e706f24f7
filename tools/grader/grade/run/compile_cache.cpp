#include "grader/grade/run/compile_cache.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "clothref/io/files.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/compiler_messages.h"
#include "grader/grade/run/tools.h"

#ifndef CLOTHREF_DATA_FROM_BIN
#define CLOTHREF_DATA_FROM_BIN ""
#endif

namespace clothref::grader {
namespace fs = std::filesystem;

std::vector<std::string> baseFlags(const CourseToolchain& t) {
  // Without variable tracking (locations of local variables for a debugger; the sanitizers'
  // reports name functions, files and lines only): with UBSan's checks it was more than half of an
  // instrumented compile (issue 39: 17 of 22 s of CPU for cloth.cpp, 7 s without it). -Og, not
  // -O1: -O1's inlining of Eigen's instrumented calls was most of what was left (integrator.cpp
  // 5.0 s of CPU at -O1, 2.1 s at -Og, every check kept; the reports name the same lines).
  if (t.sanitize)
    return {t.compiler,
            "-std=c++20",
            "-Og",
            "-g",
            "-fno-var-tracking-assignments",
            "-fno-var-tracking",
            "-fno-omit-frame-pointer",
            kSanitizeFlag,
            "-ffp-contract=off",
            "-fno-fast-math"};
  return {t.compiler, "-std=c++20", t.optimisation, "-ffp-contract=off", "-fno-fast-math"};
}

// Unique among the threads of this process (a batch grades several submissions at once): the
// cache's temporary files carry it beside the pid.
std::string uniqueSuffix() {
  static std::atomic<unsigned long> counter{0};
  return std::to_string(getpid()) + "-" + std::to_string(counter++);
}

namespace {

// FNV-1a, 64 bits: a cache key, not a security boundary (objects only ever come from our compiler).
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// The bytes of every stand-in file under their relative names (once per course folder): where
// the course folder lives (source tree, install) is no part of a key.
std::uint64_t courseHeadersHash(const CourseToolchain& t) {
  static std::mutex mutex;
  static std::map<fs::path, std::uint64_t> known;
  const std::lock_guard lock(mutex);
  auto found = known.find(t.course_dir);
  if (found != known.end()) return found->second;
  std::uint64_t h = 0;
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(t.course_dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) h = fnv1a(fs::relative(f, t.course_dir).string() + readBytes(f), h);
  return known[t.course_dir] = h;
}

// A compile argument as a key sees it: the course folder's location replaced by a name, and a
// precompiled header by its folder's name (which is its key), so objects built with clothref
// (`prebuilt_dir`) are found wherever clothref is installed.
std::string keyArgument(const CourseToolchain& t, const std::string& arg) {
  const std::string course = t.course_dir.string();
  std::string out = arg;
  for (std::size_t at; !course.empty() && (at = out.find(course)) != std::string::npos;)
    out.replace(at, course.size(), "<course>");
  if (out.size() > 13 && out.compare(out.size() - 13, 13, "/course_pch.h") == 0)
    out = "<pch>/" + fs::path(out).parent_path().filename().string();
  return out;
}

// What names the compiler in a key: its `--version` text (asked once per process), so an
// upgraded or another compiler never reuses a precompiled header or an object of the old one.
std::string compilerIdentity(const CourseToolchain& t, const fs::path& work_dir) {
  static std::mutex mutex;
  static std::map<std::string, std::string> known;
  const std::lock_guard lock(mutex);
  auto found = known.find(t.compiler);
  if (found != known.end()) return found->second;
  const ToolRun run = runTools({{t.compiler, "--version"}}, work_dir, 1, 30, nullptr).front();
  return known[t.compiler] = run.ok ? run.output : std::string();
}

// How a compile was confined: an object built unconfined (the fallback as a non-root user) may
// hold host bytes (`.incbin`), so it is never reused by a confined run, nor the other way round.
std::string confinement(const Isolation& isolation) {
  switch (isolation.kind) {
    case IsolationKind::Bubblewrap:
      return "bubblewrap";
    case IsolationKind::Rlimits:
      // which tool uid does not matter (each grade holds its own), whether there is one does
      return isolation.tool_uid >= 0 ? "rlimits tool-uid" : "rlimits grader-uid";
    case IsolationKind::None:
      break;
  }
  return "none";
}

}  // namespace

// The cache file for a compile command: its flags (paths of the source and object excluded), the
// bytes of the source and of every stand-in header, the compiler's identity and, for student
// files, how the compile was confined. Our own reference files (`trusted`: prebuilt with
// clothref) are keyed without the confinement, so the prebuilt objects serve every isolation.
fs::path cachePath(const CourseToolchain& t, const std::vector<std::string>& command,
                   const fs::path& source, const fs::path& work_dir, bool trusted) {
  std::uint64_t hash = fnv1a(readBytes(source));
  for (std::size_t k = 0; k + 1 < command.size(); ++k) {
    if (command[k] == "-c" || command[k] == "-o") {
      ++k;
      continue;
    }
    hash = fnv1a(keyArgument(t, command[k]) + '\n', hash);
  }
  hash = fnv1a(std::to_string(courseHeadersHash(t)), hash);
  hash = fnv1a(compilerIdentity(t, work_dir), hash);
  if (!trusted) hash = fnv1a(confinement(t.isolation), hash);
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.o", static_cast<unsigned long long>(hash));
  return t.cache_dir / name;
}

namespace {

// The headers every file of an edition sees, in a fixed order: the std and Eigen headers course
// files include, then every stand-in header except configs.h (the springs probe's second build
// sets its particlesPerEdge, so it stays outside the precompiled part and one header serves
// both sizes). Including more than a student's file does is harmless: the stand-in headers are
// the course's, and a name they bring is one the course's own build has too.
std::string precompiledHeaderText(const CourseToolchain& t, int edition) {
  std::string text =
      "#include <algorithm>\n#include <cmath>\n#include <filesystem>\n#include <functional>\n"
      "#include <iostream>\n#include <stdexcept>\n#include <string>\n#include <vector>\n"
      "#include <Eigen/Core>\n#include <Eigen/Dense>\n";
  std::vector<std::string> names;
  for (const fs::path& dir :
       {t.course_dir / std::to_string(edition) / "include", t.course_dir / "common" / "include"}) {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(dir, error))
      if (entry.path().extension() == ".h" && entry.path().filename() != "configs.h")
        names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) text += "#include \"" + name + "\"\n";
  return text;
}

// The compile of an edition's precompiled header, written to `dir`.
std::vector<std::string> precompileCommand(const CourseToolchain& t, int edition,
                                           const fs::path& dir) {
  const std::string ed = std::to_string(edition);
  std::vector<std::string> command = baseFlags(t);
  command.insert(command.end(),
                 {"-fdiagnostics-color=never", "-DCLOTHREF_GRADER_EDITION_" + ed,
                  "-I" + (t.course_dir / ed / "include").string(),
                  "-I" + (t.course_dir / "common" / "include").string(), "-isystem",
                  t.eigen_include.string(), "-x", "c++-header", (dir / "course_pch.h").string(),
                  "-o", (dir / "course_pch.h.gch").string()});
  return command;
}

// The folder name of an edition's precompiled header: its key is the compiler's identity, the
// command (paths of the header itself excluded), the header's text, the bytes of every stand-in
// header and Eigen's version header (gcc never checks whether a header changed since).
std::string precompiledHeaderName(const CourseToolchain& t, int edition, const fs::path& work_dir) {
  std::uint64_t hash = fnv1a("clothref-grader-pch-2\n" + compilerIdentity(t, work_dir));
  for (const std::string& arg : precompileCommand(t, edition, {}))
    if (arg.find("course_pch.h") == std::string::npos)
      hash = fnv1a(keyArgument(t, arg) + '\n', hash);
  hash = fnv1a(precompiledHeaderText(t, edition), hash);
  hash = fnv1a(std::to_string(courseHeadersHash(t)), hash);
  hash = fnv1a(readBytes(t.eigen_include / "Eigen" / "src" / "Core" / "util" / "Macros.h"), hash);
  char name[40];
  std::snprintf(name, sizeof name, "pch-%016llx", static_cast<unsigned long long>(hash));
  return name;
}

}  // namespace

// The edition's precompiled stand-in headers (the `-include` file; gcc takes the .gch beside it):
// the one built with clothref (`prebuilt_dir`) when its key matches, else the cache's, built there
// on first use (once per process: concurrent submissions of a batch wait for it). Without either,
// none: building one costs about as much as the four compiles it speeds up.
fs::path precompiledHeader(const CourseToolchain& t, int edition, const fs::path& work_dir) {
  if (t.cache_dir.empty() && t.prebuilt_dir.empty()) return {};
  const std::string name = precompiledHeaderName(t, edition, work_dir);
  std::error_code error;
  for (const fs::path& root : {t.prebuilt_dir, t.cache_dir})
    if (!root.empty() && fs::exists(root / name / "course_pch.h.gch", error))
      return root / name / "course_pch.h";
  if (t.cache_dir.empty()) return {};
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  const fs::path dir = t.cache_dir / name;
  if (fs::exists(dir / "course_pch.h.gch", error)) return dir / "course_pch.h";
  const fs::path temporary = t.cache_dir / (name + ".tmp" + uniqueSuffix());
  fs::create_directories(temporary, error);
  std::ofstream(temporary / "course_pch.h") << precompiledHeaderText(t, edition);
  const bool built = runTools({precompileCommand(t, edition, temporary)}, work_dir, 1,
                              t.compile_seconds, &t.isolation)
                         .front()
                         .ok;
  if (built) fs::rename(temporary, dir, error);  // another grader may have won: use theirs
  fs::remove_all(temporary, error);
  return fs::exists(dir / "course_pch.h.gch", error) ? dir / "course_pch.h" : fs::path();
}

// A stored object (prebuilt or cached) copied into a build folder for the link, readable by the
// link's uid whatever mode the store gave it (a Gradescope image closes our tree: 0600).
bool copyObject(const fs::path& from, const fs::path& object) {
  std::error_code error;
  return fs::exists(from, error) &&
         fs::copy_file(from, object, fs::copy_options::overwrite_existing, error) &&
         chmod(object.c_str(), 0644) == 0;
}

// The object built with clothref for this command (our reference files), copied to `object`.
bool fromPrebuilt(const CourseToolchain& t, const std::vector<std::string>& command,
                  const fs::path& source, const fs::path& object) {
  if (t.prebuilt_dir.empty()) return false;
  return copyObject(
      t.prebuilt_dir / cachePath(t, command, source, object.parent_path(), true).filename(),
      object);
}

namespace {

// Sanitizer defaults compiled into a sanitized probe: no leak check (LeakSanitizer needs ptrace).
// GCC's libubsan ignores UBSAN_OPTIONS' log_path (sanitizerLimits): given it before student code.
constexpr const char* kSanitizerOptionsSource =
    "#include <dlfcn.h>\n#include <stdlib.h>\n"
    "extern \"C\" const char* __asan_default_options() { return \"detect_leaks=0\"; }\n"
    "extern \"C\" const char* __ubsan_default_options() { return \"print_stacktrace=1\"; }\n"
    "__attribute__((constructor(101))) static void clothrefUbsanReportPath() {\n"
    "  const char* path = getenv(\"CLOTHREF_SANITIZER_LOG\");\n"
    "  void* ubsan = path ? dlopen(\"libubsan.so.1\", RTLD_NOLOAD | RTLD_LAZY) : nullptr;\n"
    "  void* set = ubsan ? dlsym(ubsan, \"__sanitizer_set_report_path\") : nullptr;\n"
    "  if (set) reinterpret_cast<void (*)(const char*)>(set)(path);\n}\n";

}  // namespace

std::vector<std::string> compileCommand(const CourseToolchain& t, int edition,
                                        const fs::path& source, const fs::path& object,
                                        int particles_per_edge, const fs::path& pch) {
  const std::string ed = std::to_string(edition);
  std::vector<std::string> command = baseFlags(t);
  command.insert(command.end(), {"-fmax-errors=3", "-fdiagnostics-color=never",
                                 "-DCLOTHREF_GRADER_EDITION_" + ed});
  if (!pch.empty()) command.insert(command.end(), {"-include", pch.string()});
  if (particles_per_edge != 25)
    command.push_back("-DCLOTHREF_GRADER_PARTICLES_PER_EDGE=" + std::to_string(particles_per_edge));
  command.insert(command.end(),
                 {"-I" + (t.course_dir / ed / "include").string(),
                  "-I" + (t.course_dir / "common" / "include").string(), "-isystem",
                  t.eigen_include.string(), "-c", source.string(), "-o", object.string()});
  return command;
}

// A compile or link the grader could not run (ToolRun::ours): the grade stops as ours.
const ToolRun& checked(const ToolRun& run) {
  if (run.ours) throw GraderFault(run.output.substr(0, run.output.find('\n')));
  return run;
}

// Runs the compile commands, taking objects from the cache where it has them and filling it.
std::vector<ToolRun> compileAll(const CourseToolchain& t,
                                const std::vector<std::vector<std::string>>& commands,
                                const fs::path& work_dir) {
  std::vector<ToolRun> results(commands.size());
  std::vector<std::vector<std::string>> to_run;
  std::vector<std::size_t> index;
  std::vector<fs::path> cached(commands.size());
  for (std::size_t k = 0; k < commands.size(); ++k) {
    const auto& c = commands[k];
    const fs::path source = *(std::find(c.begin(), c.end(), "-c") + 1);
    const fs::path object = *(std::find(c.begin(), c.end(), "-o") + 1);
    std::error_code error;
    if (!t.cache_dir.empty()) {
      cached[k] = cachePath(t, c, source, work_dir, t.trusted_sources);
      if (copyObject(cached[k], object)) {
        results[k].ok = true;
        continue;
      }
    }
    if (fromPrebuilt(t, c, source, object)) {
      results[k].ok = true;
      continue;
    }
    to_run.push_back(c);
    index.push_back(k);
  }
  const std::vector<ToolRun> runs =
      runTools(to_run, work_dir, t.jobs, t.compile_seconds, &t.isolation);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::size_t k = index[r];
    results[k] = checked(runs[r]);
    if (!runs[r].ok || cached[k].empty()) continue;
    const auto& c = commands[k];
    const fs::path object = *(std::find(c.begin(), c.end(), "-o") + 1);
    std::error_code error;
    fs::create_directories(t.cache_dir, error);
    const fs::path temporary = cached[k].string() + ".tmp" + uniqueSuffix();
    if (fs::copy_file(object, temporary, fs::copy_options::overwrite_existing, error))
      fs::rename(temporary, cached[k], error);  // atomic: concurrent graders never see half a file
  }
  return results;
}

// Our own reference files and helpers are compiled with the grader's uid, unconfined (only it may
// read them), and keyed as the objects prebuilt with clothref are.
CourseToolchain oursOf(const CourseToolchain& toolchain) {
  CourseToolchain ours = toolchain;
  ours.isolation = Isolation{};
  ours.trusted_sources = true;
  return ours;
}

// The object holding the sanitizer's defaults (kSanitizerOptionsSource), compiled into
// `work_dir` (prebuilt with clothref, cached, or compiled here); empty when it fails.
fs::path sanitizerOptionsObject(const CourseToolchain& toolchain, const fs::path& work_dir) {
  const fs::path source = work_dir / "sanitizer_options.cpp";
  const fs::path object = work_dir / "sanitizer_options.o";
  std::ofstream(source) << kSanitizerOptionsSource;
  const CourseToolchain ours = oursOf(toolchain);
  const ToolRun built =
      compileAll(ours, {{ours.compiler, "-c", source.string(), "-o", object.string()}}, work_dir)
          .front();
  return built.ok ? object : fs::path();
}

// The link of a probe: the objects in order, the driver library last; with the sanitizer's flag
// and defaults for a sanitized build.
std::vector<std::string> linkCommand(const CourseToolchain& toolchain, int edition,
                                     const std::vector<fs::path>& objects,
                                     const fs::path& sanitizer_options, const fs::path& out) {
  std::vector<std::string> command = {toolchain.compiler, "-o", out.string()};
  if (toolchain.sanitize) command.push_back(kSanitizeFlag);
  if (!sanitizer_options.empty()) command.push_back(sanitizer_options.string());
  for (const auto& o : objects) command.push_back(o.string());
  command.push_back(
      (toolchain.driver_lib_dir / ("libclothref_grader_course_" + std::to_string(edition) + ".a"))
          .string());
  return command;
}

// Paths a compile or link in the scratch folder gets are absolute.
CourseToolchain absolutePaths(const CourseToolchain& given) {
  CourseToolchain toolchain = given;
  if (!toolchain.cache_dir.empty()) toolchain.cache_dir = fs::absolute(toolchain.cache_dir);
  if (!toolchain.prebuilt_dir.empty())
    toolchain.prebuilt_dir = fs::absolute(toolchain.prebuilt_dir);
  return toolchain;
}

}  // namespace clothref::grader
