// clothref grade DIR...: compile a student's cloth.cpp, sphere.cpp and integrator.cpp against the
// course stand-in and grade each stub (docs/grading.md).
#include <iostream>

#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "commands.h"
#include "grader/grade/grade.h"
#include "grader/grade/report.h"

namespace clothref::cli {

Command addGradeCommand(CLI::App& root) {
  auto* app = root.add_subcommand(
      "grade", "Grade student submissions stub by stub (compile, probe, score, feedback)");
  struct Options {
    std::vector<std::string> dirs;
    int edition = 0;
    std::string results, junit, report, rubric, keep_work, cache_dir;
    bool no_whole_run = false;
    double timeout = 20;
    std::string optimisation = "-O2";
  };
  auto options = std::make_shared<Options>();
  app->add_option("DIR", options->dirs, "submission directories (the three files anywhere below)")
      ->required()
      ->check(CLI::ExistingDirectory);
  app->add_option("--edition", options->edition,
                  "course edition (default: detected from the files)")
      ->check(CLI::IsMember({2022, 2024}));
  app->add_option("--results", options->results, "write Gradescope results.json here");
  app->add_option("--junit", options->junit, "write JUnit XML here");
  app->add_option("--report", options->report, "write the Markdown report here (default: stdout)");
  app->add_option("--rubric", options->rubric,
                  "JSON rubric: weights, tolerances, accepted variants")
      ->check(CLI::ExistingFile);
  app->add_option("--timeout", options->timeout, "wall-clock limit per probe process, seconds")
      ->check(CLI::PositiveNumber);
  app->add_option("--opt", options->optimisation, "optimisation flag for student code")
      ->check(CLI::IsMember({"-O0", "-O1", "-O2", "-O3"}));
  app->add_option("--cache-dir", options->cache_dir,
                  "reuse compiled objects of identical files across runs (keyed by bytes + flags)");
  app->add_option("--keep-work", options->keep_work,
                  "copy the scratch folder (objects, probe I/O, child output) to this directory");
  app->add_flag("--no-whole-run", options->no_whole_run, "skip the information-only whole run");
  return {app, [options] {
            const bool single = options->dirs.size() == 1;
            if (!single &&
                (!options->results.empty() || !options->junit.empty() || !options->report.empty()))
              throw InputError("--results, --junit and --report take one submission DIR; got " +
                               std::to_string(options->dirs.size()));
            grader::GradeOptions grade;
            grade.edition = options->edition;
            if (!options->rubric.empty()) grade.rubric_path = options->rubric;
            grade.keep_work = options->keep_work;
            grade.whole_run = !options->no_whole_run;
            grade.limits.wall_seconds = options->timeout;
            grade.limits.cpu_seconds = static_cast<std::uint64_t>(options->timeout) + 1;
            grade.toolchain.optimisation = options->optimisation;
            grade.toolchain.cache_dir = options->cache_dir;
            int exit_code = kExitOk;
            for (const std::string& dir : options->dirs) {
              grader::GradeReport report;
              try {
                report = grader::gradeSubmission(dir, grade);
              } catch (const InputError& error) {
                std::cerr << "clothref grade: " << error.what() << '\n';
                exit_code = kExitBadInput;
                continue;
              }
              std::cerr << grader::summaryLine(report) << '\n';
              if (!options->results.empty()) {
                OutputFile out(options->results);
                out.stream() << grader::resultsJson(report).dump(2) << '\n';
                out.commit();
              }
              if (!options->junit.empty()) {
                OutputFile out(options->junit);
                out.stream() << grader::junitXml(report);
                out.commit();
              }
              if (!options->report.empty()) {
                OutputFile out(options->report);
                out.stream() << grader::markdownReport(report);
                out.commit();
              } else if (single && options->results.empty() && options->junit.empty()) {
                std::cout << grader::markdownReport(report);
              }
            }
            return exit_code;
          }};
}

}  // namespace clothref::cli
