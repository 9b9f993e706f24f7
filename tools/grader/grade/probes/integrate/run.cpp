// One run of the integrator probe (run.h).
#include "grader/grade/probes/integrate/run.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "grader/grade/explain/stages/stages.h"

namespace clothref::grader::integrators {

void completeOneStep(OneStep& step, Method method) {
  step.expected = stepped(step.state, clothrefStep(method));
  step.start = step.state;
  simulate(step.start);  // contacts move bodies before integrate() does
  step.distance = distance(step.actual, step.expected);
}

bool runIntegrator(const ProbeContext& context, int index, bool course_size, IntegratorRun& run,
                   util::ProbeFailure& failure, ChildRun& child, bool log) {
  run.index = index;
  run.method = integratorMethod(index);
  run.stub = stubName(integratorStub(index));
  run.rel = context.rubric.tolerances.integrate_rel;
  const std::uint64_t seed = context.seed + 7 * std::uint64_t(index);
  run.random = course_size ? courseSystem(seed, context.edition) : randomSystem(seed);
  run.spring_particles = course_size ? run.random.cloth.particles.size() : 2;
  switch (run.method) {
    case Method::Explicit:
    case Method::Implicit:
      run.dts = {0.002, 0.001, 0.0005, 0.00025};
      break;
    case Method::Midpoint:
      run.dts = {0.01, 0.005, 0.0025, 0.00125};
      break;
    default:
      run.dts = {0.1, 0.05, 0.025};
      run.end_time = 2.0;
      break;
  }
  run.limit = stabilityLimit(run.method);
  run.stable_dt = 0.5 * run.limit;
  const std::int64_t stable_steps = static_cast<std::int64_t>(20.0 / run.stable_dt);

  // Case 0: one step on the random state. Cases 1..: the convergence ladder. Last: stability.
  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kIntegrate;
  request.ints[key::kMethod] = {index};
  addSystem(request, 0, run.random, 1, 0);
  for (std::size_t k = 0; k < run.dts.size(); ++k) {
    const std::int64_t steps = std::llround(run.end_time / run.dts[k]);
    const std::int64_t stride = std::max<std::int64_t>(1, steps / 50);
    run.strides.push_back(stride);
    addSystem(request, int(k) + 1, springSystem(float(run.dts[k]), run.spring_particles), steps,
              stride);
  }
  run.stable_case = int(run.dts.size()) + 1;
  const std::int64_t stable_stride = std::max<std::int64_t>(1, stable_steps / 100);
  addSystem(request, run.stable_case, springSystem(float(run.stable_dt), run.spring_particles),
            stable_steps, stable_stride);
  // Last: the stage record, one step of a contact-free random state (stages.h).
  run.stage_case = run.stable_case + 1;
  addSystem(request, run.stage_case, stageSystem(seed, course_size, context.edition), 1, 0);
  request.ints[key::perCase(key::kRecordStages, run.stage_case)] = {1};
  // Last: one step on the course's cloth; in 2024 with its corners unpinned, as the program's keys
  // 1-4 leave them (2022's program has no such keys: its corners are always fixed, and a step that
  // pins them again changes nothing there).
  OneStep course_cloth;
  course_cloth.state = courseSystem(seed + 2000, context.edition, context.edition == 2024);
  course_cloth.case_index = run.stage_case + 1;
  addSystem(request, course_cloth.case_index, course_cloth.state, 1, 0);
  request.ints[key::kCases] = {course_cloth.case_index + 1};

  ProbeContext quiet = context;
  if (!log) quiet.limits.log = nullptr;  // a crash that the course-size retry may still grade
  const auto answer = util::runGroup(quiet, context.probe, integratorFolder(index, course_size),
                                     request, failure, &child);
  if (!answer) return false;
  run.answer = *answer;
  run.actual = answerSystem(run.answer, 0, run.random);
  run.expected = stepped(run.random, clothrefStep(run.method));
  run.start = run.random;
  simulate(run.start);  // contacts move bodies before integrate() does
  run.distance = distance(run.actual, run.expected);
  course_cloth.actual = answerSystem(run.answer, course_cloth.case_index, course_cloth.state);
  completeOneStep(course_cloth, run.method);
  run.course_cloth = std::move(course_cloth);
  return true;
}

bool onlyDivergedRuns(const probe::ProbeMessage& answer) {
  const std::string trajectory = std::string(key::kTrajectory) + ".";
  const auto caseOf = [](const std::string& name) {
    const std::size_t dot = name.rfind('.');
    return dot == std::string::npos ? std::string() : name.substr(dot + 1);
  };
  std::set<std::string> diverged;  // the cases, as perCase's suffix
  for (const auto& [name, values] : answer.floats) {
    if (name.rfind(trajectory, 0) != 0) continue;
    float largest = 0;
    for (float v : values) {
      if (!std::isfinite(v)) break;
      largest = std::max(largest, std::abs(v));
    }
    if (largest > 1e6f) diverged.insert(caseOf(name));
  }
  bool any = false;
  for (const auto& [name, values] : answer.floats)
    if (std::any_of(values.begin(), values.end(), [](float v) { return !std::isfinite(v); })) {
      if (!diverged.count(caseOf(name))) return false;
      any = true;
    }
  return any;
}

}  // namespace clothref::grader::integrators
