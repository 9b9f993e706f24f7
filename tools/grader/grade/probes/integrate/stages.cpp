// The stage explanation of one integrator run (stages.h).
#include "grader/grade/probes/integrate/stages.h"

#include <cstdio>
#include <fstream>

#include "grader/grade/probes/integrate/diagnosis.h"

namespace clothref::grader::integrators {

std::vector<std::string> RunStages::causes(bool likely) const {
  std::vector<std::string> ids;
  if (right()) return ids;
  for (const stages::StageCause& c : explanation.causes)
    if (c.likely == likely) ids.push_back(c.id);
  return ids;
}

const stages::StageCause* RunStages::cause(const std::string& id) const {
  for (const stages::StageCause& c : explanation.causes)
    if (c.id == id) return &c;
  return nullptr;
}

std::string RunStages::markdown() const {
  if (right()) return "";
  char h[32];
  std::snprintf(h, sizeof h, "%.4g", fit.record.h);
  return "\n**Your stages.** One step of the same cloth and spheres without contact, at deltaTime "
         "h = " +
         std::string(h) +
         " s (small enough for every course method to be stable), every state your integrate() "
         "handed to simulateOneStep() written in the course's terms. " +
         stages::stageText(fit, explanation);
}

RunStages explainRun(const ProbeContext& context, const IntegratorRun& run, bool course_size) {
  RunStages out;
  stages::StageRecord record;
  if (!stages::stageRecordFrom(run.answer, run.stage_case, double(stages::kStageStep), record))
    return out;
  out.recorded = true;
  out.fit = stages::fitStages(record);
  out.explanation =
      stages::explainStages(out.fit, run.index, sourceHints(stubSource(context, run.stub)));
  if (context.limits.keep_files)
    std::ofstream(context.work_dir / integratorFolder(run.index, course_size) / "stages.json")
        << stages::stageJson(out.fit, out.explanation);
  return out;
}

std::string stagesShownUnder(const std::string& check) {
  return "\nYour stages are compared with the course's under “" + check + "” above.\n";
}

}  // namespace clothref::grader::integrators
