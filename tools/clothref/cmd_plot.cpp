// clothref plot: pictures of runs and charts of the analysis data, drawn by the project's
// matplotlib scripts (tools/python/clothref/plot.py) run with the Debian python3 found at
// configure time:
//   clothref plot A.jsonl [B.jsonl] -o PREFIX      cloth + spheres at --times, and energies
//   clothref plot --sweep SWEEP.json -o PREFIX     work-precision charts (clothref sweep)
//   clothref plot --stability STAB.json -o PREFIX  stability limits (clothref stability --json)
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "commands.h"
#include "run_program.h"

#ifndef CLOTHREF_PYTHON
#define CLOTHREF_PYTHON "/usr/bin/python3"
#endif
#ifndef CLOTHREF_DATA_FROM_BIN
#define CLOTHREF_DATA_FROM_BIN ""
#endif
#ifndef CLOTHREF_PYTHON_DIR
#define CLOTHREF_PYTHON_DIR ""
#endif

namespace clothref::cli {

namespace {

struct PlotOptions {
  std::vector<std::string> traces;
  std::string sweep;
  std::string stability;
  std::vector<double> times = {0, 0.5, 1};
  std::vector<std::string> labels;
  std::string norm = "final";
  std::string output;
  std::string formats = "png,svg";
};

// Runs python3 -m clothref.plot ARGS with the project's package on PYTHONPATH; its exit code.
int runPython(const std::vector<std::string>& args) {
  const std::string python = CLOTHREF_PYTHON;
  if (python.empty() || ::access(python.c_str(), X_OK) != 0)
    throw InputError("plot: no python3 at '" + python +
                     "' (tools/setup.sh installs python3-matplotlib; reconfigure after)");
  std::vector<std::string> argv = {python, "-m", "clothref.plot"};
  argv.insert(argv.end(), args.begin(), args.end());
  const char* old = std::getenv("PYTHONPATH");
  // an install's own package (<prefix>/share/clothref/python), else the source tree's
  const std::filesystem::path installed = installedDataDir(CLOTHREF_DATA_FROM_BIN);
  const std::string path =
      (installed.empty() ? std::string(CLOTHREF_PYTHON_DIR) : (installed / "python").string()) +
      (old && *old ? std::string(":") + old : "");
  return runProgram(argv,
                    {{"PYTHONPATH", path},
                     {"PYTHONDONTWRITEBYTECODE", "1"},  // nothing written into the source tree
                     {"MPLBACKEND", "Agg"}},
                    "plot") == 0
             ? kExitOk
             : kExitBadInput;
}

int runPlot(const PlotOptions& options) {
  const int modes =
      int(!options.traces.empty()) + int(!options.sweep.empty()) + int(!options.stability.empty());
  if (modes != 1)
    throw InputError("plot: give one or two traces, or --sweep FILE, or --stability FILE");
  if (options.output.empty()) throw InputError("-o: an output prefix is required");
  std::vector<std::string> args;
  if (!options.traces.empty()) {
    if (options.traces.size() > 2)
      throw InputError("plot: at most two traces (a reference and a student)");
    args = {"trace"};
    args.insert(args.end(), options.traces.begin(), options.traces.end());
    args.push_back("--times");
    for (double t : options.times) args.push_back(fmt::format("{}", t));
    if (!options.labels.empty()) {
      args.push_back("--labels");
      args.insert(args.end(), options.labels.begin(), options.labels.end());
    }
  } else if (!options.sweep.empty()) {
    args = {"sweep", options.sweep, "--norm", options.norm};
  } else {
    args = {"stability", options.stability};
  }
  args.insert(args.end(), {"-o", options.output, "--formats", options.formats});
  return runPython(args);
}

}  // namespace

Command addPlotCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "plot",
      "Draw a run (cloth and spheres at chosen times, energies; two traces overlaid) or the "
      "sweep / stability charts, to PNG and SVG (matplotlib; docs/methods.md)");
  auto options = std::make_shared<PlotOptions>();
  app->add_option("traces", options->traces, "One trace, or a reference and a student trace");
  app->add_option("--sweep", options->sweep, "Work-precision JSON from clothref sweep");
  app->add_option("--stability", options->stability, "JSON from clothref stability --json");
  app->add_option("--times", options->times, "Times (s) of the cloth pictures")
      ->capture_default_str();
  app->add_option("--labels", options->labels, "Legend labels of the traces");
  app->add_option("--norm", options->norm, "Sweep error norm: final | rms")
      ->check(CLI::IsMember({"final", "rms"}))
      ->capture_default_str();
  app->add_option("-o,--output", options->output,
                  "Output prefix: PREFIX-cloth.png, PREFIX-energy.png (traces), "
                  "PREFIX-<scene>.png (sweep), PREFIX.png (stability)");
  app->add_option("--formats", options->formats, "Comma-separated: png, svg, pdf")
      ->capture_default_str();
  return {app, [options] { return runPlot(*options); }};
}

}  // namespace clothref::cli
