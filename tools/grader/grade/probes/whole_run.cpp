// The whole-run check: the student's full simulation (their forces, contacts and explicit Euler,
// with the course's main loop) of the course scene for a short horizon, compared with clothref's
// run of the same scene by clothref's differ. Information only: a correct symplectic explicit
// drifts from the reference trajectory more than many real bugs do.
//
// In memory: the student's states come back in the probe's answer and are seen through
// BodyViews (trace/body_view.h), turned into trace step lines beside the reference's trace of the
// scene from findBuiltinScene, and the two texts are compared as streams; nothing is written to
// disk and no World is built to hold the student's arrays. The two texts stay on the test for the
// HTML report's pictures.
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

#include "clothref/diff/diff.h"
#include "clothref/record/record.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/body_view.h"
#include "clothref/trace/format.h"
#include "clothref/trace/step_line.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {
namespace {

constexpr std::int64_t kSteps = 200, kStride = 20;
constexpr double kTolerance = 1e-5;  // absolute or relative (clothref diff's combined mode)

// "the cloth's particle 312, velocity y" of a compared value.
std::string valueName(const ValueDiff& value) {
  if (value.field == Field::Time) return "the time t";
  static const char* const kAxes[] = {"x", "y", "z"};
  return "the " + value.body + "'s " + (value.body == "spheres" ? "sphere " : "particle ") +
         std::to_string(value.particle) + ", " + std::string(fieldName(value.field)) + " " +
         (value.component >= 0 && value.component < 3 ? kAxes[value.component] : "?");
}

std::string unitOf(const ValueDiff& value) {
  return value.field == Field::Position ? "m" : value.field == Field::Velocity ? "m/s" : "s";
}

// The comparison as a student reads it: steps and times in the course's units, the reference's
// value as the expected one beside yours (compare_text.h), the tolerance; no file names, no units
// in the last place.
std::string describe(const DiffReport& report, double dt) {
  const auto at = [&](std::int64_t step) {
    return "step " + std::to_string(step) + " (t = " + util::num(double(step) * dt) + " s)";
  };
  // clothref diff's combined rule: within 1e-5 absolute or 1e-5 relative to the larger value
  const auto values = [&](const ValueDiff& value) {
    const double larger = std::max(std::abs(value.a), std::abs(value.b));
    const util::Tolerance tolerance{std::max(kTolerance, kTolerance * larger), 0};
    return util::compareNumbers(valueName(value) + " at " + at(value.step), value.a, value.b,
                                tolerance, unitOf(value));
  };
  if (report.verdict == clothref::Verdict::Identical)
    return "**The runs are identical**: all " + std::to_string(report.steps_compared) +
           " recorded states (every " + std::to_string(kStride) +
           "th step) equal the reference's, bit for bit.\n";
  if (report.verdict == clothref::Verdict::WithinTolerance)
    return "**The runs are identical within the tolerance** (" + util::num(kTolerance) +
           ", absolute or relative): " + std::to_string(report.values_compared) +
           " values compared" +
           (report.worst ? "; the largest difference, the reference's value as the expected "
                           "one:\n\n" +
                               values(*report.worst)
                         : std::string(".\n"));
  std::string out = "**The runs differ**";
  if (report.first_beyond)
    out += " from " + at(report.first_beyond->step) +
           " (the reference's value as the expected one):\n\n" + values(*report.first_beyond) +
           "\n";
  else
    out += ". ";
  out += "In all, " + std::to_string(report.values_beyond) + " of " +
         std::to_string(report.values_compared) + " values compared are beyond the tolerance (" +
         util::num(kTolerance) + ", absolute or relative)";
  if (report.worst && report.first_beyond &&
      !(report.worst->step == report.first_beyond->step &&
        report.worst->particle == report.first_beyond->particle &&
        report.worst->field == report.first_beyond->field))
    out += "; the largest difference:\n\n" + values(*report.worst);
  else
    out += ".\n";
  for (const HeaderDiff& header : report.header_diffs)
    if (header.significant) {
      out += "\nThe runs' settings differ (" + header.pointer + ").\n";
      break;
    }
  return out;
}

// A stub the whole run calls (at its start or every step) that ran into its time limit in its
// own scored probe, or "": the whole run would only spend a limit of its own too.
std::string stubThatTimedOut(const ProbeContext& context) {
  if (!context.limits.log) return "";
  std::map<std::string, std::string> stub_of;
  for (const auto& [folder, stub] : probeFolders()) stub_of[folder] = stub;
  const RunLog& log = *context.limits.log;
  std::lock_guard<std::mutex> lock(context.limits.log->mutex);
  for (std::size_t k = 0; k < log.verdicts.size() && k < log.folders.size(); ++k) {
    const auto found = stub_of.find(log.folders[k]);
    if (log.verdicts[k] != Verdict::TimedOut || found == stub_of.end() || found->second.empty())
      continue;
    const bool other_integrator = found->first.rfind(group::kIntegrate, 0) == 0 &&
                                  found->second != stubName(Stub::ExplicitEuler);
    if (!other_integrator) return found->second;
  }
  return "";
}

}  // namespace

