// The trace viewer's data: one or two traces read through the library's trace reader (files,
// `-` for standard input, gzip by its first byte) and turned into what tools/pages/assets/viewer.js
// plays: decimated frames of positions, and with two traces the distance of every cloth particle
// to the other trace, the largest difference at every common recorded step and the first step
// whose state differs at all.
//
// Frames are float32 (the picture needs no more); distances and differences are computed in double
// from the traces' values before that. A page holds at most ViewOptions::max_frames frames, evenly
// spread over the common recorded steps with the first, the last and the first differing step
// always among them; the page states how many of how many it shows.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace clothref::pages {

// Frame data a page may carry, in bytes of base64 (a 10000-step course2022 pair stays under 5 MB).
inline constexpr std::int64_t kFrameBudgetBytes = 3'600'000;

struct ViewOptions {
  std::vector<std::string> labels;  // one per trace; default: the file names
  std::int64_t max_frames = 0;      // 0: as many as fit kFrameBudgetBytes
};

// What viewerData found, for the command's summary line and the tests.
struct ViewSummary {
  std::int64_t recorded = 0;                     // common recorded steps
  std::int64_t frames = 0;                       // of which shown
  std::optional<std::int64_t> first_difference;  // step, two traces only
  double largest_difference = 0;                 // m, two traces only
};

// Reads `paths` (one or two) and returns the viewer's data object (schema: docs/pictures.md).
// Throws InputError naming the file for bad input, two traces with different bodies or different
// dt (step k would not be the same time in both: refused, not aligned), or no common recorded
// step. What it keeps grows with the steps the files hold, never with what a header claims: a
// file that ends before its header's last step is refused when its end is read, as by diff.
nlohmann::ordered_json viewerData(const std::vector<std::string>& paths, const ViewOptions& options,
                                  ViewSummary* summary = nullptr);

// A trace to read: a path ("-" for standard input) when `in` is null, else the stream `in` (which
// must outlive the call), named `name` in the page and in messages.
struct TraceSource {
  std::string name;
  std::istream* in = nullptr;
};
nlohmann::ordered_json viewerData(const std::vector<TraceSource>& sources,
                                  const ViewOptions& options, ViewSummary* summary = nullptr);

// The viewer's script and style, to embed a viewer in another page (the grade report) beside
// mountViewer(elementId, data) calls of its own.
std::string viewerScriptAndStyle();

// A whole self-contained viewer page for `data` (from viewerData).
std::string viewerPage(const nlohmann::ordered_json& data, const std::string& title);

}  // namespace clothref::pages
