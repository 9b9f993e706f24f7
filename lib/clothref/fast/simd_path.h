// SIMD paths of the fast kernels: which instruction set the spring sweeps run on. Every path gives
// the same bits (IEEE add, sub, mul, div and sqrt round the same at any vector width, and nothing
// is contracted into FMA); the choice only changes speed. The release build runs on any x86-64: the
// wider paths live in their own translation units and are picked at run time from cpuid.
#pragma once

#include <string_view>

namespace clothref::fast {

enum class SimdPath { Sse2, Avx2, Avx512 };

inline constexpr SimdPath kAllSimdPaths[] = {SimdPath::Sse2, SimdPath::Avx2, SimdPath::Avx512};

// "sse2", "avx2", "avx512".
std::string_view simdPathName(SimdPath path);

// Parses a path name; returns false for an unknown one.
bool parseSimdPath(std::string_view name, SimdPath& path);

// Whether this CPU (and OS) can run `path`. SSE2 is part of x86-64, so always true for it.
bool simdPathSupported(SimdPath path);

// The widest supported path.
SimdPath bestSimdPath();

// The path a new world uses: CLOTHREF_SIMD when set (sse2 | avx2 | avx512), otherwise the best
// one. Read once per process. Throws std::invalid_argument naming CLOTHREF_SIMD when the variable
// names an unknown path or one this CPU cannot run.
SimdPath defaultSimdPath();

}  // namespace clothref::fast
