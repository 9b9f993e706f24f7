// clothref trace: simulate a scene and write its trace (JSON Lines) to stdout or a file, then a
// short summary on stderr.
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <streambuf>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/io/limits.h"
#include "clothref/io/output_file.h"
#include "clothref/io/progress.h"
#include "clothref/record/record.h"
#include "clothref/trace/hash.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct TraceOptions {
  std::string scene = "course2022";
  std::string integrator = "explicit";
  std::optional<double> dt;
  std::int64_t steps = 10000;
  std::int64_t stride = 100;
  std::string precision = "float";
  std::string output = "-";
  bool quiet = false;
  int threads = 1;
};

// Passes the trace through to `target` and reports progress from its lines: line 1 is the
// header, line k > 1 is step (k - 2) * stride, so writeTrace needs no callback.
class ProgressStreambuf : public std::streambuf {
 public:
  ProgressStreambuf(std::streambuf* target, std::int64_t stride, Progress& progress)
      : target_(target), stride_(stride), progress_(progress) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    if (traits_type::to_char_type(c) == '\n') countLine();
    return target_->sputc(traits_type::to_char_type(c));
  }
  std::streamsize xsputn(const char* text, std::streamsize count) override {
    for (std::streamsize i = 0; i < count; ++i)
      if (text[i] == '\n') countLine();
    return target_->sputn(text, count);
  }
  int sync() override { return target_->pubsync(); }

 private:
  void countLine() {
    if (++lines_ >= 2) {
      const std::int64_t done = (lines_ - 2) * stride_;
      progress_.update(done, progress_.rateAndEta(done));
    }
  }
  std::streambuf* target_;
  std::int64_t stride_;
  Progress& progress_;
  std::int64_t lines_ = 0;
};

int runTrace(const TraceOptions& options) {
  // the option validators accept only names and ranges these conversions cannot refuse
  TraceSettings settings;
  settings.method = *parseMethod(options.integrator);
  settings.precision = *parseEnum(kPrecisionNames, options.precision);
  const Scene scene = loadScene(options.scene);
  settings.dt = options.dt.value_or(scene.dt);
  // the run computes in its precision: 1e-50 is 0 in float and 1e39 is infinite
  const double run_dt =
      settings.precision == Precision::Float ? double(float(settings.dt)) : settings.dt;
  if (!(run_dt > 0) || !std::isfinite(run_dt))
    throw InputError(fmt::format("--dt: {} becomes {} in {} precision (must be finite and > 0)",
                                 settings.dt, run_dt, precisionName(settings.precision)));
  if (options.steps > inputLimits().steps)
    throw InputError(fmt::format("--steps: {} is above the limit {} (raise it with --max-steps)",
                                 options.steps, inputLimits().steps));
  settings.steps = options.steps;
  settings.stride = options.stride;

  OutputFile output(options.output);
  TraceSummary summary;
  {
    Progress progress("clothref trace", settings.steps, "steps",
                      progressStyleForStderr(options.quiet), std::cerr);
    ProgressStreambuf counting(output.stream().rdbuf(), settings.stride, progress);
    std::ostream traced(&counting);
    summary = writeTrace(scene, settings, traced, options.threads);
    traced.flush();
    if (!traced) output.stream().setstate(std::ios::badbit);  // commit() then reports it
  }
  output.commit();

  if (options.quiet) return kExitOk;  // -q: nothing on stderr but errors
  std::cerr << fmt::format(
      "clothref trace: {} {} {} dt={}: {} steps, {:.6g} s simulated in {:.3f} s wall, {} lines\n"
      "  final kinetic energy {:.9g} J, momentum ({:.9g}, {:.9g}, {:.9g}) kg m/s, hash {}\n"
      "  state {}\n",
      scene.name, methodName(settings.method), precisionName(settings.precision), settings.dt,
      summary.steps, summary.simulated_time, summary.wall_seconds, summary.recorded + 1,
      summary.kinetic_energy, summary.momentum[0], summary.momentum[1], summary.momentum[2],
      hashToHex(summary.final_hash),
      summary.first_nonfinite_step < 0
          ? std::string("stayed finite")
          : fmt::format("became non-finite (first recorded at step {})",
                        summary.first_nonfinite_step));
  return kExitOk;
}

}  // namespace

Command addTraceCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "trace", "Simulate a scene and write its trace (JSON Lines, docs/trace-format.md)");
  auto options = std::make_shared<TraceOptions>();
  app->add_option("--scene", options->scene, "Built-in scene name or scene JSON file")
      ->capture_default_str();
  app->add_option("--integrator", options->integrator, "Integration method (docs/methods.md)")
      ->check(oneOf(kMethodNames))
      ->capture_default_str();
  app->add_option("--dt", options->dt, "Time step in seconds (default: the scene's)")
      ->check(finitePositive());
  app->add_option("--steps", options->steps, "Steps to simulate")
      ->check(atLeast(0))
      ->capture_default_str();
  app->add_option("--stride", options->stride,
                  "Record every N-th step (step 0 and the last are always recorded)")
      ->check(atLeast(1))
      ->capture_default_str();
  app->add_option("--precision", options->precision, "float (the course's) | double")
      ->check(oneOf(kPrecisionNames))
      ->capture_default_str();
  app->add_option("-o,--output", options->output, "Output file, '-' for stdout")
      ->capture_default_str();
  app->add_option("--threads", options->threads,
                  "Threads for the spring sweeps of cloths with 100 or more particles per edge "
                  "(the trace is the same bytes at any count)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app->add_flag("-q,--quiet", options->quiet,
                "Nothing on stderr but errors: no progress (shown for runs over a second: one "
                "updating line on a terminal, a line per 10 % otherwise, with rate and ETA) and no "
                "summary");
  return {app, [options] { return runTrace(*options); }};
}

}  // namespace clothref::cli
