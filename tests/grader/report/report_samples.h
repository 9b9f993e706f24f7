// A report with what a student controls in every field the pages show (a folder name with an
// <img>, a path with <b>, a byte that is not UTF-8, a </pre><script> in a check's output), one
// passed and one failed check: the pages' tests start from it (tests/grader/report/*_test.cpp).
#pragma once
#include <cstddef>
#include <string>

#include "grader/grade/cause_ids.h"
#include "grader/grade/results.h"

namespace clothref::grader::test_samples {

inline GradeReport sampleReport() {
  GradeReport report;
  report.submission = "subs/<img src=x onerror=alert(1)>";
  report.edition = 2022;
  report.edition_source = "detected";
  report.files = {{"cloth.cpp", "src/<b>cloth.cpp", true, Verdict::Graded, "", 0, ""},
                  {"sphere.cpp", "", false, Verdict::MissingFile, "missing", 0, ""}};
  report.notes = {"non-UTF-8 bytes \xFF in integrator.cpp"};
  TestResult pass = makeTest("Cloth::initializeSpring", "connections at N = 25", 1);
  pass.fraction = 1;
  pass.score = pass.max_score = 6;
  TestResult fail = makeTest("Spheres::collide(Cloth*)", "approaching pair", 1);
  fail.max_score = 1.25;
  fail.output =
      "State tried:\n\n- sphere 0: x (0.1, 0.42, -0.05)\n  - expected x (1, 2, 3) - actual "
      "x (1, 2, 4)\n\n```\n</pre><script>alert(2)</script>\n```\n\n**Likely cause** "
      "(`collision-normal-sign`): <the normal>";
  fail.causes = {Cause{cause::kCollisionNormalSign,
                       true,
                       {},
                       {},
                       "<the normal>",
                       "<why> it points inwards",
                       "n = -n;  // mistake <b>\nn = xs - xc;  // fix",
                       {}}};
  report.tests = {pass, fail};
  report.stub_score = {{"Cloth::initializeSpring", 6}, {"Spheres::collide(Cloth*)", 0}};
  report.stub_max = {{"Cloth::initializeSpring", 6}, {"Spheres::collide(Cloth*)", 1.25}};
  report.score = 6;
  report.max_score = 7.25;
  return report;
}

// A collision check's state as a sketch: sphere 0 approaching, and (`with_particle`) particle 312
// below it, each with its velocity before, the course's after and the student's after.
inline Sketch sampleSketch(bool with_particle) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0",
                           {0.1f, 0.42f, -0.05f},
                           0.5f,
                           {0.3f, -2, 0.1f},
                           {0.3f, -1.98f, 0.1f},
                           {0.3f, -2, 0.1f}});
  if (with_particle)
    sketch.bodies.push_back({"particle 312",
                             {0, 0, 0},
                             0,
                             {0.2f, 0.5f, -0.1f},
                             {-0.35f, -1.8f, 0.17f},
                             {0.2f, 0.5f, -0.1f}});
  return sketch;
}

inline std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace clothref::grader::test_samples
