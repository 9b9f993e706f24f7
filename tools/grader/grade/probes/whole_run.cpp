// The whole-run check: the student's full simulation (their forces, contacts and explicit Euler,
// with the course's main loop) of the course scene for a short horizon, written as a clothref
// trace and compared with clothref's trace by clothref diff. Information only: a correct
// symplectic explicit drifts from the reference trajectory more than many real bugs do.
#include <fstream>

#include "clothref/diff/diff.h"
#include "clothref/record/record.h"
#include "clothref/record/world_views.h"
#include "clothref/scene/make_world.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/format.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader {

std::vector<TestResult> probeWholeRun(const ProbeContext& context) {
  const std::string scene_name = context.edition == 2024 ? "course2024" : "course2022";
  TestResult t = makeTest("Cloth + Spheres + ExplicitEuler (whole run)",
                          "course scene " + scene_name + " for 200 steps (information only)", 0);
  t.informational = true;
  t.fraction = 1;
  const Scene* scene = findBuiltinScene(scene_name);
  if (!scene) {
    t.output = "Not run: clothref has no scene " + scene_name + ".";
    return {t};
  }
  TraceSettings settings;
  settings.method = Method::Explicit;
  settings.precision = Precision::Float;
  settings.dt = scene->dt;
  settings.steps = 200;
  settings.stride = 20;
  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kWholeRun;
  request.ints[key::kMethod] = {0};
  request.floats[key::kDt] = {float(settings.dt)};
  request.ints[key::kSteps] = {settings.steps};
  request.ints[key::kStride] = {settings.stride};
  util::ProbeFailure failure;
  // information only, never scored: one run
  const auto answer =
      util::runGroup(context, context.probe, group::kWholeRun, request, failure, nullptr, true);
  if (!answer) {
    t.output = "Your full simulation did not finish: " + failure.text;
    return {t};
  }
  const auto dir = context.work_dir / group::kWholeRun;
  const auto reference_path = dir / "reference.jsonl";
  const auto student_path = dir / "student.jsonl";
  {
    std::ofstream out(reference_path);
    writeTrace(*scene, settings, out);
  }
  {
    World<float> world = makeWorld<float>(*scene, Method::Explicit, settings.dt);
    const int cloth_n = world.cloth ? world.cloth->particles.size() : 0;
    const int sphere_n = world.spheres ? world.spheres->size() : 0;
    const int capacity = static_cast<int>(answer->scalarInt(key::kSphereCapacity, sphere_n));
    const auto& cx = answer->f(key::kClothPos);
    const auto& cv = answer->f(key::kClothVel);
    const auto& sx = answer->f(key::kSpherePos);
    const auto& sv = answer->f(key::kSphereVel);
    std::string text = traceHeader(*scene, settings).dump() + "\n";
    std::int64_t record = 0;
    for (std::int64_t s = 0; s <= settings.steps; ++s) {
      if (!isRecorded(s, settings.steps, settings.stride)) continue;
      const std::size_t c0 = std::size_t(record) * std::size_t(4 * cloth_n);
      const std::size_t s0 = std::size_t(record) * std::size_t(4 * capacity);
      if (c0 + std::size_t(4 * cloth_n) > cx.size() || s0 + std::size_t(4 * sphere_n) > sx.size())
        break;
      world.step = s;
      if (world.cloth) {
        world.cloth->particles.position =
            util::matrix({cx.begin() + long(c0), cx.begin() + long(c0 + 4 * cloth_n)}, cloth_n);
        world.cloth->particles.velocity =
            util::matrix({cv.begin() + long(c0), cv.begin() + long(c0 + 4 * cloth_n)}, cloth_n);
      }
      if (world.spheres) {
        world.spheres->particles.position =
            util::matrix({sx.begin() + long(s0), sx.begin() + long(s0 + 4 * sphere_n)}, sphere_n);
        world.spheres->particles.velocity =
            util::matrix({sv.begin() + long(s0), sv.begin() + long(s0 + 4 * sphere_n)}, sphere_n);
      }
      appendStepLine(text, world);
      ++record;
    }
    std::ofstream out(student_path);
    out << text;
  }
  DiffOptions options;
  options.global.mode = ToleranceMode::Combined;
  options.global.abs = 1e-5;
  options.global.rel = 1e-5;
  options.common_steps = true;
  try {
    const DiffReport report = diffTraces(reference_path.string(), student_path.string(), options);
    t.output =
        "Your cloth.cpp, sphere.cpp and integrator.cpp run the course's main loop "
        "(simulateOneStep, then ExplicitEuler::integrate) on " +
        scene_name + " for 200 steps of " + util::num(settings.dt) +
        " s; `clothref diff` against "
        "clothref (tolerance 1e-5 absolute or relative). This never changes your score: "
        "an accepted variant (e.g. symplectic explicit Euler) also differs here.\n\n```\n" +
        formatReport(report) + "```\n";
  } catch (const std::exception& error) {
    t.output = "The traces could not be compared: " + std::string(error.what());
  }
  return {t};
}

}  // namespace clothref::grader
