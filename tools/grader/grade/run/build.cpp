#include "grader/grade/run/build.h"

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

#ifndef CLOTHREF_GRADER_COURSE_DIR
#define CLOTHREF_GRADER_COURSE_DIR ""
#endif
#ifndef CLOTHREF_GRADER_REFERENCE_DIR
#define CLOTHREF_GRADER_REFERENCE_DIR ""
#endif
#ifndef CLOTHREF_GRADER_LIB_DIR
#define CLOTHREF_GRADER_LIB_DIR ""
#endif
#ifndef CLOTHREF_GRADER_PREBUILT_DIR
#define CLOTHREF_GRADER_PREBUILT_DIR ""
#endif
#ifndef CLOTHREF_DATA_FROM_BIN
#define CLOTHREF_DATA_FROM_BIN ""
#endif
#ifndef CLOTHREF_GRADER_EIGEN_INCLUDE
#define CLOTHREF_GRADER_EIGEN_INCLUDE "/usr/include/eigen3"
#endif

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

std::string fromEnv(const char* name, const char* fallback) {
  const char* value = std::getenv(name);
  return value && *value ? value : fallback;
}

std::vector<std::string> baseFlags(const CourseToolchain& t) {
  if (t.sanitize)
    return {t.compiler,    "-std=c++20",        "-O1",           "-g", "-fno-omit-frame-pointer",
            kSanitizeFlag, "-ffp-contract=off", "-fno-fast-math"};
  return {t.compiler, "-std=c++20", t.optimisation, "-ffp-contract=off", "-fno-fast-math"};
}

// Sanitizer defaults compiled into a sanitized probe (the child's environment is clean, so no
// ASAN_OPTIONS): no leak check at exit (a leak is not the crash we look for, and LeakSanitizer
// needs ptrace, which a sandbox may refuse).
constexpr const char* kSanitizerOptionsSource =
    "extern \"C\" const char* __asan_default_options() { return \"detect_leaks=0\"; }\n"
    "extern \"C\" const char* __ubsan_default_options() { return \"print_stacktrace=1\"; }\n";

// Unique among the threads of this process (a batch grades several submissions at once): the
// cache's temporary files carry it beside the pid.
std::string uniqueSuffix() {
  static std::atomic<unsigned long> counter{0};
  return std::to_string(getpid()) + "-" + std::to_string(counter++);
}

std::vector<std::string> compileCommand(const CourseToolchain& t, int edition,
                                        const fs::path& source, const fs::path& object,
                                        int particles_per_edge, const fs::path& pch = {}) {
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

}  // namespace

fs::path objectCachePath(const CourseToolchain& t, const std::vector<std::string>& command,
                         const fs::path& source, const fs::path& work_dir) {
  return cachePath(t, command, source, work_dir, t.trusted_sources);
}

std::vector<fs::path> ourFolders(const CourseToolchain& t) {
  std::vector<fs::path> candidates;
  const auto add = [&](const fs::path& path) {
    if (!path.empty()) candidates.push_back(fs::absolute(path).lexically_normal());
  };
  std::error_code error;
  const fs::path course = fs::absolute(t.course_dir).lexically_normal();
  const fs::path checkout = course.parent_path().parent_path().parent_path();
  add(fs::is_directory(checkout / "lib" / "clothref", error) ? checkout
                                                             : course.parent_path().parent_path());
  add(t.reference_dir);
  if (!t.prebuilt_dir.empty()) add(fs::absolute(t.prebuilt_dir).parent_path());
  if (!t.driver_lib_dir.empty())
    add(fs::absolute(t.driver_lib_dir).lexically_normal().parent_path().parent_path());
  add(t.cache_dir);
  const auto system = [&](const fs::path& path) {
    static const char* const folders[] = {
        "/",    "/usr",     "/usr/local", "/usr/share", "/opt", "/home",    "/root", "/tmp",
        "/var", "/var/tmp", "/etc",       "/srv",       "/run", "/dev/shm", "/mnt",  "/media"};
    for (const char* folder : folders)
      if (path == fs::path(folder)) return true;
    return path == fs::temp_directory_path(error).lexically_normal() || !path.has_relative_path();
  };
  const auto under = [](const fs::path& path, const fs::path& root) {
    const std::string p = path.string(), r = root.string();
    return p == r || (p.size() > r.size() && p.compare(0, r.size(), r) == 0 && p[r.size()] == '/');
  };
  std::vector<fs::path> ours;
  for (const fs::path& path : candidates) {
    if (system(path)) continue;
    bool inside = false;
    for (const fs::path& other : candidates)
      inside = inside || (other != path && !system(other) && under(path, other));
    if (!inside && std::find(ours.begin(), ours.end(), path) == ours.end()) ours.push_back(path);
  }
  return ours;
}

