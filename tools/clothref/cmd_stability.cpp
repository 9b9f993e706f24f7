// clothref stability: the largest stable dt per method and scene, measured by bisection and
// predicted from the amplification of one step on the scene's linear modes
// (lib/clothref/analysis/stability.h, docs/methods.md). Progress on stderr.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "analysis_options.h"
#include "clothref/analysis/stability.h"
#include "clothref/io/error.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct StabilityOptions {
  AnalysisSelection selection;
  std::optional<double> high;
  bool json = false;
  bool quiet = false;
};

int runStability(const StabilityOptions& options) {
  const std::vector<Scene> scenes = selectedScenes(options.selection);
  const std::vector<Method> methods = selectedMethods(options.selection);
  const std::vector<Precision> precisions = selectedPrecisions(options.selection);
  const auto progress = [&options](const std::string& line) {
    if (!options.quiet) std::cerr << line << '\n';
  };
  if (options.high && !(*options.high > 0 && std::isfinite(*options.high)))
    throw InputError(fmt::format("--high: must be a finite number > 0 (got {})", *options.high));
  const std::vector<StabilityResult> results =
      stabilityStudy(scenes, methods, precisions, progress, options.high);
  if (options.json)
    std::cout << stabilityToJson(results).dump(2) << '\n';
  else
    std::cout << stabilityTable(results);
  return kExitOk;
}

}  // namespace

Command addStabilityCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "stability",
      "Largest stable dt per method and scene: measured by bisection, predicted from each "
      "method's amplification on the scene's linear modes (docs/methods.md)");
  auto options = std::make_shared<StabilityOptions>();
  options->selection.default_scenes = {"spring", "spring-undamped", "course2022"};
  addAnalysisSelection(app, options->selection);
  app->add_option("--high", options->high,
                  "Upper end of the dt search (s), instead of the scene's (1 s for the spring "
                  "scenes, 0.02 s otherwise)");
  app->add_flag("--json", options->json,
                "Print {\"results\": [{\"scene\", \"method\", \"precision\", \"dt_max_measured\", "
                "\"dt_max_theory\", \"criterion\", ...}]}");
  app->add_flag("-q,--quiet", options->quiet, "No progress lines on stderr");
  return {app, [options] { return runStability(*options); }};
}

}  // namespace clothref::cli
