// Trace format constants shared by the writer, the reader and the differ (docs/trace-format.md).
#pragma once

#include <cstdint>
#include <string_view>

namespace clothref {

inline constexpr std::string_view kTraceFormat = "clothref-trace";
inline constexpr int kTraceVersion = 1;

// The header's human description of the per-step hash (see trace/hash.h).
inline constexpr std::string_view kTraceHashDescription =
    "xxh3-64 of little-endian x,y,z of positions then velocities, per body";

// Whether step `step` of a run of `steps` steps with `stride` is recorded: every stride-th step,
// and always the last.
inline bool isRecorded(std::int64_t step, std::int64_t steps, std::int64_t stride) {
  return step % stride == 0 || step == steps;
}

}  // namespace clothref
