// A student's source as text: comments and literals blanked, and where a stub's body lies. Used by
// edition detection, the quoting of source lines and the integrator probe's source patterns.
#pragma once
#include <string>

namespace clothref::grader {

// `source` with every comment and string or character literal blanked (newlines kept, so line
// numbers stay): the one comment stripper of the grader (edition detection, stub lines, the
// integrator probe's source patterns).
std::string blankedCode(const std::string& source);

// The lines of a stub's body in a student file: from the line of its opening brace to the line of
// its closing one (1-based); first = 0 when the file defines no such function.
struct StubLines {
  int first = 0, last = 0;
  bool contains(int line) const { return first > 0 && line >= first && line <= last; }
};
// Finds the definition of `stub`, a course name from stubTable() ("RungeKuttaFourth::integrate",
// "Spheres::collide(Cloth*)", "Spheres::collide()": a parameter list in the name picks the
// overload), ignoring comments and string literals and skipping declarations.
StubLines stubLines(const std::string& source, const std::string& stub);
// The body of `stub` found as stubLines finds it, from its opening brace to the closing one,
// blanked (blankedCode); "" when the file defines no such function.
std::string stubCode(const std::string& source, const std::string& stub);

}  // namespace clothref::grader
