// clothref gradescope: writes the Gradescope autograder archive (setup.sh and run_autograder at
// the zip root, this checkout's sources, the rubric) with tools/grader/gradescope/make_archive.py.
// The archive holds the sources of a commit, so it is made from the source checkout this binary
// was built from; docs/grading-reference.md, "Gradescope".
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "clothref/io/error.h"
#include "commands.h"
#include "run_program.h"

#ifndef CLOTHREF_PYTHON
#define CLOTHREF_PYTHON "/usr/bin/python3"
#endif
#ifndef CLOTHREF_SOURCE_DIR
#define CLOTHREF_SOURCE_DIR ""
#endif

namespace clothref::cli {

namespace {

struct GradescopeOptions {
  std::string output;
  std::string edition;
  std::string rubric;
  double timeout = 0;  // s per probe; 0 = the grader's default
  bool html = false;
};

int runGradescope(const GradescopeOptions& options) {
  const std::string script =
      std::string(CLOTHREF_SOURCE_DIR) + "/tools/grader/gradescope/make_archive.py";
  if (::access(script.c_str(), R_OK) != 0)
    throw InputError("gradescope: the archive is made from the clothref source checkout, and " +
                     script + " is not there");
  std::vector<std::string> argv = {CLOTHREF_PYTHON, script, "-o", options.output};
  if (!options.edition.empty()) argv.insert(argv.end(), {"--edition", options.edition});
  if (!options.rubric.empty()) argv.insert(argv.end(), {"--rubric", options.rubric});
  if (options.timeout > 0) argv.insert(argv.end(), {"--timeout", std::to_string(options.timeout)});
  if (options.html) argv.push_back("--html");
  return runProgram(argv, {{"PYTHONDONTWRITEBYTECODE", "1"}}, "gradescope") == 0 ? kExitOk
                                                                                 : kExitBadInput;
}

}  // namespace

Command addGradescopeCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "gradescope",
      "Write the Gradescope autograder archive: setup.sh, run_autograder, this checkout's sources "
      "and the rubric (docs/grading-reference.md, \"Gradescope\")");
  auto options = std::make_shared<GradescopeOptions>();
  app->add_option("-o,--output", options->output, "The archive to write (autograder.zip)")
      ->required();
  app->add_option("--edition", options->edition, "Force the edition (default: detected)")
      ->check(CLI::IsMember({"2022", "2024"}));
  app->add_option("--rubric", options->rubric, "Rubric JSON (clothref grade --rubric)");
  app->add_option("--timeout", options->timeout, "Wall-clock limit per probe, s (at most 1 day)")
      ->check(finitePositive() & CLI::Range(0.0, 86400.0));
  app->add_flag("--html", options->html, "Also write report.html next to results.json");
  return {app, [options] { return runGradescope(*options); }};
}

}  // namespace clothref::cli
