// clothref diff A B: compare two traces within tolerances (lib/clothref/diff/diff.h). Prints only
// what differs (or one line when identical), or one JSON object with --json. Exit 0 when the traces
// agree within tolerance, 1 when they differ, 2 on bad input.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "clothref/diff/diff.h"
#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "clothref/io/terminal_text.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct DiffCommandOptions {
  std::string path_a, path_b;
  std::optional<double> abs, rel, floor;
  std::optional<std::int64_t> ulps;
  std::string tolerances;
  std::string write_tolerances;
  bool common_steps = false;
  bool json = false;
};

void checkNonNegative(const char* flag, const std::optional<double>& value) {
  if (value && !(*value >= 0 && std::isfinite(*value)))
    throw InputError(fmt::format("{}: must be a finite number >= 0 (got {})", flag, *value));
}

// The global tolerance from the flags: --ulps, or --abs and/or --rel (both = combined).
DiffOptions buildOptions(const DiffCommandOptions& o) {
  checkNonNegative("--abs", o.abs);
  checkNonNegative("--rel", o.rel);
  checkNonNegative("--floor", o.floor);
  if (o.ulps && *o.ulps < 0)
    throw InputError(fmt::format("--ulps: must be >= 0 (got {})", *o.ulps));
  if (o.ulps && (o.abs || o.rel))
    throw InputError("--ulps: cannot be combined with --abs or --rel (pick one mode)");
  DiffOptions options = o.tolerances.empty() ? DiffOptions{} : readToleranceFile(o.tolerances);
  // flags replace the file's default; per-body entries of the file still apply
  if (o.ulps || o.abs || o.rel) {
    Tolerance global;
    global.floor = options.global.floor;
    if (o.ulps) {
      global.mode = ToleranceMode::Ulps;
      global.ulps = *o.ulps;
    } else {
      global.mode = o.abs && o.rel ? ToleranceMode::Combined
                    : o.abs        ? ToleranceMode::Absolute
                                   : ToleranceMode::Relative;
      global.abs = o.abs.value_or(0);
      global.rel = o.rel.value_or(0);
    }
    options.global = global;
  }
  if (o.floor) options.global.floor = *o.floor;
  options.common_steps = o.common_steps;
  return options;
}

int runDiff(const DiffCommandOptions& o) {
  if (o.path_a == "-" && o.path_b == "-")
    throw InputError("A and B are both standard input (-): at most one trace can come from it");
  const DiffOptions options = buildOptions(o);
  const DiffReport report = diffTraces(o.path_a, o.path_b, options);
  if (!o.write_tolerances.empty()) {
    OutputFile file(o.write_tolerances);
    // a file name that is not UTF-8 is shown with U+FFFD rather than aborting the dump
    file.stream() << observedTolerances(report).dump(2, ' ', false,
                                                     nlohmann::json::error_handler_t::replace)
                  << '\n';
    file.commit();
  }
  if (o.json)
    std::cout << reportToJson(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << '\n';
  else
    std::cout << terminalSafe(formatReport(report), true);  // scene names, keys, paths
  std::cout.flush();
  return report.verdict == Verdict::Differ ? kExitDiffer : kExitOk;
}

}  // namespace

Command addDiffCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "diff",
      "Compare two traces. Exit 0: they agree within tolerance; 1: they differ; 2: bad input");
  app->footer(
      "A value pair passes if both are the same non-finite kind, or both |a|, |b| < floor, or by "
      "mode:\n"
      "  ulps (default 0 = bit-exact): distance in units in the last place, in the trace's\n"
      "    precision (t: double); absolute: |a-b| <= abs; relative: |a-b|/max(|a|,|b|) <= rel;\n"
      "    combined (--abs and --rel): either passes.\n"
      "Steps with equal hash and equal bytes are skipped without parsing. Header differences\n"
      "(scene parameters, integrator, dt, precision) make the traces differ; build info, scene\n"
      "name and description are informational. Tolerance file and --json report formats:\n"
      "docs/trace-format.md.");
  auto options = std::make_shared<DiffCommandOptions>();
  app->add_option("A", options->path_a, "First trace (the reference)")->required();
  app->add_option("B", options->path_b, "Second trace")->required();
  app->add_option("--abs", options->abs, "Absolute tolerance (with --rel: combined mode)");
  app->add_option("--rel", options->rel, "Relative tolerance, fraction of max(|a|,|b|)");
  app->add_option("--floor", options->floor, "Pairs with both |a|, |b| below this always pass");
  app->add_option("--ulps", options->ulps, "Tolerance in units in the last place (default 0)");
  app->add_option("--tolerances", options->tolerances,
                  "Tolerance file (JSON): default, time, and per body per field; flags replace "
                  "its default");
  app->add_option("--write-tolerances", options->write_tolerances,
                  "Write a tolerance file with the observed maxima (applying it passes this diff)");
  app->add_flag("--common-steps", options->common_steps,
                "Compare only the steps both traces have (otherwise different step sets exit 2)");
  app->add_flag("--json", options->json, "Print the report as one JSON object");
  return {app, [options] { return runDiff(*options); }};
}

}  // namespace clothref::cli
