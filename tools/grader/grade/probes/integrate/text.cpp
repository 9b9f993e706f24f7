// The integrator probe's Markdown (text.h).
#include "grader/grade/probes/integrate/text.h"

#include <algorithm>
#include <cmath>

namespace clothref::grader::integrators {

std::string systemText(const System& s) {
  const std::string bodies =
      s.course_size
          ? "the course's " + std::to_string(s.cloth.particles.size()) +
                "-particle cloth (corners fixed, k_s = 500, k_d = 5, positions and velocities "
                "randomly perturbed) and its " +
                std::to_string(s.spheres.size()) + " sphere(s) under gravity"
          : "a 4 x 4 cloth (corners fixed, k_s = 500, k_d = 5, positions and velocities randomly "
            "perturbed) and 2 spheres under gravity, sphere 0 pressing on cloth particle 5 "
            "(sphere-cloth contact inside simulateOneStep)";
  return bodies + ", dt = " + util::num(s.dt) + "; first free cloth particle (index 1): x " +
         util::vec3(s.cloth.particles.position.col(1)) + ", v " +
         util::vec3(s.cloth.particles.velocity.col(1)) + "; sphere 0: x " +
         util::vec3(s.spheres.particles.position.col(0)) + ", v " +
         util::vec3(s.spheres.particles.velocity.col(0));
}

namespace {

// The course's cloth after one step: how many cloth particles part from
// the course method's, and the one that parts most.
std::string courseClothText(const OneStep& step, double rel) {
  const auto& e = step.expected.cloth.particles;
  const auto& a = step.actual.cloth.particles;
  int differ = 0, worst = 0;
  double worst_distance = -1;
  for (int j = 0; j < e.size() && j < a.size(); ++j) {
    double d = 0;  // as distance() measures: |a - e| / (1 + |e|), NaN as far
    const auto part = [&](const Mat4X<float>& ev, const Mat4X<float>& av) {
      for (int r = 0; r < 3; ++r) {
        const double x =
            std::abs(double(av(r, j)) - double(ev(r, j))) / (1 + std::abs(double(ev(r, j))));
        d = std::isfinite(x) ? std::max(d, x) : 1e300;
      }
    };
    part(e.position, a.position);
    part(e.velocity, a.velocity);
    if (d > rel) ++differ;
    if (d > worst_distance) worst_distance = d, worst = j;
  }
  const util::Tolerance tolerance{rel, rel};
  const std::string p = "cloth particle " + std::to_string(worst);
  const auto& masses = step.state.cloth.particles.mass;
  const bool pinned = std::any_of(masses.begin(), masses.end(), [](float m) { return m == 0; });
  return "State 2: the course's " + std::to_string(e.size()) + "-particle cloth (" +
         (pinned ? "corners fixed" : "corners unpinned, as the program's keys 1-4 leave them") +
         ", perturbed) and its " + std::to_string(step.state.spheres.size()) +
         " sphere(s), no contact, dt = " + util::num(step.state.dt) + ": after one step " +
         std::to_string(differ) + " cloth particles part from the course method's, the most " + p +
         ":\n\n" +
         util::compareVectors(p + ", x", e.position.col(worst), a.position.col(worst), tolerance,
                              "m") +
         util::compareVectors(p + ", v", e.velocity.col(worst), a.velocity.col(worst), tolerance,
                              "m/s");
}

}  // namespace

std::string oneStepText(const IntegratorRun& run) {
  const System& e = run.expected;
  const System& a = run.actual;
  const util::Tolerance tolerance{run.rel, run.rel};
  if (run.distance <= run.rel)  // only the course's cloth parts
    return "State: " + systemText(run.random) +
           ".\n\nAfter one step: the course method's, every body, x and v.\n\n" +
           (run.course_cloth ? courseClothText(*run.course_cloth, run.rel) : "");
  std::string text = "State: " + systemText(run.random) +
                     ".\n\nAfter one step (expected: the course method's):\n\n" +
                     util::compareVectors("cloth particle 1, x", e.cloth.particles.position.col(1),
                                          a.cloth.particles.position.col(1), tolerance, "m") +
                     util::compareVectors("cloth particle 1, v", e.cloth.particles.velocity.col(1),
                                          a.cloth.particles.velocity.col(1), tolerance, "m/s") +
                     util::compareVectors("sphere 0, x", e.spheres.particles.position.col(0),
                                          a.spheres.particles.position.col(0), tolerance, "m");
  if (run.course_cloth && run.course_cloth->distance > run.rel)
    text += "\n" + courseClothText(*run.course_cloth, run.rel);
  return text;
}

std::string orderText(const IntegratorRun& run, const std::vector<double>& student_errors,
                      const std::vector<double>& reference_errors, bool usable, double observed,
                      double expected_order) {
  std::string table = "| dt (s) | your max error (m) | course method's |\n|---|---|---|\n";
  for (std::size_t k = 0; k < run.dts.size(); ++k)
    table += "| " + util::num(run.dts[k]) + " | " + util::num(student_errors[k]) + " | " +
             util::num(reference_errors[k]) + " |\n";
  return "A unit mass on a damped spring (k = 100 N/m, c = 2 N s/m, rest 1 m, released at 1.2 "
         "m), " +
         util::num(run.end_time) + " s against the closed form, at " +
         std::to_string(run.dts.size()) + " step sizes. Observed order " +
         (usable ? util::num(observed) : std::string("not measurable")) + ", the course method's " +
         util::num(expected_order) + " (theory " + std::to_string(methodInfo(run.method).order) +
         ").\n\n" + table;
}

std::string stabilityText(const IntegratorRun& run, double amplitude) {
  return "The same spring for 20 s at dt = " + util::num(run.stable_dt) +
         " s, half the course method's stability limit " + util::num(run.limit) +
         " s. Largest |stretch| " +
         (amplitude >= 1e299 ? std::string("not finite") : util::num(amplitude)) +
         " m (released at 0.2 m; must stay below 0.3 m).\n";
}

}  // namespace clothref::grader::integrators
