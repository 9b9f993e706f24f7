// Recording a run: simulates a scene and writes it as a trace (docs/trace-format.md). Line 1 is the
// header (format, version, full scene, integrator, dt, precision, steps, stride, bodies, build);
// then one step line per recorded step (trace/step_line.h).
#pragma once

#include <array>
#include <cstdint>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "clothref/base/precision.h"
#include "clothref/core/integrator.h"
#include "clothref/scene/scene.h"

namespace clothref {

struct TraceSettings {
  Method method = Method::Explicit;
  Precision precision = Precision::Float;
  double dt = 0;            // seconds; the scene's dt unless overridden
  std::int64_t steps = 0;   // steps to take
  std::int64_t stride = 1;  // record every stride-th step; step 0 and the last are always recorded

  bool operator==(const TraceSettings&) const = default;
};

// What a run ended with, for the human summary on stderr and for tests.
struct TraceSummary {
  std::int64_t steps = 0;
  std::int64_t recorded = 0;               // step lines written
  double simulated_time = 0;               // seconds
  double wall_seconds = 0;                 // seconds spent stepping and writing
  double kinetic_energy = 0;               // joules, final state
  std::array<double, 3> momentum{};        // kg m / s, final state
  bool finite = true;                      // final state finite
  std::int64_t first_nonfinite_step = -1;  // first recorded step with a non-finite value, or -1
  std::uint64_t final_hash = 0;
};

// The header object of a trace.
nlohmann::ordered_json traceHeader(const Scene& scene, const TraceSettings& settings);

// Runs `scene` with `settings` and writes the whole trace to `out`. `threads` (>= 1) share the
// spring sweeps of cloths of kThreadedGridEdge or more particles per edge; the trace is the same
// bytes at any thread count, so it is not a setting of the run and is not in the header.
TraceSummary writeTrace(const Scene& scene, const TraceSettings& settings, std::ostream& out,
                        int threads = 1);

}  // namespace clothref
