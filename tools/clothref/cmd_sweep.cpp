// clothref sweep: work-precision data (error against a reference, wall time per simulated second,
// derivative evaluations, stable or not) for every method, precision and dt on the chosen scenes;
// CSV and JSON (lib/clothref/analysis/work_precision.h, docs/methods.md). Progress on stderr.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>

#include "clothref/analysis/work_precision.h"
#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct SweepOptions {
  std::vector<std::string> scenes;
  std::vector<std::string> methods;
  std::string precision = "both";
  int repeats = 5;
  std::vector<int> substeps;
  std::string csv;
  std::string json = "-";
  bool quiet = false;
};

int runSweep(const SweepOptions& options) {
  std::vector<Scene> scenes;
  const std::vector<std::string> names =
      options.scenes.empty() ? std::vector<std::string>{"spring", "course2022"} : options.scenes;
  for (const std::string& name : names) scenes.push_back(loadScene(name));
  std::vector<MethodChoice> methods;
  if (options.methods.empty()) methods = analysisMethods();
  for (const std::string& name : options.methods) {
    MethodChoice method;
    if (!parseMethodChoice(name, method))
      throw InputError("--method: unknown method '" + name +
                       "' (explicit, implicit, midpoint, rk4, symplectic, backward-euler)");
    methods.push_back(method);
  }
  std::vector<Precision> precisions;
  if (options.precision == "both") {
    precisions = {Precision::Float, Precision::Double};
  } else {
    const std::optional<Precision> precision = parseEnum(kPrecisionNames, options.precision);
    if (!precision)
      throw InputError("--precision: must be float, double or both, got '" + options.precision +
                       "'");
    precisions = {*precision};
  }
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
  const SweepResult result = sweep(scenes, methods, precisions, settings_for, progress);
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
  app->add_option("--scene", options->scenes,
                  "Scene name or file, repeatable (default: spring, course2022)");
  app->add_option("--method", options->methods, "Method, repeatable (default: all six)");
  app->add_option("--precision", options->precision, "float | double | both")
      ->capture_default_str();
  app->add_option("--repeats", options->repeats, "Timed runs per point (>= 5 for the charts)")
      ->capture_default_str();
  app->add_option("--substeps", options->substeps,
                  "Steps per sample interval, repeatable (dt = interval / substeps; default: the "
                  "scene's ladder)");
  app->add_option("--csv", options->csv, "Write the points as CSV to this file ('-' = stdout)");
  app->add_option("--json", options->json, "Write the JSON to this file ('-' = stdout, default)")
      ->capture_default_str();
  app->add_flag("-q,--quiet", options->quiet, "No progress lines on stderr");
  return {app, [options] { return runSweep(*options); }};
}

}  // namespace clothref::cli
