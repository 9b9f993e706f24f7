// Not a test of its own: tests/CMakeLists.txt builds this file and expects the build to fail,
// because the switch below lacks a method (core/method.h: a switch over Method has every case and
// no `default:`, and -Werror=switch makes a missing one an error). So adding a row to the method
// table without a case in every switch over methods cannot build.
#include "clothref/core/method.h"

namespace clothref {

int evaluationsBySwitch(Method method) {
  switch (method) {
    case Method::Explicit:
    case Method::Symplectic:
      return 1;
    case Method::Implicit:
    case Method::Midpoint:
      return 2;
    case Method::Rk4:
      return 4;
      // Method::BackwardEuler is missing on purpose
  }
  return 0;
}

}  // namespace clothref

int main() { return clothref::evaluationsBySwitch(clothref::Method::Rk4) == 4 ? 0 : 1; }
