// The state hash written on every trace line: XXH3-64 (seed 0) over the little-endian IEEE bytes
// of, for each body in order (cloth, then spheres), the x, y, z of every particle's position, then
// the x, y, z of every particle's velocity. 4 bytes per value in float runs, 8 in double runs.
// docs/trace-format.md specifies it so any tool can recompute it from a trace line.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "clothref/trace/body_view.h"

namespace clothref {

// Inputs: the bodies in trace order. Output: the 64-bit hash.
template <typename T>
std::uint64_t stateHash(std::span<const BodyView<T>> bodies);

// 16 lowercase hex digits.
std::string hashToHex(std::uint64_t hash);

}  // namespace clothref