CourseToolchain defaultToolchain() {
  CourseToolchain t;
  // An install keeps the course side in <prefix>/share/clothref/grader; a build tree uses the
  // source tree's and its own.
  const fs::path installed = installedDataDir(CLOTHREF_DATA_FROM_BIN) / "grader";
  const bool from_install = !installed.parent_path().empty() && fs::is_directory(installed);
  const auto where = [&](const char* name, const char* relative, const char* built) {
    return fromEnv(name, from_install ? (installed / relative).c_str() : built);
  };
  t.course_dir = where("CLOTHREF_GRADER_COURSE_DIR", "course", CLOTHREF_GRADER_COURSE_DIR);
  t.reference_dir =
      where("CLOTHREF_GRADER_REFERENCE_DIR", "reference", CLOTHREF_GRADER_REFERENCE_DIR);
  t.driver_lib_dir = where("CLOTHREF_GRADER_LIB_DIR", "lib", CLOTHREF_GRADER_LIB_DIR);
  t.prebuilt_dir = where("CLOTHREF_GRADER_PREBUILT_DIR", "prebuilt", CLOTHREF_GRADER_PREBUILT_DIR);
  t.eigen_include = CLOTHREF_GRADER_EIGEN_INCLUDE;
  t.compiler = fromEnv("CLOTHREF_GRADER_CXX", "g++");
  return t;
}

bool prebuildCourse(const CourseToolchain& given, const std::vector<int>& editions,
                    const fs::path& out_dir, const fs::path& work_dir, std::string* problem) {
  CourseToolchain t = given;
  t.cache_dir = fs::absolute(out_dir);
  t.prebuilt_dir.clear();
  t.trusted_sources = true;  // our reference files: keyed for every isolation
  std::set<std::string> wanted;
  for (const int edition : editions) {
    const fs::path pch = precompiledHeader(t, edition, work_dir);
    if (pch.empty()) {
      if (problem) *problem = "the precompiled header of " + std::to_string(edition) + " failed";
      return false;
    }
    wanted.insert(pch.parent_path().filename().string());
    std::vector<std::vector<std::string>> commands;
    for (const std::string& name : studentFileNames()) {
      const fs::path source = t.reference_dir / std::to_string(edition) / name;
      commands.push_back(compileCommand(t, edition, source, work_dir / (name + ".o"), 25, pch));
      wanted.insert(cachePath(t, commands.back(), source, work_dir, true).filename().string());
    }
    const std::vector<ToolRun> runs = compileAll(t, commands, work_dir);
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (!runs[k].ok) {
        if (problem) *problem = "our reference " + studentFileNames()[k] + " does not compile";
        return false;
      }
  }
  // What an older clothref built (other headers or flags) is never found again: remove it.
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(t.cache_dir, error))
    if (!wanted.count(entry.path().filename().string())) fs::remove_all(entry.path(), error);
  return true;
}

