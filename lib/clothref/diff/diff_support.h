// What the diff files share (internal to lib/clothref/diff).
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace clothref::diff_support {

using ordered_json = nlohmann::ordered_json;

inline constexpr std::uint64_t kInfiniteUlps = std::numeric_limits<std::uint64_t>::max();
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr int kToleranceFileVersion = 1;

// A JSON value in one short line for a report; "(missing)" for an absent key.
inline std::string compact(const ordered_json& value) {
  if (value.is_discarded()) return "(missing)";
  if (value.is_number_float()) return fmt::format("{}", value.get<double>());
  return value.dump();
}

}  // namespace clothref::diff_support
