#include "clothref/trace/step_line.h"

#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "clothref/trace/hash.h"

namespace clothref {

namespace {

// Shortest round-trip text in the value's own precision; non-finite values as quoted strings.
template <typename T>
void appendNumber(std::string& out, T value) {
  if (std::isfinite(value)) {
    fmt::format_to(std::back_inserter(out), "{}", value);
  } else if (std::isnan(value)) {
    out += "\"NaN\"";
  } else {
    out += value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  }
}

// [[x,y,z],...] of `count` 4-value columns.
template <typename T>
void appendColumns(std::string& out, const T* columns, int count) {
  out += '[';
  for (int i = 0; i < count; ++i) {
    if (i) out += ',';
    out += '[';
    appendNumber(out, columns[4 * i]);
    out += ',';
    appendNumber(out, columns[4 * i + 1]);
    out += ',';
    appendNumber(out, columns[4 * i + 2]);
    out += ']';
  }
  out += ']';
}

}  // namespace

template <typename T>
void appendStepLine(std::string& out, std::int64_t step, double t,
                    std::span<const BodyView<T>> bodies) {
  fmt::format_to(std::back_inserter(out), "{{\"step\":{},\"t\":", step);
  // t follows the same non-finite rule as every other number
  appendNumber(out, t);
  fmt::format_to(std::back_inserter(out), ",\"hash\":\"{}\",\"bodies\":{{",
                 hashToHex(stateHash(bodies)));
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (b) out += ',';
    fmt::format_to(std::back_inserter(out), "\"{}\":{{\"position\":", bodies[b].name);
    appendColumns(out, bodies[b].position, bodies[b].particles);
    out += ",\"velocity\":";
    appendColumns(out, bodies[b].velocity, bodies[b].particles);
    out += '}';
  }
  out += "}}\n";
}

template void appendStepLine(std::string&, std::int64_t, double, std::span<const BodyView<float>>);
template void appendStepLine(std::string&, std::int64_t, double, std::span<const BodyView<double>>);

}  // namespace clothref
