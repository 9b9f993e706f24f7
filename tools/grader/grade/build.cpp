#include "build.h"

#include <chrono>
#include <cstdlib>
#include <sstream>

#include "child_process.h"

#ifndef CLOTHREF_GRADER_COURSE_DIR
#define CLOTHREF_GRADER_COURSE_DIR ""
#endif
#ifndef CLOTHREF_GRADER_REFERENCE_DIR
#define CLOTHREF_GRADER_REFERENCE_DIR ""
#endif
#ifndef CLOTHREF_GRADER_LIB_DIR
#define CLOTHREF_GRADER_LIB_DIR ""
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

std::vector<std::string> compileCommand(const CourseToolchain& t, int edition,
                                        const fs::path& source, const fs::path& object,
                                        int particles_per_edge) {
  const std::string ed = std::to_string(edition);
  std::vector<std::string> command = {t.compiler, "-std=c++20", t.optimisation,
                                      "-ffp-contract=off", "-fno-fast-math", "-fmax-errors=3",
                                      "-fdiagnostics-plain-output",
                                      "-DCLOTHREF_GRADER_EDITION_" + ed};
  if (particles_per_edge != 25)
    command.push_back("-DCLOTHREF_GRADER_PARTICLES_PER_EDGE=" + std::to_string(particles_per_edge));
  command.insert(command.end(), {"-I" + (t.course_dir / ed / "include").string(),
                                 "-I" + (t.course_dir / "common" / "include").string(),
                                 "-isystem", t.eigen_include.string(), "-c", source.string(),
                                 "-o", object.string()});
  return command;
}

}  // namespace

CourseToolchain defaultToolchain() {
  CourseToolchain t;
  t.course_dir = fromEnv("CLOTHREF_GRADER_COURSE_DIR", CLOTHREF_GRADER_COURSE_DIR);
  t.reference_dir = fromEnv("CLOTHREF_GRADER_REFERENCE_DIR", CLOTHREF_GRADER_REFERENCE_DIR);
  t.driver_lib_dir = fromEnv("CLOTHREF_GRADER_LIB_DIR", CLOTHREF_GRADER_LIB_DIR);
  t.eigen_include = CLOTHREF_GRADER_EIGEN_INCLUDE;
  t.compiler = fromEnv("CLOTHREF_GRADER_CXX", "g++");
  return t;
}

std::string firstCompilerError(const std::string& log, const std::string& file_name) {
  std::istringstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find("error") == std::string::npos) continue;
    if (lines[i].find(": error:") == std::string::npos &&
        lines[i].find("fatal error:") == std::string::npos &&
        lines[i].find("undefined reference") == std::string::npos)
      continue;
    std::string quote;
    for (std::size_t k = i; k < lines.size() && k < i + 3; ++k) {
      std::string line = lines[k];
      // Scratch paths say nothing to a student: keep only the file name.
      for (std::size_t at; (at = line.find("/src-")) != std::string::npos;) {
        std::size_t begin = line.rfind(' ', at);
        begin = begin == std::string::npos ? 0 : begin + 1;
        const std::size_t end = line.find(file_name, at);
        if (end == std::string::npos) break;
        line.replace(begin, end - begin, "");
      }
      if (k > i && (line.find(": error:") != std::string::npos ||
                    line.find(": note:") != std::string::npos ||
                    line.find("In function") != std::string::npos))
        break;
      quote += line + "\n";
    }
    return quote;
  }
  return lines.empty() ? std::string("(no compiler output)") : lines.front();
}

