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
#include "grader/grade/run/compile_cache.h"
#include "grader/grade/run/compiler_messages.h"
#include "grader/grade/run/tools.h"
#include "grader/grade/submission/neighbours.h"

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
  std::vector<fs::path> ours;
  for (const fs::path& path : candidates) {
    if (system(path)) continue;
    bool inside = false;
    for (const fs::path& other : candidates)
      inside = inside || (other != path && !system(other) && isUnder(path, other));
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

namespace {

// One edition's precompiled header and our three reference objects for `t`'s flags, into its
// cache (the prebuilt folder); their names go to `wanted`.
bool prebuildEdition(const CourseToolchain& t, int edition, const fs::path& work_dir,
                     std::set<std::string>& wanted, std::string* problem) {
  const std::string what = std::to_string(edition) + (t.sanitize ? " (sanitizer)" : "");
  const fs::path pch = precompiledHeader(t, edition, work_dir);
  if (pch.empty()) {
    if (problem) *problem = "the precompiled header of " + what + " failed";
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
      if (problem)
        *problem = "our reference " + studentFileNames()[k] + " of " + what + " does not compile";
      return false;
    }
  return true;
}

}  // namespace

bool prebuildCourse(const CourseToolchain& given, const std::vector<int>& editions,
                    const fs::path& out_dir, const fs::path& work_dir, std::string* problem) {
  CourseToolchain t = given;
  t.cache_dir = fs::absolute(out_dir);
  t.prebuilt_dir.clear();
  t.trusted_sources = true;  // our reference files: keyed for every isolation
  // Our own files at build time: no limit meant for students' compiles on a loaded machine (an
  // instrumented header or object takes minutes of wall time there).
  t.compile_seconds = 3600;
  std::set<std::string> wanted;
  // The normal build, then the sanitizer's (ProbeRebuilder): its own precompiled header, our
  // reference objects for files that did not build, and the object of its defaults.
  for (const bool sanitize : {false, true})
    for (const int edition : editions) {
      t.sanitize = sanitize;
      if (!prebuildEdition(t, edition, work_dir, wanted, problem)) return false;
    }
  const fs::path options = sanitizerOptionsObject(t, work_dir);
  if (options.empty()) {
    if (problem) *problem = "the sanitizer's defaults (sanitizer_options.cpp) do not compile";
    return false;
  }
  const fs::path options_source = work_dir / "sanitizer_options.cpp";
  wanted.insert(cachePath(t, {t.compiler, "-c", options_source.string(), "-o", options.string()},
                          options_source, work_dir, true)
                    .filename()
                    .string());
  // What an older clothref built (other headers or flags) is never found again: remove it.
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(t.cache_dir, error))
    if (!wanted.count(entry.path().filename().string())) fs::remove_all(entry.path(), error);
  return true;
}

ProbeBuild buildProbes(const SubmissionFiles& files, int edition, const CourseToolchain& given,
                       const fs::path& work_dir) {
  // Compiles run inside the scratch folder: every path they get must be absolute.
  const CourseToolchain toolchain = absolutePaths(given);
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
  const CourseToolchain ours = oursOf(toolchain);
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
  const fs::path sanitizer_options =
      toolchain.sanitize ? sanitizerOptionsObject(toolchain, work_dir) : fs::path();
  const auto link = [&](const std::vector<fs::path>& objects, const fs::path& out) {
    return checked(runTools({linkCommand(toolchain, edition, objects, sanitizer_options, out)},
                            work_dir, 1, toolchain.compile_seconds, &toolchain.isolation)
                       .front());
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
  build.objects = objects;
  build.ok = true;
  return build;
}

}  // namespace clothref::grader
