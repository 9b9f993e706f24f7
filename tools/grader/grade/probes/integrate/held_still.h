// Particles and spheres a student's step holds still where the course's method moves them (a
// helper that re-pins the top row or four hard-coded corners; integrator-pins-particles): read
// from the run's one-step states, per cloth size, and laid over a model's step (models.h).
#pragma once
#include <string>
#include <vector>

#include "grader/grade/probes/integrate/run.h"

namespace clothref::grader::integrators {

// Cloth particles a step holds still, on cloths of one size (code that pins hard-coded indices
// only on the course's 25 x 25 cloth leaves the small probe cloth alone).
struct Pins {
  int cloth_size = 0;  // particles of the cloths they apply to
  std::vector<int> particles;
  bool positions = false;  // put back where they were, not only stopped
};

// The cloth particles the student's step leaves at rest where the course's moves them, per cloth
// size: on the random state and on the course's cloth.
std::vector<Pins> pinnedParticles(const IntegratorRun& run);
// The spheres the student's step leaves without velocity where the course's gives them one.
std::vector<int> stoppedSpheres(const IntegratorRun& run);

// `pinned` (those of s's cloth size) and `spheres` held still in `s` after a step that began at
// cloth positions `cloth_x0` (after the first simulateOneStep()).
void holdStill(const std::vector<Pins>& pinned, const std::vector<int>& spheres, System& s,
               const Mat4X<float>& cloth_x0);

// Sorted indices as runs: "0-24", and a column of a grid as "24 to 624 in steps of 25".
std::string indexRanges(const std::vector<int>& indices);

}  // namespace clothref::grader::integrators
