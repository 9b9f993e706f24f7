// The integrator probe's Markdown: the state tried, the first step expected against the student's,
// the convergence table and the stability run, in the course's units.
#pragma once
#include <string>
#include <vector>

#include "grader/grade/probes/integrate/run.h"

namespace clothref::grader::integrators {

// The system in a line: which bodies, dt, and the first free cloth particle and sphere 0.
std::string systemText(const System& s);

// The state, then one step of the course method against the student's (particle 1, sphere 0).
std::string oneStepText(const IntegratorRun& run);

// The spring run, the observed and expected orders, and one row per step size.
std::string orderText(const IntegratorRun& run, const std::vector<double>& student_errors,
                      const std::vector<double>& reference_errors, bool usable, double observed,
                      double expected_order);

// The stability run and its largest stretch (>= 1e299: not finite).
std::string stabilityText(const IntegratorRun& run, double amplitude);

}  // namespace clothref::grader::integrators
