// The fuzz targets: one function per parser, each taking arbitrary bytes. A target may throw
// InputError (bad input, the expected outcome) and nothing else; anything else, and every crash,
// leak or undefined behaviour the sanitizers see, is a finding. Valid input (the seed corpora)
// throws nothing. Used by the libFuzzer binaries
// (fuzz_main.cpp, -DCLOTHREF_FUZZ=ON) and by fuzz_regression_test.cpp, which replays the
// committed corpora and crash inputs in the normal build.
#pragma once

#include <cstring>
#include <sstream>
#include <string>
#include <string_view>

#include "clothref/diff/diff.h"
#include "clothref/golden/golden.h"
#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/reader.h"
#include "grader/grade/rubric.h"

namespace clothref::fuzz {

// A valid header for one body of two particles, used in front of a fuzzed step line.
inline constexpr std::string_view kStepLineHeader =
    R"({"format":"clothref-trace","version":1,"scene":{},"integrator":"explicit",)"
    R"("precision":"float","dt":0.001,"steps":4,"stride":2,)"
    R"("bodies":[{"name":"cloth","particles":2}],"hash":"h","build":{}})";

inline void sceneJson(std::string_view input) {
  const Scene scene = sceneFromJson(parseJson(input, "scene.json"));
  validateScene(scene);
}

inline void traceHeader(std::string_view input) {
  std::istringstream in{std::string(input)};
  TraceReader reader(in, "trace.jsonl");
  TraceStep step;
  while (reader.next()) reader.parseStep(step);
}

inline void stepLine(std::string_view input) {
  std::istringstream in(std::string(kStepLineHeader) + "\n" + std::string(input));
  TraceReader reader(in, "trace.jsonl");
  TraceStep step;
  while (reader.next()) {
    reader.parseStep(step);
    stateHashOf(reader.header(), step);
  }
}

inline void toleranceFile(std::string_view input) {
  toleranceOptionsFromJson(parseJson(input, "tolerances.json"), "tolerances.json");
}

inline void goldenManifest(std::string_view input) {
  manifestFromJson(parseJson(input, "manifest.json"), "manifest.json");
}

// The grader's rubric file, over the 2022 defaults (the edition with every stub).
inline void rubric(std::string_view input) {
  grader::rubricFromJson(parseJson(input, "rubric.json"), "rubric.json",
                         grader::defaultRubric(2022));
}

// A trace read through the gzip decoder (the seeds are gzip-compressed traces: one member, several,
// empty ones): multi-member streams, trailing bytes, truncation, bombs. The line limits are
// lowered for the call, so a bomb costs at most a few MiB per execution.
inline void gzipTrace(std::string_view input) {
  struct Lowered {
    InputLimits saved = inputLimits();
    Lowered() {
      inputLimits().header_bytes = std::size_t(1) << 16;
      inputLimits().line_bytes = std::size_t(1) << 20;
    }
    ~Lowered() { inputLimits() = saved; }
  } lowered;
  std::istringstream in{std::string(input)};
  TraceReader reader(in, "trace.jsonl.gz");
  TraceStep step;
  while (reader.next()) reader.parseStep(step);
}

// Two traces separated by a line "----": diff them both ways and render every report.
inline void diffTwo(std::string_view input) {
  const std::size_t split = input.find("\n----\n");
  // A keeps its last newline; B is the rest after the separator line
  const std::string a(input.substr(0, split == std::string_view::npos ? split : split + 1));
  const std::string b(split == std::string_view::npos ? "" : input.substr(split + 6));
  for (int order = 0; order < 2; ++order) {
    std::istringstream in_a(order ? b : a), in_b(order ? a : b);
    DiffOptions options;
    options.common_steps = order == 1;
    const DiffReport report = diffTraces(in_a, "a.jsonl", in_b, "b.jsonl", options);
    formatReport(report);
    reportToJson(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    observedTolerances(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  }
}

}  // namespace clothref::fuzz
