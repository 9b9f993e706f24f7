// The integrator mistakes as rows of one table on the course's step (integrate_mistakes.h). A
// new mistake on lines the step already switches is its row in rows() and its catalogue entry;
// the prover tries every row of the stub's method.
#include "grader/grade/mistakes/integrate_mistakes.h"

#include "grader/grade/cause_ids.h"

namespace clothref::grader::integrators {
namespace {

// The methods a row applies to (bits of integratorIndex: explicit 1, implicit 2, midpoint 4,
// RK4 8).
constexpr unsigned kE = 1, kI = 2, kM = 4, kR = 8, kAll = 15;

// A reading of a mistake: the catalogue's id, the stubs it applies to, its words ("{method}":
// the course's method of the stub), the lines it changes, the method it runs (Heun: a corrector
// on implicit Euler's prediction, whatever the stub) and a constant it sets.
struct Row {
  const char* id;
  unsigned methods;
  bool first_pass;  // tried on the first step before any fit
  const char* text;
  Lines lines;
  std::optional<Method> runs{};
  Overlay overlay{};
};

// Every reading: those of one id in the order the prover tries them, the first-pass ones in the
// order the one-step check tries them. "{method}" is the stub's course method.
// clang-format off
const std::vector<Row>& rows() {
  static const std::vector<Row> table = {
    {cause::kOnlyFirstBody, kAll, true, "{method} on particles[0] (the cloth) only",
     {.first_body_only = true}},
    {cause::kOnlyFirstBody, kE, true, "symplectic Euler on particles[0] (the cloth) only",
     {.first_body_only = true, .velocity_first = true}},
    {cause::kPositionUsesAcceleration, kE, true, "explicit Euler with x += v dt + a dt²/2",
     {.position_half_acceleration = true}},
    {cause::kVelocityNotIntegrated, kE, true, "explicit Euler without the velocity update",
     {.updates_velocity = false}},
    {cause::kPositionNotIntegrated, kE, true, "explicit Euler without the position update",
     {.updates_position = false}},
    {cause::kBackupAlias, kI | kM | kR, true, "{method} with a backup that follows the live state",
     {.backup_follows_live = true}},
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
    {cause::kMidpointFullStep, kM, true, "the course's implicit Euler (a full-step prediction)",
     {.predictor_full_step = true}},
    {cause::kNoReevaluation, kM, true,
     "the course's midpoint with simulateOneStep() before the half step",
     {.evaluates_before_predictor = true}},
    // simulateOneStep() at the unchanged start state; a contact in it is applied a second time,
    // so this is not explicit Euler's result.
    {cause::kNoReevaluation, kM, true, "the course's midpoint whose half step adds nothing",
     {.predictor_adds_nothing = true}},
    {cause::kIntegerDivisionRk4, kR, true, "the course's RK4 with 1 / 6 = 0 in the update",
     {.result_adds_nothing = true}},
    {cause::kIntegerDivisionRk4, kR, false,
     "the course's RK4 with 1 / 6 = 0 in an update added (+=) to the state the last stage left",
     {.result_adds_nothing = true, .result_on_last_stage = true}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose position update adds the velocity k's",
     {.result_position_from_kv = true}},
    {cause::kRk4MixedIncrements, kR, true, "the course's RK4 whose velocity update takes k4 of x",
     {.result_velocity_k4_from_kx = true}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 2 position adds a velocity k", {.stage_position_from_kv = 0}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 3 position adds a velocity k", {.stage_position_from_kv = 1}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose stage 4 position adds a velocity k", {.stage_position_from_kv = 2}},
    {cause::kRk4MixedIncrements, kR, true,
     "the course's RK4 whose position update reads k4 after the velocity update (v_new·h)",
     {.result_k4x_after_velocity = true}},
    {cause::kRk4StageNotFromBackup, kR, true,
     "the course's RK4 with each stage built on the previous stage instead of the backup",
     {.stage_from_current = true}},
    {cause::kRk4StageFromWrongIncrement, kR, true,
     "the course's RK4 with each stage position from that stage's new velocity",
     {.stage_position_from_new_velocity = true}},
    // Each increment read after the velocity was overwritten with v0 + c·h·a_k of its own stage:
    // the stage positions x0 + c·h·(v0 + c'·h·a_k), the update's k's (v0 + c'·h·a_k)·h.
    {cause::kRk4StageFromWrongIncrement, kR, false,
     "the course's RK4 with each position increment read after the stage's velocity was "
     "overwritten with v0 + c·h·a of that stage",
     {.stage_increment_after_overwrite = true}},
    {cause::kRk4StagesDiscarded, kR, true, "the course's RK4 whose update uses k1 only",
     {.result_first_stage_only = true}},
    {cause::kRk4FourthStageHalfStep, kR, true,
     "the course's RK4 whose fourth stage is taken from a half step (x0 + k3/2, v0 + k3v/2)",
     {.stage = {0.5f, 0.5f, 0.5f}}},
    {cause::kVelocityNotIntegrated, kI | kM | kR, false, "{method} without the velocity update",
     {.updates_velocity = false}},
    {cause::kPositionNotIntegrated, kI | kM | kR, false, "{method} without the position update",
     {.updates_position = false}},
    // The same step as a backup that follows the live state: the corrector adds onto the
    // prediction. Which one the student wrote is the source's to say (backupCause).
    {cause::kCorrectorFromPrediction, kI | kM, false,
     "{method} whose corrector steps from the predicted state", {.backup_follows_live = true}},
    {cause::kIntegerDivisionHalf, kM, false,
     "the course's midpoint with 1 / 2 = 0 (the half step adds nothing)",
     {.predictor_adds_nothing = true}},
    {cause::kHeunMethod, kAll, false, "Heun's method (the trapezoidal corrector)",
     {.corrector_trapezoidal = true}, Method::Implicit},
    {cause::kHalfStepCorrector, kI | kM | kR, false, "{method} whose corrector takes h/2", {},
     std::nullopt, Overlay{.result_step = 0.5}},
    {cause::kCorrectorStartVelocity, kI | kM, false,
     "{method} whose corrector moves the positions with the start velocity v0",
     {.corrector_start_velocity = true}},
    // Variants the rubric may accept (stages::methodTables' `accepted`), which a fitted overlay
    // (particles held still) may follow.
    {"explicit-as-symplectic", kE, false, "symplectic Euler (v first, then x with the new v)",
     {.velocity_first = true}},
    {"implicit-corrector-v-new", kI, false, "implicit Euler whose corrector uses the new v",
     {.corrector_new_velocity = true}},
    {"symplectic-predictor", kI, false,
     "implicit Euler with a symplectic predictor (v first, then x)", {.predictor_symplectic = true}},
    {"symplectic-predictor", kM, false, "midpoint with a symplectic predictor (v first, then x)",
     {.predictor_symplectic = true}},
  };
  return table;
}
// clang-format on

unsigned methodBit(Method method) {
  switch (method) {
    case Method::Explicit:
      return kE;
    case Method::Implicit:
      return kI;
    case Method::Midpoint:
      return kM;
    case Method::Rk4:
      return kR;
    default:
      return 0;
  }
}

std::string wordsOf(const Row& row, Method method) {
  std::string text = row.text;
  const std::string name = method == Method::Explicit   ? "explicit Euler"
                           : method == Method::Implicit ? "implicit Euler"
                           : method == Method::Midpoint ? "midpoint"
                                                        : "RK4";
  const auto at = text.find("{method}");
  if (at != std::string::npos) text.replace(at, 8, "the course's " + name);
  return text;
}

}  // namespace

Step courseStep(const StepModel& model) {
  Lines lines;
  Method method = model.method;
  Overlay o = model.overlay;
  for (int r : model.rows) {
    if (r < 0 || std::size_t(r) >= rows().size()) continue;
    const Row& row = rows()[std::size_t(r)];
    merge(lines, row.lines);
    if (row.runs) method = *row.runs;
    if (row.overlay.result_step != 1) o.result_step = row.overlay.result_step;
  }
  return linesStep(method, lines, o);
}

std::vector<Reading> readingsOf(std::string_view id, Method method) {
  std::vector<Reading> out;
  for (std::size_t r = 0; r < rows().size(); ++r) {
    const Row& row = rows()[r];
    if (row.id == id && (row.methods & methodBit(method)))
      out.push_back({row.id, wordsOf(row, method), int(r), row.first_pass});
  }
  return out;
}

std::vector<Reading> readingsOf(Method method) {
  std::vector<Reading> out;
  for (std::size_t r = 0; r < rows().size(); ++r) {
    const Row& row = rows()[r];
    if (row.methods & methodBit(method))
      out.push_back({row.id, wordsOf(row, method), int(r), row.first_pass});
  }
  return out;
}

std::vector<std::string> readingIds() {
  std::vector<std::string> ids;
  for (const Row& row : rows())
    if (ids.empty() || ids.back() != row.id) ids.push_back(row.id);
  return ids;
}

Step readingStep(std::string_view id, Method method) {
  const std::vector<Reading> readings = readingsOf(id, method);
  StepModel model{method};
  if (!readings.empty()) model.rows = {readings.front().row};
  return courseStep(model);
}

std::optional<StepModel> combined(const StepModel& a, const StepModel& b) {
  if (a.method != b.method) return std::nullopt;
  StepModel both = a;
  Lines lines;
  std::optional<Method> runs;
  for (const StepModel* m : {&a, &b})
    for (int r : m->rows) {
      if (r < 0 || std::size_t(r) >= rows().size()) return std::nullopt;
      const Row& row = rows()[std::size_t(r)];
      if (!merge(lines, row.lines)) return std::nullopt;
      if (row.runs && runs && *row.runs != *runs) return std::nullopt;
      if (row.runs) runs = row.runs;
      if (m == &b) both.rows.push_back(r);
    }
  const Overlay& o = b.overlay;
  Overlay& t = both.overlay;
  if (o.step != 1) t.step = o.step;
  if (o.result_step != 1) t.result_step = o.result_step;
  if (o.result_dt) t.result_dt = o.result_dt;
  if (!o.weights_x.empty()) t.weights_x = o.weights_x;
  if (!o.weights_v.empty()) t.weights_v = o.weights_v;
  for (std::size_t k = 0; k < 2; ++k)
    if (o.velocity_factor[k] != 1) t.velocity_factor[k] = o.velocity_factor[k];
  if (!o.pinned.empty()) t.pinned = o.pinned;
  if (!o.pinned_spheres.empty()) t.pinned_spheres = o.pinned_spheres;
  t.pins_at_stages = t.pins_at_stages || o.pins_at_stages;
  if (o.dt_after_factor) t.dt_after_factor = o.dt_after_factor;
  if (o.dt_after) t.dt_after = o.dt_after;
  return both;
}

std::vector<std::pair<std::string, Step>> acceptedVariants(const Rubric& rubric, Method method) {
  std::vector<std::pair<std::string, Step>> accepted;
  if (method == Method::Explicit && rubric.accepts("explicit-as-symplectic"))
    accepted.push_back({"explicit written as symplectic Euler (v first, then x with the new v)",
                        readingStep("explicit-as-symplectic", method)});
  if (method == Method::Implicit && rubric.accepts("implicit-corrector-v-new"))
    accepted.push_back({"the corrector's position uses the new velocity",
                        readingStep("implicit-corrector-v-new", method)});
  if ((method == Method::Implicit || method == Method::Midpoint) &&
      rubric.accepts("symplectic-predictor"))
    accepted.push_back(
        {"the predictor written as symplectic Euler (v first, then x with the new v)",
         readingStep("symplectic-predictor", method)});
  return accepted;
}

}  // namespace clothref::grader::integrators
