// The method table: every integration method the library offers, one row each. Every list of
// methods (the CLI's choices, the golden set, verify's orders and energy checks, the stability
// theory, the grader's stability check, the docs' tables) reads this table, so a new method is one
// row here plus its function (and one line in integrate(), or, for a method that needs more than
// the core has, a MethodStepper that the area implementing it installs in the world: see
// `stepped_by_solver`). A switch over Method never has a `default:`: the build makes a missing
// case an error (-Werror=switch), so a new row cannot be forgotten in one.
#pragma once

#include <algorithm>
#include <array>
#include <complex>
#include <limits>
#include <optional>
#include <string_view>

#include "clothref/base/enum_table.h"

namespace clothref {

enum class Method { Explicit, Implicit, Midpoint, Rk4, Symplectic, BackwardEuler };

// Where a method comes from: one of the course's stubs (with the course's semantics, whatever its
// name says), or a textbook method offered beside them under its honest name.
enum class MethodOrigin { Course, Textbook };

// A coefficient of a polynomial in z: numerator / denominator (exact in any precision).
struct Coefficient {
  int numerator = 0;
  int denominator = 1;
};

// How one step of a method acts on the linear test equation y' = lambda y, z = lambda dt.
enum class AmplificationKind {
  // y is multiplied by R(z) = P(z) / Q(z), P and Q polynomials of degree <= 4 in z
  Rational,
  // symplectic Euler: it updates x and v differently, so on a second-order mode
  // x'' = -kappa x - delta x' its step is a 2 x 2 matrix, not a function of z
  // (analysis/stability.cpp)
  SymplecticEuler,
};

struct Amplification {
  AmplificationKind kind = AmplificationKind::Rational;
  std::array<Coefficient, 5> p{};                          // coefficients of z^0 .. z^4
  std::array<Coefficient, 5> q{{{1, 1}, {}, {}, {}, {}}};  // Q = 1 unless the method solves
};

struct MethodInfo {
  Method method;
  std::string_view name;  // on the command line, in traces and scene files
  int order;              // global order of accuracy the method is built to have
  int evaluations;        // derivative evaluations per step, counting the step's own
  bool needs_callback;    // calls simulateOneStep during integrate()
  MethodOrigin origin;
  std::string_view course_name;  // the course's class, or "" for a textbook method
  std::string_view summary;
  Amplification amplification;  // R(z) on y' = lambda y: stability theory, verify, the grader
  // Stepped by clothref/solver (a linear solve per step) through World::stepper, not by the
  // core's integrate(); makeWorld installs the stepper.
  bool stepped_by_solver = false;
};

// One row per method; the last field, R(z), as {kind, P's coefficients, Q's (default 1)}, each
// coefficient {numerator, denominator} of z^0, z^1, ...
// clang-format off
inline constexpr std::array<MethodInfo, 6> kMethods{{
    {Method::Explicit, "explicit", 1, 1, false, MethodOrigin::Course, "ExplicitEuler",
     "forward Euler: x += v dt, then v += a dt",
     {AmplificationKind::Rational, {{{1, 1}, {1, 1}}}}},                          // 1 + z
    {Method::Implicit, "implicit", 1, 2, true, MethodOrigin::Course, "ImplicitEuler",
     "the course's one predictor-corrector pass of backward Euler",
     {AmplificationKind::Rational, {{{1, 1}, {1, 1}, {1, 1}}}}},                  // 1 + z + z^2
    {Method::Midpoint, "midpoint", 2, 2, true, MethodOrigin::Course, "MidpointEuler",
     "explicit midpoint: half step, evaluate, full step from the start",
     {AmplificationKind::Rational, {{{1, 1}, {1, 1}, {1, 2}}}}},                  // 1 + z + z^2/2
    {Method::Rk4, "rk4", 4, 4, true, MethodOrigin::Course, "RungeKuttaFourth",
     "classical fourth-order Runge-Kutta",
     {AmplificationKind::Rational, {{{1, 1}, {1, 1}, {1, 2}, {1, 6}, {1, 24}}}}}, // ... + z^4/24
    {Method::Symplectic, "symplectic", 1, 1, false, MethodOrigin::Textbook, "",
     "symplectic (semi-implicit) Euler: v += a dt, then x += v dt",
     {AmplificationKind::SymplecticEuler}},                                       // a 2 x 2 matrix
    {Method::BackwardEuler, "backward-euler", 1, 1, false, MethodOrigin::Textbook, "",
     "backward Euler linearised once per step (Baraff & Witkin): one sparse CG solve per step",
     {AmplificationKind::Rational, {{{1, 1}}}, {{{1, 1}, {-1, 1}}}}, true},      // 1 / (1 - z)
}};
// clang-format on

// The row of `method`.
constexpr const MethodInfo& methodInfo(Method method) {
  for (const MethodInfo& info : kMethods)
    if (info.method == method) return info;
  return kMethods[0];  // unreachable for a listed method
}

// A polynomial of the table at z, summed from z^0 up, each term (z^k * numerator) / denominator
// with z^k = z * z * ... (so RK4's R is 1 + z + z*z/2 + z*z*z/6 + z*z*z*z/24, bit for bit).
template <typename Z>
Z evaluatePolynomial(const std::array<Coefficient, 5>& coefficients, Z z) {
  Z sum(0);
  Z power(1);
  for (std::size_t k = 0; k < coefficients.size(); ++k) {
    if (k) power = k == 1 ? z : power * z;
    const Coefficient& c = coefficients[k];
    if (c.numerator == 0) continue;
    Z term = c.numerator == 1 ? power : power * typename Z::value_type(c.numerator);
    if (c.denominator != 1) term /= typename Z::value_type(c.denominator);
    sum = k ? sum + term : term;
  }
  return sum;
}

// R(z) of a Rational amplification (NaN for one that is not a function of z).
template <typename T>
std::complex<T> amplification(const Amplification& a, std::complex<T> z) {
  if (a.kind != AmplificationKind::Rational)
    return std::complex<T>(std::numeric_limits<T>::quiet_NaN(), 0);
  const std::complex<T> p = evaluatePolynomial(a.p, z);
  const bool q_is_one = a.q[0].numerator == 1 && a.q[0].denominator == 1 &&
                        std::all_of(a.q.begin() + 1, a.q.end(),
                                    [](const Coefficient& c) { return c.numerator == 0; });
  return q_is_one ? p : p / evaluatePolynomial(a.q, z);
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
