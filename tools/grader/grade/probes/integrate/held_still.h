// Particles and spheres a student's step holds still where the course's method moves them (a
// helper that re-pins the top row or four hard-coded corners; integrator-pins-particles): read
// from the run's one-step states, per cloth size, and laid over a model's step (an Overlay of
// mistakes/integrate_mistakes.h, which holds them still).
#pragma once
#include <string>
#include <vector>

#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/probes/integrate/run.h"

namespace clothref::grader::integrators {

// The cloth particles the student's step leaves at rest where the course's moves them, per cloth
// size: on the random state and on the course's cloth.
std::vector<Pins> pinnedParticles(const IntegratorRun& run);
// The spheres the student's step leaves without velocity where the course's gives them one.
std::vector<int> stoppedSpheres(const IntegratorRun& run);

// Sorted indices as runs: "0-24", and a column of a grid as "24 to 624 in steps of 25".
std::string indexRanges(const std::vector<int>& indices);

}  // namespace clothref::grader::integrators
