// The stage record from the integrator probe's answer (bridge/probe_keys.h, "the stage record"),
// and the explanation as structured data (stages.h).
#include <nlohmann/json.hpp>

#include "grader/bridge/probe_keys.h"
#include "grader/bridge/probe_protocol.h"
#include "grader/grade/explain/stages/stages.h"

namespace clothref::grader::stages {

static_assert(probe::key::kMaxStageRecords == kMaxRecordedCalls, "one cap on both sides");

namespace {

std::vector<double> doubles(const std::vector<float>& values, std::size_t from = 0,
                            std::size_t count = std::size_t(-1)) {
  std::vector<double> out;
  for (std::size_t i = from; i < values.size() && i - from < count; ++i) out.push_back(values[i]);
  return out;
}

}  // namespace

bool stageRecordFrom(const probe::ProbeMessage& answer, int k, double h, StageRecord& record) {
  namespace key = probe::key;
  const auto f = [&](const char* name) -> const std::vector<float>& {
    return answer.f(key::perCase(name, k));
  };
  record = StageRecord{};
  record.h = h;
  const auto& after = f(key::kDtAfter);
  record.h_after = after.empty() ? h : double(after[0]);
  const auto& calls = answer.i(key::perCase(key::kCalls, k));
  record.calls = calls.empty() ? 0 : int(calls[0]);
  const char* starts[2][3] = {{key::kStartClothPos, key::kStartClothVel, key::kStartClothAcc},
                              {key::kStartSpherePos, key::kStartSphereVel, key::kStartSphereAcc}};
  const char* evals[2][3] = {{key::kEvalClothPos, key::kEvalClothVel, key::kEvalClothAcc},
                             {key::kEvalSpherePos, key::kEvalSphereVel, key::kEvalSphereAcc}};
  const char* results[2][2] = {{key::kClothPos, key::kClothVel},
                               {key::kSpherePos, key::kSphereVel}};
  std::size_t records = std::size_t(-1);
  for (int b = 0; b < 2; ++b) {
    BodyState& start = record.start[std::size_t(b)];
    start.x = doubles(f(starts[b][0]));
    start.v = doubles(f(starts[b][1]));
    start.a = doubles(f(starts[b][2]));
    record.result[std::size_t(b)].x = doubles(f(results[b][0]));
    record.result[std::size_t(b)].v = doubles(f(results[b][1]));
    const std::size_t size = start.x.size();
    if (size == 0 && b == kCloth) return false;
    if (start.v.size() != size || start.a.size() != size ||
        record.result[std::size_t(b)].x.size() != size ||
        record.result[std::size_t(b)].v.size() != size)
      return false;
    for (int part = 0; part < 3; ++part) {
      const std::size_t n = size == 0 ? 0 : f(evals[b][part]).size() / size;
      if (size != 0 && f(evals[b][part]).size() % size != 0) return false;
      if (size != 0) records = std::min(records, n);
    }
  }
  if (records == std::size_t(-1)) records = 0;
  record.evaluations.resize(std::min<std::size_t>(records, kMaxRecordedCalls));
  for (std::size_t r = 0; r < record.evaluations.size(); ++r)
    for (int b = 0; b < 2; ++b) {
      const std::size_t size = record.start[std::size_t(b)].x.size();
      BodyState& s = record.evaluations[r][std::size_t(b)];
      s.x = doubles(f(evals[b][0]), r * size, size);
      s.v = doubles(f(evals[b][1]), r * size, size);
      s.a = doubles(f(evals[b][2]), r * size, size);
    }
  return true;
}

std::string stageJson(const StageFit& fit, const StageExplanation& e) {
  nlohmann::json out;
  out["method"] = e.method;
  out["calls"] = e.calls;
  out["course_calls"] = e.course_calls;
  out["recorded"] = fit.recorded;
  out["fits"] = e.fits;
  out["course"] = e.course;
  out["accepted"] = e.accepted;
  out["equals"] = e.equals;
  out["scale"] = e.scale;
  out["damping"] = e.damping;
  out["departure"] = {{"state", e.departure.state},
                      {"what", e.departure.what},
                      {"yours", e.departure.yours},
                      {"course", e.departure.course}};
  nlohmann::json states = nlohmann::json::array();
  for (const StageState& s : fit.states)
    states.push_back({{"x", s.x.fits ? text(s.x.course, fit.recorded) : ""},
                      {"v", s.v.fits ? text(s.v.course, fit.recorded) : ""},
                      {"x_residual", s.x.residual},
                      {"v_residual", s.v.residual},
                      {"same_as", s.same_as},
                      {"spheres", s.spheres == SpheresAre::Same      ? "same stage"
                                  : s.spheres == SpheresAre::AtStart ? "at their start"
                                  : s.spheres == SpheresAre::Own     ? "own stage"
                                                                     : "no combination"}});
  out["states"] = states;
  nlohmann::json causes = nlohmann::json::array();
  for (const StageCause& c : e.causes)
    causes.push_back({{"id", c.id}, {"likely", c.likely}, {"why", c.why}});
  out["causes"] = causes;
  out["text"] = stageText(fit, e);
  return out.dump(1);
}

}  // namespace clothref::grader::stages
