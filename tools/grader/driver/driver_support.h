// The driver's shared part (driver/probe_driver.cpp, the child's main): reading and writing a
// message's body states, the stack fill before a student's stub, the spring set of a request and
// the course's integrator of a method row. Each group's course side is a header of groups/
// (one per probe, found by the build); this header and those are included into the one
// translation unit of probe_driver.cpp, so their functions keep internal linkage there, as when
// they were one file: the compiler inlines them as before, and a crash report counts the same
// driver frames outside the student's files.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// std only, the headers of clothref the course side may include (docs/layout.md): the course's
// formulas and the method table
#include "clothref/core/method.h"
#include "clothref/formula/course_formulas.h"
#include "grader/bridge/probe_keys.h"
#include "grader/bridge/probe_protocol.h"

// the course's headers (the stand-in of this edition)
#include "cloth.h"
#include "configs.h"
#include "integrator.h"
#include "particles.h"
#include "sphere.h"

// Internal linkage in the one translation unit that includes it (the comment above says why).
namespace {

using probe::ProbeMessage;
namespace key = probe::key;
namespace group = probe::group;
using key::perCase;

// A request the driver cannot serve (an unknown group or method): main refuses it.
struct BadRequest {
  std::string why;
};

// ---- The stack a student's stub starts on (issue 38: undefined behaviour that neither crashes
// nor varies). A local the stub reads before it writes it (`Eigen::Vector4f force; force += ...`)
// holds what the stack held there, the same bytes in both runs of a probe. So before each call of
// a stub the driver fills the stack below its own frame, where the stub's frame will be, with one
// byte: 0x00, or the byte of probe::kStackFillVariable (0xff in the second run: NaN in every
// float, -1 in every int). A stub that reads such a local answers differently in the two runs
// (undefined-behaviour); one that does not reads none of these bytes and answers the same.
constexpr std::size_t kStackFillBytes = 32 << 10;  // more than a stub's frame of fixed-size Eigen

unsigned char stackFillByte() {
  static const unsigned char byte = [] {
    const char* fill = std::getenv(probe::kStackFillVariable);
    return fill ? static_cast<unsigned char>(std::strtoul(fill, nullptr, 16)) : 0;
  }();
  return byte;
}

// Not inlined, so that its frame lies where the next call's will; the empty asm that reads the
// array keeps the stores (the array is dead after them).
[[gnu::noinline]] void fillStack() {
  unsigned char below[kStackFillBytes];
  std::memset(below, stackFillByte(), sizeof below);
  asm volatile("" : : "r"(below) : "memory");
}

// Copies a 4 x n column-major float array in or out of a Particles matrix.
void load(Eigen::Ref<Eigen::Matrix4Xf> target, const std::vector<float>& values) {
  const long n = std::min<long>(target.cols(), static_cast<long>(values.size() / 4));
  for (long c = 0; c < n; ++c)
    for (int r = 0; r < 4; ++r) target(r, c) = values[static_cast<size_t>(4 * c + r)];
}
std::vector<float> save(const Eigen::Ref<Eigen::Matrix4Xf>& source) {
  return std::vector<float>(source.data(), source.data() + source.size());
}
void loadMass(Particles& particles, const std::vector<float>& masses) {
  for (size_t i = 0; i < masses.size() && i < particles.mass().size(); ++i)
    particles.mass(static_cast<int>(i)) = masses[i];
}

// The spring set sent under the spring keys: once (k < 0) or as case k.
std::vector<Spring> springsFrom(const ProbeMessage& in, int k) {
  const auto name = [k](const char* spring_key) {
    return k < 0 ? std::string(spring_key) : perCase(spring_key, k);
  };
  const auto& start = in.i(name(key::kSpringStart));
  const auto& end = in.i(name(key::kSpringEnd));
  const auto& type = in.i(name(key::kSpringType));
  const auto& rest = in.f(name(key::kSpringRest));
  std::vector<Spring> springs;
  for (size_t s = 0; s < start.size() && s < end.size() && s < rest.size(); ++s)
    springs.emplace_back(
        static_cast<unsigned>(start[s]), static_cast<unsigned>(end[s]), rest[s],
        s < type.size() ? static_cast<Spring::Type>(type[s]) : Spring::Type::STRUCTURAL);
  return springs;
}

// The rows of clothref's method table (core/method.h), copied at compile time: the driver holds
// no clothref symbol that a student's file could declare and reach.
constexpr auto kMethodRows = [] {
  std::array<std::pair<clothref::Method, std::string_view>, clothref::kMethods.size()> rows{};
  for (std::size_t row = 0; row < rows.size(); ++row)
    rows[row] = {clothref::kMethods[row].method, clothref::kMethods[row].name};
  return rows;
}();

// The course's integrator of the request's key::kMethod, a row of the method table; a row the
// course has no class for, or a number outside the table, is refused.
const Integrator& integratorFor(std::int64_t row) {
  static const ExplicitEuler explicitEuler;
  static const ImplicitEuler implicitEuler;
  static const MidpointEuler midpointEuler;
  static const RungeKuttaFourth rungeKutta;
  if (row < 0 || row >= std::ssize(kMethodRows))
    throw BadRequest{"no method " + std::to_string(row) + " in the method table"};
  const auto& [method, name] = kMethodRows[static_cast<std::size_t>(row)];
  switch (method) {
    case clothref::Method::Explicit:
      return explicitEuler;
    case clothref::Method::Implicit:
      return implicitEuler;
    case clothref::Method::Midpoint:
      return midpointEuler;
    case clothref::Method::Rk4:
      return rungeKutta;
    case clothref::Method::Symplectic:
    case clothref::Method::BackwardEuler:
      break;  // textbook methods: the course has no class for them
  }
  throw BadRequest{"method " + std::string(name) + " is not one of the course's integrators"};
}

}  // namespace
