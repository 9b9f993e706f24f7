// ProbeRebuilder (grader/grade/run/build.h): the files a crashed probe group runs, rebuilt with
// the sanitizers and linked against the grade's own objects of the rest; and rebuildWithFile, a
// repair's probe: one student file's repaired bytes compiled and linked the same way.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <stdexcept>

#include "grader/grade/run/build.h"
#include "grader/grade/run/compile_cache.h"
#include "grader/grade/run/compiler_messages.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/run/tools.h"
#include "grader/grade/submission/submission.h"

namespace clothref::grader {
namespace fs = std::filesystem;

ProbeRebuilder::ProbeRebuilder(const ProbeBuild& base, const SubmissionFiles& files, int edition,
                               const CourseToolchain& toolchain, Folder folder)
    : base_(base),
      files_(files),
      edition_(edition),
      toolchain_(absolutePaths(toolchain)),
      folder_(std::move(folder)) {}

fs::path ProbeRebuilder::probe(const std::vector<std::string>& rebuilt) {
  const std::lock_guard lock(mutex_);  // one build at a time: a later set reuses the objects
  const auto& names = studentFileNames();
  const auto stem = [](const std::string& name) { return name.substr(0, name.size() - 4); };
  const auto in = [&](const std::string& name) {
    return std::find(rebuilt.begin(), rebuilt.end(), name) != rebuilt.end();
  };
  std::string set = "probe";
  for (const std::string& name : names)
    if (in(name)) set += "-" + stem(name);
  if (const auto found = probes_.find(set); found != probes_.end()) return found->second;
  fs::path& result = probes_[set];
  if (!base_.ok || base_.objects.size() != names.size() || base_.files.size() != names.size())
    return result;
  const fs::path work_dir = folder_(set);
  const std::string ed = std::to_string(edition_);
  fs::path pch = precompiledHeader(toolchain_, edition_, work_dir);
  if (toolchain_.kit && !pch.empty()) pch = kitHeader(*toolchain_.kit, pch);

  // The files not compiled yet: the student's own first (as the tool uid), then our reference
  // files (as the grader's uid); objects of earlier sets are copied in after the compiles.
  const CourseToolchain ours = oursOf(toolchain_);
  std::map<std::string, fs::path> made;  // this set's files compiled here
  for (const bool reference : {false, true}) {
    std::vector<std::vector<std::string>> commands;
    std::vector<std::string> compiled;
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string& name = names[k];
      if (!in(name) || objects_.count(name) || base_.files[k].compiled == reference) continue;
      const fs::path object = work_dir / (stem(name) + ".o");
      fs::path source = toolchain_.reference_dir / ed / name;
      if (!reference) {
        const fs::path folder = work_dir / ("src-" + stem(name));
        fs::create_directories(folder);
        source = folder / name;
        // the bytes the finder read, never the student's path again
        std::ofstream copy(source, std::ios::binary | std::ios::trunc);
        copy << files_.bytes.at(name);
        if (!copy.flush()) throw std::runtime_error("cannot copy " + name + " for a rebuild");
      }
      commands.push_back(
          compileCommand(reference ? ours : toolchain_, edition_, source, object, 25, pch));
      compiled.push_back(name);
    }
    const std::vector<ToolRun> runs = compileAll(reference ? ours : toolchain_, commands, work_dir);
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const fs::path object = work_dir / (stem(compiled[r]) + ".o");
      objects_[compiled[r]] = made[compiled[r]] = runs[r].ok ? object : fs::path();
    }
  }

  // The rebuilt objects first, then the grade's own objects of the other files.
  std::vector<fs::path> objects;
  for (const std::string& name : names)
    if (in(name)) {
      if (objects_[name].empty()) return result;
      fs::path object = work_dir / (stem(name) + ".o");
      if (!made.count(name) && !copyObject(objects_[name], object)) return result;
      objects.push_back(object);
    }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (in(names[k])) continue;
    const fs::path copy = work_dir / (stem(names[k]) + "-base.o");
    if (!copyObject(base_.objects[k], copy)) return result;
    objects.push_back(copy);
  }
  const fs::path options =
      toolchain_.sanitize ? sanitizerOptionsObject(toolchain_, work_dir) : fs::path();
  const fs::path out = work_dir / set;
  const ToolRun linked =
      checked(runTools({linkCommand(toolchain_, edition_, objects, options, out)}, work_dir, 1,
                       toolchain_.compile_seconds, &toolchain_.isolation)
                  .front());
  if (linked.ok) result = out;
  return result;
}

ProbeBuild rebuildWithFile(const ProbeBuild& base, const std::string& name,
                           const std::string& bytes, int edition, const CourseToolchain& given,
                           const fs::path& work_dir) {
  const CourseToolchain toolchain = absolutePaths(given);
  const auto& names = studentFileNames();
  ProbeBuild build;
  if (!base.ok || base.objects.size() != names.size()) {
    build.problem = "the grade's own build has no objects to link a repair with";
    return build;
  }
  const auto stem = [](const std::string& file) { return file.substr(0, file.size() - 4); };
  fs::path pch = precompiledHeader(toolchain, edition, work_dir);
  if (toolchain.kit && !pch.empty()) pch = kitHeader(*toolchain.kit, pch);
  const fs::path folder = work_dir / ("src-" + stem(name));
  fs::create_directories(folder);
  {
    std::ofstream copy(folder / name, std::ios::binary | std::ios::trunc);
    copy << bytes;
    if (!copy.flush()) throw std::runtime_error("cannot write the repaired " + name);
  }
  const auto since = [](auto start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const auto start = std::chrono::steady_clock::now();
  // Through the object cache like every student compile: the same repaired bytes (a regrade, or
  // two students with one mistake written alike) compile once.
  const fs::path object = work_dir / (stem(name) + ".o");
  const ToolRun compiled =
      compileAll(toolchain, {compileCommand(toolchain, edition, folder / name, object, 25, pch)},
                 work_dir)
          .front();
  build.compile_seconds = since(start);
  if (!compiled.ok) {
    build.problem = firstCompilerError(
        compiled.output,
        CompileSite{work_dir, folder / name, name,
                    courseHeaderDirs(toolchain.course_dir, edition, toolchain.eigen_include)});
    return build;
  }
  // The repaired object first (as ProbeRebuilder's), then the grade's own objects of the others.
  std::vector<fs::path> objects = {object};
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) continue;
    const fs::path copy = work_dir / (stem(names[k]) + "-base.o");
    if (!copyObject(base.objects[k], copy)) throw std::runtime_error("cannot copy an object");
    objects.push_back(copy);
  }
  const auto link_start = std::chrono::steady_clock::now();
  const ToolRun linked =
      checked(runTools({linkCommand(toolchain, edition, objects, {}, work_dir / "probe")}, work_dir,
                       1, toolchain.compile_seconds, &toolchain.isolation)
                  .front());
  build.link_seconds = since(link_start);
  if (!linked.ok) {
    build.problem = firstCompilerError(linked.output, CompileSite{work_dir, {}, name, {}});
    return build;
  }
  build.probe = work_dir / "probe";
  build.ok = true;
  return build;
}

}  // namespace clothref::grader
