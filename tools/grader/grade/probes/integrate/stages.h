// The stage explanation of one integrator run (stages.h) for the probe's checks: the fit of the
// recorded contact-free step (h = stages::kStageStep, where every course method is stable, so an
// unstable stub is explained too), its Markdown as a student reads it, and the catalogue ids it
// shows (likely) or suggests (possible). Kept as stages.json beside the probe's files under
// --keep-work.
#pragma once
#include <string>
#include <vector>

#include "grader/grade/explain/stages/stages.h"
#include "grader/grade/probes/integrate/run.h"

namespace clothref::grader::integrators {

struct RunStages {
  bool recorded = false;  // the answer held a stage record
  stages::StageFit fit;
  stages::StageExplanation explanation;
  // The course's method or an accepted variant, stage by stage: nothing to explain.
  bool right() const { return !recorded || explanation.course || !explanation.accepted.empty(); }
  // The explanation's causes, likely (the fit shows them) or not (a possibility).
  std::vector<std::string> causes(bool likely) const;
  const stages::StageCause* cause(const std::string& id) const;
  // The Markdown for the first failed check of the stub ("" when right()).
  std::string markdown() const;
};

// Fits and explains the run's stage record; writes stages.json when the work folder is kept.
RunStages explainRun(const ProbeContext& context, const IntegratorRun& run, bool course_size);

// The line a later failed check of the stub shows instead of repeating the explanation.
std::string stagesShownUnder(const std::string& check);

}  // namespace clothref::grader::integrators