std::vector<TestResult> probeWholeRun(const ProbeContext& context) {
  const std::string& scene_name = context.course.scene;
  TestResult t = makeTest("Cloth + Spheres + ExplicitEuler (whole run)",
                          "course scene " + scene_name + " for 200 steps (information only)", 0);
  t.informational = true;
  t.fraction = 0;
  const Scene* scene = findBuiltinScene(scene_name);
  if (!scene) {
    t.output = "Not run: clothref has no scene " + scene_name + ".";
    return {t};
  }
  TraceSettings settings;
  settings.method = Method::Explicit;
  settings.precision = Precision::Float;
  settings.dt = scene->dt;
  settings.steps = kSteps;
  settings.stride = kStride;
  // the time of a step as the course's float deltaTime gives it (the reference's trace writes so)
  const double dt = double(static_cast<float>(settings.dt));
  const std::string what =
      "Your cloth.cpp, sphere.cpp and integrator.cpp ran the course's main loop "
      "(simulateOneStep(), then ExplicitEuler::integrate) on the course scene " +
      scene_name + " for " + std::to_string(kSteps) + " steps of " + util::num(settings.dt) +
      " s (" + util::num(double(kSteps) * dt) + " s), and so did the reference; every " +
      std::to_string(kStride) +
      "th state is compared. This never changes your score: an "
      "accepted variant (e.g. symplectic explicit Euler) also differs here.\n\n";
  if (const std::string stopped = stubThatTimedOut(context); !stopped.empty()) {
    t.output = what + "Not run: your " + stopped +
               " did not finish within the time limit in its own probe (above), and the whole run "
               "calls it.";
    return {t};
  }
  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kWholeRun;
  request.ints[key::kMethod] = {util::methodRow(settings.method)};
  request.floats[key::kDt] = {float(settings.dt)};
  request.ints[key::kSteps] = {settings.steps};
  request.ints[key::kStride] = {settings.stride};
  util::ProbeFailure failure;
  // information only, never scored: one run
  const auto answer =
      util::runGroup(context, context.probe, group::kWholeRun, request, failure, nullptr, true);
  if (!answer) {
    t.output = what + "Your run did not finish: " + failure.text;
    return {t};
  }
  // The student's states, body by body in the header's order, seen through BodyViews.
  const nlohmann::ordered_json header = traceHeader(*scene, settings);
  std::int64_t cloth_n = 0, sphere_n = 0;
  for (const auto& body : header["bodies"])
    (body["name"] == "cloth" ? cloth_n : sphere_n) = body["particles"].get<std::int64_t>();
  const std::int64_t capacity = answer->scalarInt(key::kSphereCapacity, sphere_n);
  const auto& cx = answer->f(key::kClothPos);
  const auto& cv = answer->f(key::kClothVel);
  const auto& sx = answer->f(key::kSpherePos);
  const auto& sv = answer->f(key::kSphereVel);
  auto traces = std::make_shared<TestResult::Traces>();
  traces->student = header.dump() + "\n";
  std::size_t record = 0;
  for (std::int64_t s = 0; s <= settings.steps; ++s) {
    if (!isRecorded(s, settings.steps, settings.stride)) continue;
    const std::size_t c0 = record * std::size_t(4 * cloth_n);
    const std::size_t s0 = record * std::size_t(4 * capacity);
    if (c0 + std::size_t(4 * cloth_n) > cx.size() || c0 + std::size_t(4 * cloth_n) > cv.size() ||
        s0 + std::size_t(4 * sphere_n) > sx.size() || s0 + std::size_t(4 * sphere_n) > sv.size())
      break;  // an answer cut short: the comparison says where the run ends
    std::vector<BodyView<float>> bodies;
    for (const auto& body : header["bodies"])
      if (body["name"] == "cloth")
        bodies.push_back({"cloth", cx.data() + c0, cv.data() + c0, int(cloth_n)});
      else
        bodies.push_back({"spheres", sx.data() + s0, sv.data() + s0, int(sphere_n)});
    appendStepLine(traces->student, s, double(s) * dt,
                   std::span<const BodyView<float>>(bodies.data(), bodies.size()));
    ++record;
  }
  {
    std::ostringstream reference;
    writeTrace(*scene, settings, reference);
    traces->reference = reference.str();
  }
  DiffOptions options;
  options.global.mode = ToleranceMode::Combined;
  options.global.abs = kTolerance;
  options.global.rel = kTolerance;
  options.common_steps = true;
  try {
    std::istringstream reference(traces->reference), student(traces->student);
    const DiffReport report = diffTraces(reference, "the reference", student, "your run", options);
    t.fraction = report.verdict == clothref::Verdict::Differ ? 0 : 1;
    t.output = what + describe(report, dt);
  } catch (const std::exception& error) {
    t.output = what + "Your run could not be compared with the reference's: " +
               codeSpan(safeName(error.what())) + ".";
  }
  t.traces = traces;
  return {t};
}

// The probe's row of the probe table (probes.h): no stub, information only.
std::vector<ProbeGroup> probeRowsWholeRun() {
  return {{probe::group::kWholeRun, "", {}, probeWholeRun, {probe::group::kWholeRun}}};
}

}  // namespace clothref::grader
