// Precision: the floating-point type of a run (float is the course's), its names, and the one
// dispatch from the runtime choice to the template parameter.
#pragma once

#include <utility>

#include "clothref/base/enum_table.h"

namespace clothref {

enum class Precision { Float, Double };

inline constexpr EnumTable<Precision, 2> kPrecisionNames{{
    {Precision::Float, "float"},
    {Precision::Double, "double"},
}};

constexpr std::string_view precisionName(Precision precision) {
  return enumName(kPrecisionNames, precision);
}

// Calls f.template operator()<float>() or <double>() for `precision` and returns its result:
//   withPrecision(p, [&]<typename T>() { return run<T>(...); })
template <typename F>
decltype(auto) withPrecision(Precision precision, F&& f) {
  if (precision == Precision::Float) return std::forward<F>(f).template operator()<float>();
  return std::forward<F>(f).template operator()<double>();
}

}  // namespace clothref
