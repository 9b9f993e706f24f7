// The course's step with its lines switchable (integrate_step.h): its driver, the driver's lines
// and their rows, and the families in order. A new line of the driver (which bodies, which
// evaluations) is its switch in FrameSwitches, its use in linesStep and its row here; a family's
// row that changes the driver's lines too names this table's row (Row::frame).
#include "grader/grade/mistakes/integrate_step.h"

#include <cstring>

#include "grader/grade/cause_ids.h"

namespace clothref::grader::integrators {
namespace {

// The driver's lines a mistake changes; the defaults are the course's.
struct FrameSwitches {
  bool reevaluates = true;       // integrate()'s own simulateOneStep() calls (off: explicit)
  bool evaluates_again = false;  // one more simulateOneStep() before an explicit step
  bool per_body = false;         // integrate() on one body at a time, each with its calls
  bool first_body_only = false;  // integrate() on particles[0] (the cloth) only
};

// Every reading on the driver's lines or on lines every method reads (EveryMethod): those of one
// id in the order the prover tries them, the first-pass ones in the order the one-step check tries
// them. "{method}" is the stub's course method.
// clang-format off
const std::vector<Row<FrameSwitches>>& frameRows() {
  static const std::vector<Row<FrameSwitches>> table = {
    {cause::kOnlyFirstBody, kAll, true, "{method} on particles[0] (the cloth) only",
     {.first_body_only = true}},
    {cause::kBackupAlias, kI | kM | kR, true, "{method} with a backup that follows the live state",
     {}, {.backup_follows_live = true}},
    {cause::kNoReevaluation, kI | kM | kR, true,
     "explicit Euler (what simulateOneStep() computes unused)", {.reevaluates = false}},
    // From the live state after the stub's own simulateOneStep() (no backups, or "backups" that
    // follow the live state): a contact is resolved a second time.
    {cause::kNoReevaluation, kI | kM | kR, false,
     "explicit Euler from the state your own simulateOneStep() leaves (the step starts after "
     "that call, not from backups taken before it)",
     {.reevaluates = false, .evaluates_again = true}},
    {cause::kPerBodyLoop, kI | kM | kR, true,
     "{method} run on each body in turn, each with its own simulateOneStep() calls",
     {.per_body = true}},
    {cause::kVelocityNotIntegrated, kI | kM | kR, false, "{method} without the velocity update",
     {}, {.updates_velocity = false}},
    {cause::kPositionNotIntegrated, kI | kM | kR, false, "{method} without the position update",
     {}, {.updates_position = false}},
    // The same step as a backup that follows the live state: the corrector adds onto the
    // prediction. Which one the student wrote is the source's to say (backupCause).
    {cause::kCorrectorFromPrediction, kI | kM, false,
     "{method} whose corrector steps from the predicted state", {}, {.backup_follows_live = true}},
    {cause::kHalfStepCorrector, kI | kM | kR, false, "{method} whose corrector takes h/2", {}, {},
     std::nullopt, Overlay{.result_step = 0.5}},
  };
  return table;
}
// clang-format on

}  // namespace

const Family& everyMethodFamily() {
  static const Family rows = familyOf(frameRows(), nullptr);
  return rows;
}

int frameRow(const char* id) {
  for (std::size_t r = 0; id && r < frameRows().size(); ++r)
    if (std::strcmp(frameRows()[r].id, id) == 0) return int(r);
  return -1;
}

const Family& family(FamilyId id) {
  static const std::array<const Family*, kFamilies> all = {
      &everyMethodFamily(), &explicitEulerFamily(), &predictorCorrectorFamily(),
      &rungeKutta4Family()};
  return *all[std::size_t(id)];
}

void holdStill(const std::vector<Pins>& pinned, const std::vector<int>& spheres, System& s,
               const Mat4X<float>& cloth_x0) {
  for (const Pins& pins : pinned)
    if (pins.cloth_size == s.cloth.particles.size())
      for (int j : pins.particles)
        if (j >= 0 && j < s.cloth.particles.size()) {
          s.cloth.particles.velocity.col(j).setZero();
          if (pins.positions && j < cloth_x0.cols())
            s.cloth.particles.position.col(j) = cloth_x0.col(j);
        }
  for (int j : spheres)
    if (j >= 0 && j < s.spheres.particles.size()) s.spheres.particles.velocity.col(j).setZero();
}

Step linesStep(Method method, const EveryMethod& every, const FamilyRows& rows, const Overlay& o) {
  FrameSwitches frame;
  for (int r : rows[kEveryMethod])
    if (r >= 0 && std::size_t(r) < frameRows().size())
      switches::merge(frame, frameRows()[std::size_t(r)].lines);
  // The method's integrate() with its family's switches on, set once for every call.
  const bool explicit_euler = method == Method::Explicit || !frame.reevaluates;
  FamilyId id = kRungeKutta4;
  if (explicit_euler)
    id = kExplicitEuler;
  else if (method == Method::Implicit || method == Method::Midpoint)
    id = kPredictorCorrector;
  const Integrate integrate = family(id).integrate(rows[id]);
  return [method, every, frame, o, explicit_euler, integrate](System& s) {
    simulate(s);
    const Mat4X<float> cloth_x0 = s.cloth.particles.position;
    const float dt = o.step == 1 ? s.dt : float(double(s.dt) * o.step);
    const Sizes z{dt, o.result_dt ? float(double(*o.result_dt) * o.step) : dt,
                  float(o.result_step)};
    const std::function<void()> at_stage = [&] {
      if (o.pins_at_stages) holdStill(o.pinned, o.pinned_spheres, s, cloth_x0);
    };
    std::vector<Particles<float>*> bodies{&s.cloth.particles};
    if (!frame.first_body_only) bodies.push_back(&s.spheres.particles);
    if (explicit_euler) {
      if (frame.evaluates_again) simulate(s);
      integrate({s, bodies, method, every, z, o, at_stage});
    } else {
      // A per-body loop: each body alone, later bodies after the earlier ones have moved; the
      // first body uses the derivatives evaluated before integrate(), each later one those of
      // the previous body's last simulateOneStep().
      std::vector<std::vector<Particles<float>*>> groups;
      if (frame.per_body)
        for (auto* p : bodies) groups.push_back({p});
      else
        groups.push_back(bodies);
      for (const auto& group : groups) integrate({s, group, method, every, z, o, at_stage});
    }
    // What the fitted overlay lays over the step.
    Particles<float>* both[] = {&s.cloth.particles, &s.spheres.particles};
    for (std::size_t b = 0; b < 2; ++b)
      if (o.velocity_factor[b] != 1) both[b]->velocity *= float(o.velocity_factor[b]);
    holdStill(o.pinned, o.pinned_spheres, s, cloth_x0);
    if (o.dt_after_factor) s.dt = float(double(s.dt) * *o.dt_after_factor);
    if (o.dt_after) s.dt = *o.dt_after;
  };
}

}  // namespace clothref::grader::integrators
