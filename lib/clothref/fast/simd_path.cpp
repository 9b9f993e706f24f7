#include "clothref/fast/simd_path.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace clothref::fast {

std::string_view simdPathName(SimdPath path) {
  switch (path) {
    case SimdPath::Sse2:
      return "sse2";
    case SimdPath::Avx2:
      return "avx2";
    case SimdPath::Avx512:
      return "avx512";
  }
  return "?";
}

bool parseSimdPath(std::string_view name, SimdPath& path) {
  for (SimdPath candidate : kAllSimdPaths) {
    if (simdPathName(candidate) == name) {
      path = candidate;
      return true;
    }
  }
  return false;
}

bool simdPathSupported(SimdPath path) {
  // __builtin_cpu_supports also checks that the OS saves the wide registers (XGETBV)
  switch (path) {
    case SimdPath::Sse2:
      return true;
    case SimdPath::Avx2:
      return __builtin_cpu_supports("avx2");
    case SimdPath::Avx512:
      return __builtin_cpu_supports("avx512f");
  }
  return false;
}

SimdPath bestSimdPath() {
  if (simdPathSupported(SimdPath::Avx512)) return SimdPath::Avx512;
  if (simdPathSupported(SimdPath::Avx2)) return SimdPath::Avx2;
  return SimdPath::Sse2;
}

namespace {

SimdPath pathFromEnvironment() {
  const char* value = std::getenv("CLOTHREF_SIMD");
  if (value == nullptr || *value == '\0') return bestSimdPath();
  SimdPath path;
  if (!parseSimdPath(value, path))
    throw std::invalid_argument("CLOTHREF_SIMD: unknown SIMD path '" + std::string(value) +
                                "' (sse2, avx2, avx512)");
  if (!simdPathSupported(path))
    throw std::invalid_argument("CLOTHREF_SIMD: this CPU cannot run the " + std::string(value) +
                                " path");
  return path;
}

}  // namespace

SimdPath defaultSimdPath() {
  // decided once, at the first call: the CPU does not change under a running process
  static const SimdPath path = pathFromEnvironment();
  return path;
}

}  // namespace clothref::fast
