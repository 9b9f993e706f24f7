// The integrator mistakes as rows on the course's step (integrate_mistakes.h): the rows of the
// families (integrate_step.h) numbered in their order, a model's rows run on the step, and two
// models combined. A new mistake is its catalogue entry and its row in its family's file.
#include "grader/grade/mistakes/integrate_mistakes.h"

namespace clothref::grader::integrators {
namespace {

// A row of the families' tables: its family and its number there.
struct Place {
  FamilyId family;
  int row;
};

// The place of row `r` (the rows of every family in order); none when there is no such row.
std::optional<Place> placeOf(int r) {
  if (r < 0) return std::nullopt;
  for (int f = 0; f < kFamilies; ++f) {
    const int size = int(family(FamilyId(f)).rows.size());
    if (r < size) return Place{FamilyId(f), r};
    r -= size;
  }
  return std::nullopt;
}

const Family::Head& headOf(const Place& at) { return family(at.family).rows[std::size_t(at.row)]; }

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

std::string wordsOf(const Family::Head& row, Method method) {
  std::string text = row.text;
  const std::string name = method == Method::Explicit   ? "explicit Euler"
                           : method == Method::Implicit ? "implicit Euler"
                           : method == Method::Midpoint ? "midpoint"
                                                        : "RK4";
  const auto at = text.find("{method}");
  if (at != std::string::npos) text.replace(at, 8, "the course's " + name);
  return text;
}

// Every row in order, with `visit(global row number, its head)`.
template <typename Visit>
void eachRow(Visit visit) {
  int r = 0;
  for (int f = 0; f < kFamilies; ++f)
    for (const Family::Head& head : family(FamilyId(f)).rows) visit(r++, head);
}

// Row `at`'s lines added to a model's: its family's row, the driver's row it names (Row::frame)
// and the lines every method reads; false when one of those is set two ways.
bool addLines(const Place& at, EveryMethod& every, FamilyRows& rows) {
  const Family::Head& row = headOf(at);
  rows[at.family].push_back(at.row);
  if (const int frame = frameRow(row.frame); frame >= 0) rows[kEveryMethod].push_back(frame);
  return switches::merge(every, row.every);
}

}  // namespace

Step courseStep(const StepModel& model) {
  EveryMethod every;
  FamilyRows rows;
  Method method = model.method;
  Overlay o = model.overlay;
  for (int r : model.rows) {
    const std::optional<Place> at = placeOf(r);
    if (!at) continue;
    addLines(*at, every, rows);
    const Family::Head& row = headOf(*at);
    if (row.runs) method = *row.runs;
    if (row.result_step != 1) o.result_step = row.result_step;
  }
  return linesStep(method, every, rows, o);
}

std::vector<Reading> readingsOf(std::string_view id, Method method) {
  std::vector<Reading> out;
  eachRow([&](int r, const Family::Head& row) {
    if (row.id == id && (row.methods & methodBit(method)))
      out.push_back({row.id, wordsOf(row, method), r, row.first_pass});
  });
  return out;
}

std::vector<Reading> readingsOf(Method method) {
  std::vector<Reading> out;
  eachRow([&](int r, const Family::Head& row) {
    if (row.methods & methodBit(method))
      out.push_back({row.id, wordsOf(row, method), r, row.first_pass});
  });
  return out;
}

std::vector<std::string> readingIds() {
  std::vector<std::string> ids;
  eachRow([&](int, const Family::Head& row) {
    if (ids.empty() || ids.back() != row.id) ids.push_back(row.id);
  });
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
  EveryMethod every;
  FamilyRows rows;
  std::optional<Method> runs;
  for (const StepModel* m : {&a, &b})
    for (int r : m->rows) {
      const std::optional<Place> at = placeOf(r);
      if (!at) return std::nullopt;
      if (!addLines(*at, every, rows)) return std::nullopt;
      const Family::Head& row = headOf(*at);
      if (row.runs && runs && *row.runs != *runs) return std::nullopt;
      if (row.runs) runs = row.runs;
      if (m == &b) both.rows.push_back(r);
    }
  for (int f = 0; f < kFamilies; ++f)
    if (!family(FamilyId(f)).merges(rows[std::size_t(f)])) return std::nullopt;
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
