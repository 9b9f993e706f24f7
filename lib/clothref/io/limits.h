// Input limits: the largest input every reader accepts, so no file (/dev/zero, a header claiming
// 10^12 particles, an array nested 10^5 deep) can exhaust memory or the stack. One set per
// process; the CLI raises them with --max-* flags (docs/reliability.md lists them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace clothref {

struct InputLimits {
  std::size_t file_bytes =
      std::size_t(256) << 20;  // a whole file read into memory (scene, tolerance file, manifest)
  std::size_t line_bytes = std::size_t(256) << 20;  // one trace step line
  // The header line, parsed as a JSON document (about 30 bytes of memory per byte of text for a
  // long array), so bounded far below a step line, which is parsed in place.
  std::size_t header_bytes = std::size_t(4) << 20;
  std::size_t json_depth = 64;             // nesting of arrays and objects in any JSON input
  std::int64_t particles = 10'000'000;     // particles of one body in a trace header
  std::int64_t steps = 1'000'000'000'000;  // steps of a run or a trace header
};

// The process's limits (defaults above until the CLI changes them).
inline InputLimits& inputLimits() {
  static InputLimits limits;
  return limits;
}

// At most `max_chars` of `text` for an error message, with "..." and the full size when cut, so
// a 100 MB unterminated string does not come back as a 100 MB error line.
inline std::string excerpt(std::string_view text, std::size_t max_chars = 60) {
  if (text.size() <= max_chars) return std::string(text);
  return std::string(text.substr(0, max_chars)) + "...(" + std::to_string(text.size()) + " bytes)";
}

}  // namespace clothref