ProbeBuild buildProbes(const SubmissionFiles& files, int edition,
                       const CourseToolchain& toolchain, const fs::path& work_dir) {
  ProbeBuild build;
  const std::string ed = std::to_string(edition);
  const auto stem = [](const std::string& name) { return name.substr(0, name.size() - 4); };

  // 1. Student files, each alone in its folder; plus cloth.cpp at the second size.
  std::vector<std::vector<std::string>> commands;
  std::vector<std::string> names;
  for (const std::string& name : studentFileNames()) {
    UsedFile used;
    used.name = name;
    auto found = files.found.find(name);
    if (found == files.found.end()) {
      used.problem = "missing";
      build.files.push_back(used);
      continue;
    }
    used.path = found->second.string();
    const fs::path folder = work_dir / ("src-" + stem(name));
    fs::create_directories(folder);
    fs::copy_file(found->second, folder / name, fs::copy_options::overwrite_existing);
    commands.push_back(compileCommand(toolchain, edition, folder / name,
                                      work_dir / (stem(name) + ".o"), 25));
    names.push_back(name);
    if (name == "cloth.cpp") {
      commands.push_back(compileCommand(toolchain, edition, folder / name,
                                        work_dir / "cloth-small.o", kSecondParticlesPerEdge));
      names.push_back("cloth-small");
    }
    build.files.push_back(used);
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<ToolRun> runs = runTools(commands, work_dir, toolchain.jobs, toolchain.compile_seconds);
  bool small_compiled = false;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == "cloth-small") {
      small_compiled = runs[k].ok;
      if (!runs[k].ok) build.small_problem = firstCompilerError(runs[k].output, "cloth.cpp");
      continue;
    }
    for (UsedFile& used : build.files)
      if (used.name == names[k]) {
        used.compiled = runs[k].ok;
        used.compile_seconds = runs[k].seconds;
        if (!runs[k].ok) used.problem = firstCompilerError(runs[k].output, used.name);
      }
  }

  // 2. Our reference version for every file that is missing or did not compile.
  commands.clear();
  names.clear();
  for (const UsedFile& used : build.files) {
    if (used.compiled) continue;
    const fs::path reference = toolchain.reference_dir / ed / used.name;
    commands.push_back(compileCommand(toolchain, edition, reference,
                                      work_dir / (stem(used.name) + ".o"), 25));
    names.push_back(used.name);
  }
  runs = runTools(commands, work_dir, toolchain.jobs, toolchain.compile_seconds);
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (!runs[k].ok) {
      build.problem = "our reference " + names[k] + " for " + ed + " does not compile: " +
                      firstCompilerError(runs[k].output, names[k]);
      return build;
    }
  build.compile_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // 3. Link. A link error (e.g. a framework function deleted) makes us swap in our version of
  // the file the linker complains about, one file at a time.
  const auto link_start = std::chrono::steady_clock::now();
  const fs::path driver_lib = toolchain.driver_lib_dir / ("libclothref_grader_course_" + ed + ".a");
  const auto link = [&](const std::vector<fs::path>& objects, const fs::path& out) {
    std::vector<std::string> command = {toolchain.compiler, "-o", out.string()};
    for (const auto& o : objects) command.push_back(o.string());
    command.push_back(driver_lib.string());
    return runTools({command}, work_dir, 1, toolchain.compile_seconds).front();
  };
  std::vector<fs::path> objects = {work_dir / "cloth.o", work_dir / "sphere.o",
                                   work_dir / "integrator.o"};
  build.probe = work_dir / "probe";
  ToolRun linked = link(objects, build.probe);
  for (UsedFile& used : build.files) {
    if (linked.ok) break;
    if (!used.compiled) continue;
    const std::string error = firstCompilerError(linked.output, used.name);
    std::vector<std::string> ref = compileCommand(toolchain, edition,
                                                  toolchain.reference_dir / ed / used.name,
                                                  work_dir / (stem(used.name) + "-ref.o"), 25);
    if (!runTools({ref}, work_dir, 1, toolchain.compile_seconds).front().ok) continue;
    std::vector<fs::path> swapped = objects;
    for (auto& o : swapped)
      if (o.filename() == stem(used.name) + ".o") o = work_dir / (stem(used.name) + "-ref.o");
    ToolRun retry = link(swapped, build.probe);
    if (retry.ok) {
      used.compiled = false;
      used.problem = "link error: " + error;
      objects = swapped;
      linked = retry;
    }
  }
  if (!linked.ok) {
    build.problem = "the probe does not link: " + firstCompilerError(linked.output, "");
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
    if (!small_link.ok) build.small_problem = firstCompilerError(small_link.output, "cloth.cpp");
  }
  build.link_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - link_start).count();
  build.ok = true;
  return build;
}

}  // namespace clothref::grader
