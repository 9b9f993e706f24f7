// Likely causes of an integrator's wrong first step from its numbers: the known mistakes
// simulated on the same state (mistakes/integrate_mistakes.h) and compared, RK4's final weights
// fitted on the course's stages, the simulateOneStep() count; the stub's source only refines them.
#pragma once
#include <string>
#include <vector>

#include "grader/grade/probes/integrate/run.h"

namespace clothref::grader::integrators {

// The body of the run's stub in the student's integrator.cpp, comments and literals blanked
// (submission/source_text.h, stubCode), or "".
std::string stubSource(const ProbeContext& context, const std::string& stub);

// The catalogue ids the first step's numbers show (likely). Adds notes to `output`; a per-body
// loop suggested only by the call count is a guess, in `guesses`.
std::vector<std::string> diagnoseOneStep(const ProbeContext& context, const IntegratorRun& run,
                                         std::string& output, std::vector<std::string>& guesses);

}  // namespace clothref::grader::integrators
