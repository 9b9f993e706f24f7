// The integrators' causes proven by replay (docs/grading-reference.md, "Likely means proven"):
// each cause named on a stub's checks has one or more models (the course's step with that
// mistake's rows, mistakes/integrate_mistakes.h, or with what is fitted from the run laid over it:
// another step, result weights, a velocity factor, pinned particles), and a model proves its
// cause only when, run on every probe state of the stub (the
// random state, the convergence ladder, the stability run), it gives the student's numbers on
// every check. A cause no model proves is a guess whose line says where its best model parts.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "grader/grade/explain/replay.h"
#include "grader/grade/probes/integrate/models.h"
#include "grader/grade/probes/integrate/run.h"
#include "grader/grade/probes/integrate/stages.h"

namespace clothref::grader::integrators {

// `model` replayed on every probe state of the run: the one-step check (positions, velocities),
// which bodies move, deltaTime after the call, the backups check, the convergence order and the
// stability run, each against the student's numbers within the check's tolerance.
Replay replayIntegrator(const IntegratorModel& model, const ProbeContext& context,
                        const IntegratorRun& run, const std::vector<TestResult>& tests);

// Proves the causes of a failed stub: the models of the causes its tests name (likely first,
// then possible), of the stage fit's, then of every other cause with a model for the method;
// the first model that gives the student's numbers everywhere names its causes likely on every
// failed check (another that does too is an alternative reading, named as a guess that says so);
// with none, two models' switches together. A cause named but not proven becomes a guess
// with its best model's line. deltaTime read after the call and the symptoms (unstable,
// wrong-order) stay as read.
void proveIntegratorCauses(const ProbeContext& context, const IntegratorRun& run,
                           const RunStages& stages, std::vector<TestResult>& tests);

}  // namespace clothref::grader::integrators
