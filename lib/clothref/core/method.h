// The method table: every integration method the library offers, one row each. Every list of
// methods (the CLI's choices, the golden set, verify's orders, the docs' tables) reads this table,
// so a new method is one row here plus its function (and one line in integrate(), or, for a
// method that needs more than the core has, a MethodStepper that the area implementing it
// installs in the world: see `stepped_by_solver`).
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "clothref/base/enum_table.h"

namespace clothref {

enum class Method { Explicit, Implicit, Midpoint, Rk4, Symplectic, BackwardEuler };

// Where a method comes from: one of the course's stubs (with the course's semantics, whatever its
// name says), or a textbook method offered beside them under its honest name.
enum class MethodOrigin { Course, Textbook };

struct MethodInfo {
  Method method;
  std::string_view name;  // on the command line, in traces and scene files
  int order;              // global order of accuracy the method is built to have
  int evaluations;        // derivative evaluations per step, counting the step's own
  bool needs_callback;    // calls simulateOneStep during integrate()
  MethodOrigin origin;
  std::string_view course_name;  // the course's class, or "" for a textbook method
  std::string_view summary;
  // Stepped by clothref/solver (a linear solve per step) through World::stepper, not by the
  // core's integrate(); makeWorld installs the stepper.
  bool stepped_by_solver = false;
};

inline constexpr std::array<MethodInfo, 6> kMethods{{
    {Method::Explicit, "explicit", 1, 1, false, MethodOrigin::Course, "ExplicitEuler",
     "forward Euler: x += v dt, then v += a dt"},
    {Method::Implicit, "implicit", 1, 2, true, MethodOrigin::Course, "ImplicitEuler",
     "the course's one predictor-corrector pass of backward Euler"},
    {Method::Midpoint, "midpoint", 2, 2, true, MethodOrigin::Course, "MidpointEuler",
     "explicit midpoint: half step, evaluate, full step from the start"},
    {Method::Rk4, "rk4", 4, 4, true, MethodOrigin::Course, "RungeKuttaFourth",
     "classical fourth-order Runge-Kutta"},
    {Method::Symplectic, "symplectic", 1, 1, false, MethodOrigin::Textbook, "",
     "symplectic (semi-implicit) Euler: v += a dt, then x += v dt"},
    {Method::BackwardEuler, "backward-euler", 1, 1, false, MethodOrigin::Textbook, "",
     "backward Euler linearised once per step (Baraff & Witkin): one sparse CG solve per step",
     true},
}};

// The row of `method`.
constexpr const MethodInfo& methodInfo(Method method) {
  for (const MethodInfo& info : kMethods)
    if (info.method == method) return info;
  return kMethods[0];  // unreachable for a listed method
}

// Every method, in table order.
inline constexpr auto kAllMethods = [] {
  std::array<Method, kMethods.size()> methods{};
  for (std::size_t i = 0; i < kMethods.size(); ++i) methods[i] = kMethods[i].method;
  return methods;
}();

// The methods the core's integrate() steps (every row not stepped by the solver), in table order.
inline constexpr auto kIntegratorMethods = [] {
  constexpr std::size_t count = [] {
    std::size_t n = 0;
    for (const MethodInfo& info : kMethods) n += info.stepped_by_solver ? 0 : 1;
    return n;
  }();
  std::array<Method, count> methods{};
  std::size_t i = 0;
  for (const MethodInfo& info : kMethods)
    if (!info.stepped_by_solver) methods[i++] = info.method;
  return methods;
}();

// The {value, name} table the generic enum functions read.
inline constexpr auto kMethodNames = [] {
  EnumTable<Method, kMethods.size()> names{};
  for (std::size_t i = 0; i < kMethods.size(); ++i)
    names[i] = {kMethods[i].method, kMethods[i].name};
  return names;
}();

constexpr std::string_view methodName(Method method) { return methodInfo(method).name; }

// The method named `name`, or nothing.
constexpr std::optional<Method> parseMethod(std::string_view name) {
  return parseEnum(kMethodNames, name);
}

}  // namespace clothref
