// A struct of switches read field by field without a list of its fields (integrate_step.h): an
// aggregate whose fields are switches (bool, int, float, std::array of them), each defaulting to
// the course's, is visited through a structured binding, its field count found by brace
// initialisation. A new switch is its field: merging two models reads it with the others.
#pragma once
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace clothref::grader::integrators::switches {
namespace detail {

// Converts to any field type (in unevaluated brace initialisation only: never defined).
struct Any {
  template <typename T>
  operator T() const;
};

// The number of fields of aggregate T: the most initialisers T{...} takes.
template <typename T, typename... Given>
constexpr std::size_t fieldCount() {
  if constexpr (requires { T{Given{}..., Any{}}; })
    return fieldCount<T, Given..., Any>();
  else
    return sizeof...(Given);
}

// `into` takes `from` where `from` is not the course's; false when both differ from the course
// and from each other (one line set two ways).
template <typename F>
bool take(F& into, const F& from, const F& course) {
  if (from == course || from == into) return true;
  if (into != course) return false;
  into = from;
  return true;
}

}  // namespace detail

// The fields of `s` as references, in their order (a binding of the wrong count does not build,
// so a miscount is a compile error, not a field left out).
template <typename T>
constexpr auto fields(T& s) {
  constexpr std::size_t n = detail::fieldCount<std::remove_const_t<T>>();
  static_assert(n >= 1 && n <= 16, "a struct of switches has 1 to 16 fields (more: a case here)");
  if constexpr (n == 1) {
    auto& [f0] = s;
    return std::tie(f0);
  } else if constexpr (n == 2) {
    auto& [f0, f1] = s;
    return std::tie(f0, f1);
  } else if constexpr (n == 3) {
    auto& [f0, f1, f2] = s;
    return std::tie(f0, f1, f2);
  } else if constexpr (n == 4) {
    auto& [f0, f1, f2, f3] = s;
    return std::tie(f0, f1, f2, f3);
  } else if constexpr (n == 5) {
    auto& [f0, f1, f2, f3, f4] = s;
    return std::tie(f0, f1, f2, f3, f4);
  } else if constexpr (n == 6) {
    auto& [f0, f1, f2, f3, f4, f5] = s;
    return std::tie(f0, f1, f2, f3, f4, f5);
  } else if constexpr (n == 7) {
    auto& [f0, f1, f2, f3, f4, f5, f6] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6);
  } else if constexpr (n == 8) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7);
  } else if constexpr (n == 9) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8);
  } else if constexpr (n == 10) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9);
  } else if constexpr (n == 11) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10);
  } else if constexpr (n == 12) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11);
  } else if constexpr (n == 13) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12);
  } else if constexpr (n == 14) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13);
  } else if constexpr (n == 15) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13, f14] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13, f14);
  } else if constexpr (n == 16) {
    auto& [f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13, f14, f15] = s;
    return std::tie(f0, f1, f2, f3, f4, f5, f6, f7, f8, f9, f10, f11, f12, f13, f14, f15);
  }
}

// `into` with `from`'s switches that differ from the course's (T{}), every field; false when
// both change one field differently.
template <typename T>
bool merge(T& into, const T& from) {
  const T course{};
  auto i = fields(into);
  const auto f = fields(from), c = fields(course);
  return [&]<std::size_t... K>(std::index_sequence<K...>) {
    bool together = true;
    ((together = detail::take(std::get<K>(i), std::get<K>(f), std::get<K>(c)) && together), ...);
    return together;
  }
  (std::make_index_sequence<std::tuple_size_v<decltype(i)>>{});
}

}  // namespace clothref::grader::integrators::switches
