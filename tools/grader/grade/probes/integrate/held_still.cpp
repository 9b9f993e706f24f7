// Particles and spheres a step holds still (held_still.h).
#include "grader/grade/probes/integrate/held_still.h"

#include <algorithm>

namespace clothref::grader::integrators {

// The cloth particles the student's step leaves at rest where the course's moves them, per
// cloth size: on the random state and on the course's cloth.
std::vector<Pins> pinnedParticles(const IntegratorRun& run) {
  std::vector<Pins> all;
  const auto read = [&](const System& actual, const System& expected, const System& start) {
    const auto& a = actual.cloth.particles;
    const auto& e = expected.cloth.particles;
    Pins pins{a.size(), {}, true};
    for (int j = 0; j < a.size() && j < e.size(); ++j)
      if (a.velocity.col(j).isZero(0) && !e.velocity.col(j).isZero(0)) {
        pins.particles.push_back(j);
        pins.positions =
            pins.positions && a.position.col(j) == start.cloth.particles.position.col(j);
      }
    if (pins.particles.empty()) return;
    for (Pins& same : all)
      if (same.cloth_size == pins.cloth_size) {  // the course-size retry: both states 625
        for (int j : pins.particles)
          if (std::find(same.particles.begin(), same.particles.end(), j) == same.particles.end())
            same.particles.push_back(j);
        std::sort(same.particles.begin(), same.particles.end());
        same.positions = same.positions && pins.positions;
        return;
      }
    all.push_back(std::move(pins));
  };
  read(run.actual, run.expected, run.start);
  if (run.course_cloth)
    read(run.course_cloth->actual, run.course_cloth->expected, run.course_cloth->start);
  return all;
}

// The spheres the student's step leaves without velocity where the course's gives them one (a
// helper that holds them still).
std::vector<int> stoppedSpheres(const IntegratorRun& run) {
  std::vector<int> stopped;
  const auto& a = run.actual.spheres.particles;
  const auto& e = run.expected.spheres.particles;
  for (int j = 0; j < a.size() && j < e.size(); ++j)
    if (a.velocity.col(j).isZero(0) && !e.velocity.col(j).isZero(0)) stopped.push_back(j);
  return stopped;
}

// Sorted indices as runs: "0-24", and a column of a grid as "24 to 624 in steps of 25".
std::string indexRanges(const std::vector<int>& indices) {
  std::string out;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t e = k;
    while (e + 1 < indices.size() && indices[e + 1] == indices[e] + 1) ++e;
    std::string run = std::to_string(indices[k]) + (e > k ? "-" + std::to_string(indices[e]) : "");
    if (e == k && k + 1 < indices.size()) {  // an evenly spaced run of four or more
      const int step = indices[k + 1] - indices[k];
      std::size_t f = k + 1;
      while (f + 1 < indices.size() && indices[f + 1] - indices[f] == step) ++f;
      if (f - k >= 3) {
        run = std::to_string(indices[k]) + " to " + std::to_string(indices[f]) + " in steps of " +
              std::to_string(step);
        e = f;
      }
    }
    out += (out.empty() ? "" : ", ") + run;
    k = e + 1;
  }
  return out;
}

}  // namespace clothref::grader::integrators
