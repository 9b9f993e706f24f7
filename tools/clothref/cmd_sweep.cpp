// clothref sweep: work-precision data (error against a reference, wall time per simulated second,
// derivative evaluations, stable or not) for every method, precision and dt on the chosen scenes;
// CSV and JSON (lib/clothref/analysis/work_precision.h, docs/methods.md). Progress on stderr.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>

#include "analysis_options.h"
#include "clothref/analysis/work_precision.h"
#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct SweepOptions {
  AnalysisSelection selection;
  int repeats = 5;
  std::vector<int> substeps;
  std::string csv;
  std::string json = "-";
  bool peer = false;
  bool quiet = false;
};

int runSweep(const SweepOptions& options) {
  const std::vector<Scene> scenes = selectedScenes(options.selection);
  const std::vector<Method> methods = selectedMethods(options.selection);
  const std::vector<Precision> precisions = selectedPrecisions(options.selection);
  if (options.repeats < 1)
    throw InputError(fmt::format("--repeats: must be >= 1 (got {})", options.repeats));
  for (int s : options.substeps)
    if (s < 1) throw InputError(fmt::format("--substeps: must be >= 1 (got {})", s));
  if (options.csv.empty() && options.json.empty())
    throw InputError("--csv, --json: give at least one output");

  // open the outputs first: a bad path fails before a long sweep, and nothing is left half-written
  std::unique_ptr<OutputFile> csv, json;
  if (!options.csv.empty()) csv = std::make_unique<OutputFile>(options.csv);
  if (!options.json.empty()) json = std::make_unique<OutputFile>(options.json);

  const auto settings_for = [&options](const Scene& scene) {
    SweepSettings settings = defaultSweepSettings(scene);
    settings.repeats = options.repeats;
    if (!options.substeps.empty()) {
      settings.substeps = options.substeps;
      settings.backward_euler_substeps.clear();
    }
    return settings;
  };
  const auto progress = [&options](const std::string& line) {
    if (!options.quiet) std::cerr << line << '\n';
  };
  // Boost.Odeint beside each chosen method it has a stepper for (docs/methods.md)
  std::vector<PeerStepper> peers;
  if (options.peer)
    for (PeerStepper stepper : {PeerStepper::Euler, PeerStepper::Rk4})
      if (std::find(methods.begin(), methods.end(), peerCounterpart(stepper)) != methods.end())
        peers.push_back(stepper);
  const SweepResult result = sweep(scenes, methods, precisions, settings_for, progress, peers);
  if (csv) {
    csv->stream() << sweepToCsv(result);
    csv->commit();
  }
  if (json) {
    json->stream() << sweepToJson(result).dump(1) << '\n';
    json->commit();
  }
  return kExitOk;
}

}  // namespace

Command addSweepCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "sweep",
      "Work-precision data: error, time per simulated second (median/min/max of --repeats runs), "
      "evaluations and stability for every method, precision and dt (docs/methods.md)");
  auto options = std::make_shared<SweepOptions>();
  options->selection.default_scenes = {"spring", "course2022"};
  addAnalysisSelection(app, options->selection);
  app->add_option("--repeats", options->repeats, "Timed runs per point (>= 5 for the charts)")
      ->capture_default_str();
  app->add_option("--substeps", options->substeps,
                  "Steps per sample interval, repeatable (dt = interval / substeps; default: the "
                  "scene's ladder)");
  app->add_option("--csv", options->csv, "Write the points as CSV to this file ('-' = stdout)");
  app->add_option("--json", options->json, "Write the JSON to this file ('-' = stdout, default)")
      ->capture_default_str();
  app->add_flag("--peer", options->peer,
                "Also step the scene with Boost.Odeint's euler and runge_kutta4 from the library's "
                "evaluation, beside explicit and rk4 (points odeint-euler, odeint-rk4)");
  app->add_flag("-q,--quiet", options->quiet, "No progress lines on stderr");
  return {app, [options] { return runSweep(*options); }};
}

}  // namespace clothref::cli