ProbeBuild buildProbes(const SubmissionFiles& files, int edition, const CourseToolchain& given,
                       const fs::path& work_dir) {
  // Compiles run inside the scratch folder: every path they get must be absolute.
  CourseToolchain toolchain = given;
  if (!toolchain.cache_dir.empty()) toolchain.cache_dir = fs::absolute(toolchain.cache_dir);
  if (!toolchain.prebuilt_dir.empty())
    toolchain.prebuilt_dir = fs::absolute(toolchain.prebuilt_dir);
  ProbeBuild build;
  const std::string ed = std::to_string(edition);
  const auto stem = [](const std::string& name) { return name.substr(0, name.size() - 4); };

  fs::path pch = precompiledHeader(toolchain, edition, work_dir);
  if (toolchain.kit && !pch.empty()) pch = kitHeader(*toolchain.kit, pch);
  // What a compile's messages may quote (run/compiler_messages.h): `source` itself and the headers.
  const auto site = [&](const fs::path& source, const std::string& name) {
    return CompileSite{work_dir, source, name,
                       courseHeaderDirs(toolchain.course_dir, edition, toolchain.eigen_include)};
  };
  // 1. Student files, each alone in its folder; plus cloth.cpp at the second size.
  std::vector<std::vector<std::string>> commands;
  std::vector<std::string> names;
  for (const std::string& name : studentFileNames()) {
    UsedFile used;
    used.name = name;
    auto found = files.found.find(name);
    if (found == files.found.end()) {
      used.status = Verdict::MissingFile;
      used.problem = "missing";
      build.files.push_back(used);
      continue;
    }
    used.path = found->second.string();
    const fs::path folder = work_dir / ("src-" + stem(name));
    fs::create_directories(folder);
    // The bytes the finder read through a checked descriptor, never the student's path again.
    std::ofstream copy(folder / name, std::ios::binary | std::ios::trunc);
    copy << files.bytes.at(name);
    if (!copy.flush()) throw std::runtime_error("cannot copy " + name + " into the scratch folder");
    commands.push_back(
        compileCommand(toolchain, edition, folder / name, work_dir / (stem(name) + ".o"), 25, pch));
    names.push_back(name);
    if (name == "cloth.cpp") {
      commands.push_back(compileCommand(toolchain, edition, folder / name,
                                        work_dir / "cloth-small.o", kSecondParticlesPerEdge, pch));
      names.push_back("cloth-small");
    }
    build.files.push_back(used);
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<ToolRun> runs = compileAll(toolchain, commands, work_dir);
  bool small_compiled = false;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == "cloth-small") {
      small_compiled = runs[k].ok;
      if (!runs[k].ok)
        build.small_problem = firstCompilerError(
            runs[k].output, site(work_dir / "src-cloth" / "cloth.cpp", "cloth.cpp"));
      continue;
    }
    for (UsedFile& used : build.files)
      if (used.name == names[k]) {
        used.compiled = runs[k].ok;
        used.compile_seconds = runs[k].seconds;
        if (!runs[k].ok) {
          used.status = Verdict::CompileError;
          const CompileSite where =
              site(work_dir / ("src-" + stem(used.name)) / used.name, used.name);
          used.problem = firstCompilerError(runs[k].output, where);
          used.log = compilerLog(runs[k].output, where);
        }
      }
  }

  // 2. Our reference version for every file that is missing or did not compile: our own source,
  // compiled (when nothing prebuilt matches) with the grader's uid, which alone may read it, and
  // keyed as our prebuilt objects are. No student compile runs in this folder after it.
  CourseToolchain ours = toolchain;
  ours.isolation = Isolation{};
  ours.trusted_sources = true;
  commands.clear();
  names.clear();
  for (const UsedFile& used : build.files) {
    if (used.compiled) continue;
    const fs::path reference = toolchain.reference_dir / ed / used.name;
    commands.push_back(
        compileCommand(ours, edition, reference, work_dir / (stem(used.name) + ".o"), 25, pch));
    names.push_back(used.name);
  }
  runs = compileAll(ours, commands, work_dir);
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (!runs[k].ok) {
      build.problem = "our reference " + names[k] + " for " + ed + " does not compile: " +
                      firstCompilerError(runs[k].output,
                                         site(toolchain.reference_dir / ed / names[k], names[k]));
      return build;
    }
  build.compile_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // 3. Link. A link error (e.g. a framework function deleted) makes us swap in our version of
  // the file the linker complains about, one file at a time.
  const auto link_start = std::chrono::steady_clock::now();
  const fs::path driver_lib = toolchain.driver_lib_dir / ("libclothref_grader_course_" + ed + ".a");
  fs::path sanitizer_options;
  if (toolchain.sanitize) {
    std::ofstream(work_dir / "sanitizer_options.cpp") << kSanitizerOptionsSource;
    sanitizer_options = work_dir / "sanitizer_options.o";
    const ToolRun built =
        runTools({{toolchain.compiler, "-c", (work_dir / "sanitizer_options.cpp").string(), "-o",
                   sanitizer_options.string()}},
                 work_dir, 1, toolchain.compile_seconds, &toolchain.isolation)
            .front();
    if (!built.ok) sanitizer_options.clear();
  }
  const auto link = [&](const std::vector<fs::path>& objects, const fs::path& out) {
    std::vector<std::string> command = {toolchain.compiler, "-o", out.string()};
    if (toolchain.sanitize) command.push_back(kSanitizeFlag);
    if (!sanitizer_options.empty()) command.push_back(sanitizer_options.string());
    for (const auto& o : objects) command.push_back(o.string());
    command.push_back(driver_lib.string());
    return checked(
        runTools({command}, work_dir, 1, toolchain.compile_seconds, &toolchain.isolation).front());
  };
  std::vector<fs::path> objects = {work_dir / "cloth.o", work_dir / "sphere.o",
                                   work_dir / "integrator.o"};
  build.probe = work_dir / "probe";
  ToolRun linked = link(objects, build.probe);
  for (UsedFile& used : build.files) {
    if (linked.ok) break;
    if (!used.compiled) continue;
    const CompileSite where = site({}, used.name);
    const std::string error = firstCompilerError(linked.output, where);
    const std::string log = compilerLog(linked.output, where);
    std::vector<std::string> ref =
        compileCommand(ours, edition, ours.reference_dir / ed / used.name,
                       work_dir / (stem(used.name) + "-ref.o"), 25, pch);
    if (!compileAll(ours, {ref}, work_dir).front().ok) continue;
    std::vector<fs::path> swapped = objects;
    for (auto& o : swapped)
      if (o.filename() == stem(used.name) + ".o") o = work_dir / (stem(used.name) + "-ref.o");
    ToolRun retry = link(swapped, build.probe);
    if (retry.ok) {
      used.compiled = false;
      used.status = Verdict::LinkError;
      used.problem = "link error: " + error;
      used.log = log;
      objects = swapped;
      linked = retry;
    }
  }
  if (!linked.ok) {
    build.problem = "the probe does not link: " + firstCompilerError(linked.output, site({}, ""));
    return build;
  }
  // The second-size springs probe: the student's cloth.cpp rebuilt, the rest as above.
  const bool cloth_is_students = build.files[0].compiled;
  if (cloth_is_students && small_compiled) {
    std::vector<fs::path> small = objects;
    small[0] = work_dir / "cloth-small.o";
    build.probe_small = work_dir / "probe-small";
    const ToolRun small_link = link(small, build.probe_small);
    build.small_ok = small_link.ok;
    if (!small_link.ok)
      build.small_problem = firstCompilerError(small_link.output, site({}, "cloth.cpp"));
  }
  build.link_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - link_start).count();
  build.ok = true;
  return build;
}

}  // namespace clothref::grader
