// The course's step with its lines switchable (the model of every integrator mistake,
// integrate_mistakes.h), split by method family: the course's main loop step is written once,
// its driver (simulateOneStep(), which bodies, then the method's integrate(), then the Overlay a
// fitted model lays over it) with its own lines (a struct private to it) and their rows in
// integrate_step.cpp, and each method's integrate() in its family's file: integrate_euler.cpp
// (explicit Euler), integrate_predictor.cpp (the predictor-corrector: implicit Euler and midpoint)
// and integrate_rk4.cpp. A family file holds its switches (a struct private to it, each default the
// course's), its part of the step and its rows (the readings of mistakes, keyed by the
// catalogue's cause::k…); merging two models reads every switch (switches.h), so a new line of a
// method, or of the driver, is its switch, its use and its row in that one file.
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <type_traits>
#include <vector>

#include "grader/grade/mistakes/switches.h"
#include "grader/grade/mistakes/system.h"

namespace clothref::grader::integrators {

// Cloth particles a step holds still, on cloths of one size (code that pins hard-coded indices
// only on the course's 25 x 25 cloth leaves the small probe cloth alone).
struct Pins {
  int cloth_size = 0;  // particles of the cloths they apply to
  std::vector<int> particles;
  bool positions = false;  // put back where they were, not only stopped
};

// `pinned` (those of s's cloth size) and `spheres` held still in `s` after a step that began at
// cloth positions `cloth_x0` (after the first simulateOneStep()).
void holdStill(const std::vector<Pins>& pinned, const std::vector<int>& spheres, System& s,
               const Mat4X<float>& cloth_x0);

// What a model fits from the student's numbers, laid over the step's lines; the defaults change
// nothing.
struct Overlay {
  double step = 1;         // every h of the call is step x deltaTime (deltaTime scaled before it)
  double result_step = 1;  // the result's (corrector's) terms at result_step x h
  // The result's terms at this deltaTime, whatever the call's (a constant the stub restored
  // deltaTime to before its corrector, e.g. `deltaTime = 0.0001f;`).
  std::optional<float> result_dt{};
  // RK4's result weights on k1..k4 of x (positions) and of v (velocities), replacing
  // 1/6, 1/3, 1/3, 1/6; empty: the course's.
  std::vector<double> weights_x{}, weights_v{};
  std::array<double, 2> velocity_factor{1, 1};  // each body's velocity times this after the step
  std::vector<Pins> pinned{};                   // cloth particles held still after the step
  std::vector<int> pinned_spheres{};            // spheres whose velocity is zeroed after the step
  // ... and after each stage state is written, before its simulateOneStep() (a helper called in
  // the stage loop too)
  bool pins_at_stages = false;
  std::optional<double> dt_after_factor{};  // deltaTime x this after the call
  std::optional<float> dt_after{};          // or this constant
};

// The lines each method's integrate() reads that any family's rows may set; the defaults are
// the course's. The driver's own lines (which bodies, which evaluations) are integrate_step.cpp's.
struct EveryMethod {
  bool backup_follows_live = false;  // x0, v0 read the live state (a pointer or Eigen::Ref "copy")
  bool updates_position = true, updates_velocity = true;  // the result's x and v
};

// The methods a row applies to (bits of integratorIndex: explicit 1, implicit 2, midpoint 4,
// RK4 8).
constexpr unsigned kE = 1, kI = 2, kM = 4, kR = 8, kAll = 15;

// A reading of a mistake (or of a variant the rubric accepts), a row of a family's table: the
// catalogue's id, the stubs it applies to, whether it is tried on the first step before any fit,
// its words ("{method}": the course's method of the stub), the family's switches it sets, the
// lines of every method it sets, the method it runs (Heun: a corrector on implicit Euler's
// prediction, whatever the stub) and a constant it sets (the overlay's result_step).
template <typename Switches>
struct Row {
  const char* id;
  unsigned methods;
  bool first_pass;
  const char* text;
  Switches lines{};
  EveryMethod every{};
  std::optional<Method> runs{};
  Overlay overlay{};
  // A cause whose first row of the driver's lines (integrate_step.cpp) this reading sets too:
  // one that changes the frame and a method's lines (symplectic Euler on the cloth only).
  const char* frame = nullptr;
};

// The step sizes of one call: h of every term, the result's h and the result's factor.
struct Sizes {
  float dt, result_dt, result_scale;
};

// One integrate() call as the driver hands it to a method's family: the bodies it advances.
struct Call {
  System& s;
  const std::vector<Particles<float>*>& bodies;
  Method method;  // the method run (midpoint: the prediction at h/2)
  const EveryMethod& every;
  Sizes z;
  const Overlay& o;
  const std::function<void()>& at_stage;  // after each stage state is written
};

// A method's integrate() with a model's switches on.
using Integrate = std::function<void(const Call&)>;

// A family as the driver and the readings see it: its rows without their switches, whether the
// switches of some of its rows go together, and its integrate() with them on.
struct Family {
  struct Head {
    const char* id;
    unsigned methods;
    bool first_pass;
    const char* text;
    EveryMethod every;
    std::optional<Method> runs;
    double result_step;
    const char* frame;
  };
  std::vector<Head> rows;
  std::function<bool(const std::vector<int>& rows)> merges;  // false: a switch set two ways
  std::function<Integrate(const std::vector<int>& rows)> integrate;
};

// A family from its table and its integrate(): the rows' switches merged (switches::merge) for
// a model of several rows. The driver's family has no integrate(): linesStep reads its lines.
template <typename Switches>
Family familyOf(const std::vector<Row<Switches>>& table,
                std::type_identity_t<void (*)(const Call&, const Switches&)> integrate) {
  Family family;
  for (const Row<Switches>& row : table)
    family.rows.push_back({row.id, row.methods, row.first_pass, row.text, row.every, row.runs,
                           row.overlay.result_step, row.frame});
  const auto merged = [&table](const std::vector<int>& rows, Switches& on) {
    bool together = true;
    for (int r : rows) together = switches::merge(on, table[std::size_t(r)].lines) && together;
    return together;
  };
  family.merges = [merged](const std::vector<int>& rows) {
    Switches on;
    return merged(rows, on);
  };
  if (integrate)
    family.integrate = [merged, integrate](const std::vector<int>& rows) -> Integrate {
      Switches on;
      merged(rows, on);
      return [on, integrate](const Call& call) { integrate(call, on); };
    };
  return family;
}

// The families in the order of their rows (the readings' order: readingsOf): the driver's lines
// (with the rows that set only EveryMethod), explicit Euler, the predictor-corrector, RK4.
enum FamilyId { kEveryMethod, kExplicitEuler, kPredictorCorrector, kRungeKutta4, kFamilies };
const Family& family(FamilyId id);
// Defined in their files.
const Family& everyMethodFamily();
const Family& explicitEulerFamily();
const Family& predictorCorrectorFamily();
const Family& rungeKutta4Family();
// The driver family's first row named `id` (a Row's `frame`); -1: none.
int frameRow(const char* id);

// Each family's rows of a model (the family's own row numbers).
using FamilyRows = std::array<std::vector<int>, kFamilies>;

// The course's main loop step of `method` with `every`, each family's `rows` (the driver's lines
// are its family's rows) and `overlay`:
// simulateOneStep(), then the method's integrate() (explicit Euler, the predictor-corrector or
// RK4), then what the overlay lays over it. With no row it is core/integrator.cpp's step,
// operation for operation.
Step linesStep(Method method, const EveryMethod& every, const FamilyRows& rows,
               const Overlay& overlay);

// The start state of `bodies`: a copy, or with `alias` the live state (what a pointer or
// Eigen::Ref "copy" reads later).
struct Backup {
  Backup(const std::vector<Particles<float>*>& of, bool alias_live)
      : bodies(of), alias(alias_live) {
    for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
  }
  Mat4X<float> x(std::size_t b) const { return alias ? bodies[b]->position : x0[b]; }
  Mat4X<float> v(std::size_t b) const { return alias ? bodies[b]->velocity : v0[b]; }
  const std::vector<Particles<float>*>& bodies;
  bool alias;
  std::vector<Mat4X<float>> x0, v0;
};

// `rate` · h · scale, or the course's rate · h when the scale is 1.
inline Mat4X<float> increment(const Mat4X<float>& rate, float h, float scale) {
  return scale == 1 ? Mat4X<float>(rate * h) : Mat4X<float>((rate * h) * scale);
}

}  // namespace clothref::grader::integrators
