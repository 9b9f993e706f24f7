#include "grader/grade/mistakes/formula_variants.h"

#include <cmath>
#include <optional>

#include "clothref/formula/course_formulas.h"
#include "grader/grade/cause_ids.h"

namespace clothref::grader {
namespace {

// ---- The spring force's table

// The run-time switches of formula::springForce, with the names of formula::CourseSpring's.
struct SpringVariant {
  bool spring_negated = false, damper_negated = false, no_damper = false,
       damper_unnormalised = false;
};

// A row's switches: the formula's and those of stub 2's loop around it; the defaults are the
// course's (core/cloth.cpp, computeSpringForce).
struct ForceSwitches {
  SpringVariant formula = {};
  bool along_unnormalised = false;  // the whole force times |d| (`d.normalized();` discarded)
  bool assigns = false;             // a = -F / m instead of a -= F / m
  bool assigns_total = false;       // the springs' sum assigned: what was there is lost
  bool adds_gravity_back = false;   // ... and gravity added back by hand to every free particle
  bool times_mass = false;          // F * m instead of F / m
  bool divides_by_mass = false;     // F / m: a fixed particle (m = 0) gets infinity
  bool start_only = false;          // only the start particle gets its force
  bool end_only = false;            // only the end particle gets its force
};

constexpr bool kProbed = true, kReplayed = false;

struct ForceTableRow {
  const char* cause;
  bool probed;  // simulated on every case of the probe (kReplayed: a replay's model only)
  const char* text;
  ForceSwitches switches;
};

// Every reading of a spring-force mistake, in the order the probe simulates and replays them.
// clang-format off
const std::vector<ForceTableRow>& forceTable() {
  static const std::vector<ForceTableRow> table = {
    {cause::kAssignNotAccumulate, kProbed,
     "the course's spring force assigned to the accelerations (=) instead of added",
     {.assigns = true}},
    {cause::kSpringForceSign, kProbed,
     "the course's spring force with the Hooke term's sign flipped",
     {.formula = {.spring_negated = true}}},
    {cause::kDamperSign, kProbed, "the course's spring force with the damper's sign flipped",
     {.formula = {.damper_negated = true}}},
    {cause::kMissingDamper, kProbed, "the course's spring force without the damper",
     {.formula = {.no_damper = true}}},
    {cause::kDamperNotNormalised, kProbed,
     "the course's spring force with the damper along the unnormalised x_s - x_e",
     {.formula = {.damper_unnormalised = true}}},
    {cause::kForceOneEndOnly, kProbed, "the course's spring force on the start particle only",
     {.start_only = true}},
    {cause::kMassNotInverse, kProbed,
     "the course's spring force times the mass instead of the inverse mass", {.times_mass = true}},
    {cause::kFixedParticleMoves, kProbed,
     "the course's spring force divided by the mass (infinite for a fixed particle)",
     {.divides_by_mass = true}},
    {cause::kForceOneEndOnly, kProbed, "the course's spring force on the end particle only",
     {.end_only = true}},
    {cause::kAssignNotAccumulate, kProbed,
     "the course's spring forces summed and assigned (what was there lost)",
     {.assigns_total = true}},
    {cause::kAssignNotAccumulate, kProbed,
     "the course's spring forces summed and assigned, gravity added back",
     {.assigns_total = true, .adds_gravity_back = true}},
    // The direction left unnormalised is the damper along d with the whole force times |d|.
    {cause::kDirectionNotNormalised, kReplayed,
     "the course's spring force along the unnormalised x_s - x_e (the result of normalized() "
     "discarded)",
     {.formula = {.damper_unnormalised = true}, .along_unnormalised = true}},
  };
  return table;
}
// clang-format on

}  // namespace

const std::vector<ForceRow>& forceRows() {
  static const std::vector<ForceRow> rows = [] {
    std::vector<ForceRow> out;
    for (const ForceTableRow& row : forceTable())
      out.push_back({int(out.size()), row.cause, row.probed});
    return out;
  }();
  return rows;
}

ForceRow forceRow(std::string_view cause, int reading) {
  for (const ForceRow& row : forceRows())
    if (row.cause == cause && reading-- == 0) return row;
  return {};
}

Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 const ForceRow& mistake, const Vec4<float>& gravity) {
  const ForceSwitches on = mistake.row < 0 ? ForceSwitches{} : forceTable()[mistake.row].switches;
  const auto& p = cloth.particles;
  Mat4X<float> a = acc0;
  if (on.assigns_total) {
    const Vec4<float> added = on.adds_gravity_back ? gravity : Vec4<float>::Zero();
    for (int i = 0; i < p.size(); ++i) a.col(i) = p.mass[i] != 0 ? added : Vec4<float>::Zero();
  }
  // The loop of the library's computeSpringForce (core/cloth.cpp), its accumulation switchable.
  for (const auto& s : cloth.springs) {
    const int i = int(s.start), j = int(s.end);
    Vec4<float> f;
    formula::springForce(p.position.col(i).data(), p.position.col(j).data(),
                         p.velocity.col(i).data(), p.velocity.col(j).data(), s.rest_length,
                         cloth.spring_coef, cloth.damper_coef, f.data(), on.formula);
    if (on.along_unnormalised) f *= (p.position.col(i) - p.position.col(j)).norm();
    float wi = p.inverse_mass[i], wj = p.inverse_mass[j];
    if (on.times_mass) wi = p.mass[i], wj = p.mass[j];
    if (on.divides_by_mass) wi = 1.0f / p.mass[i], wj = 1.0f / p.mass[j];
    if (on.assigns) {
      a.col(i) = -f * wi;
      a.col(j) = f * wj;
    } else {
      if (!on.end_only) a.col(i) -= f * wi;
      if (!on.start_only) a.col(j) += f * wj;
    }
  }
  return a;
}

std::string forceModelText(const ForceRow& mistake) {
  return mistake.row < 0 ? "the course's spring force" : forceTable()[mistake.row].text;
}

namespace {

// ---- The contact's table

// The run-time switches of formula::resolveContact, with the names of formula::CourseContact's,
// and one of the grader's own: massless_fixed, the textbook exchange in place of the course's
// impulse (masslessFixedContact below).
struct ContactVariant {
  bool normal_flipped = false, touching_skipped = false, separating_pushed = false,
       full_velocity = false, undivided = false, massless_fixed = false, moves_a = true,
       moves_b = true;
};

// A row's switches: the formula's, a restitution written over the course's, and those of the
// loops of stubs 3 and 4 (core/spheres.cpp, collide); the defaults are the course's.
struct ContactSwitches {
  ContactVariant formula = {};
  std::optional<float> restitution = {};  // coefRestitution overwritten
  bool first_sphere_only = false;         // only sphere 0 is tested
  bool sphere_zero_for_all = false;  // the loop over i uses position(0), radius(0): sphere 0 each
  bool pair_twice = false;           // stub 4's pairs (i, j) and (j, i)
  bool fixed_skipped = false;        // a cloth particle of mass 0 skipped: no contact with it
};

// Which stubs a row applies to: both, stub 3 (a cloth: its fixed particles, sphere 0's position
// for every sphere) or stub 4 (pairs of spheres).
enum Stubs { kBoth, kCloth, kSpheres };

struct ContactTableRow {
  const char* cause;
  Stubs stubs;
  const char* text;  // how it changes the course's collide
  ContactSwitches switches;
};

// Every reading of a contact mistake, in the order the probes simulate and replay them.
// clang-format off
const std::vector<ContactTableRow>& contactTable() {
  static const std::vector<ContactTableRow> table = {
    {cause::kNoApproachCheck, kBoth, "with an impulse for separating bodies too",
     {.formula = {.separating_pushed = true}}},
    {cause::kRestitutionFullVelocity, kBoth, "with the impulse from the whole relative velocity",
     {.formula = {.full_velocity = true}}},
    {cause::kCorrectionOneBody, kBoth, "with the position correction on the sphere only",
     {.formula = {.moves_b = false}}},
    {cause::kCorrectionOneBody, kBoth, "with the position correction on the other body only",
     {.formula = {.moves_a = false}}},
    {cause::kNoPositionCorrection, kBoth, "without the position correction",
     {.formula = {.moves_a = false, .moves_b = false}}},
    {cause::kFirstSphereOnly, kBoth, "for sphere 0 only", {.first_sphere_only = true}},
    {cause::kCollisionNormalSign, kBoth, "with the normal reversed",
     {.formula = {.normal_flipped = true}}},
    {cause::kTouchingSkipped, kBoth, "skipping bodies that exactly touch",
     {.formula = {.touching_skipped = true}}},
    {cause::kWrongMassSplit, kBoth, "with the impulse not divided by 1/m_a + 1/m_b",
     {.formula = {.undivided = true}}},
    // coefRestitution overwritten (e = 0 or 1); a case where it cannot matter is skipped
    {cause::kRestitutionIgnored, kBoth, "with restitution 0", {.restitution = 0.0f}},
    {cause::kRestitutionIgnored, kBoth, "with restitution 1", {.restitution = 1.0f}},
    // a pair twice only where there are pairs of spheres; a fixed particle and sphere 0's
    // position only where there is a cloth
    {cause::kPairProcessedTwice, kSpheres, "with every pair processed twice",
     {.pair_twice = true}},
    {cause::kFixedParticleMassless, kCloth, "with a fixed particle as massless",
     {.formula = {.massless_fixed = true}}},
    {cause::kFixedParticleSkipped, kCloth, "skipping the fixed particles",
     {.fixed_skipped = true}},
    {cause::kFirstSphereOnly, kCloth, "with sphere 0's position and radius for every sphere",
     {.sphere_zero_for_all = true}},
  };
  return table;
}
// clang-format on

// The switches of every row of `model` at once.
ContactSwitches switchesOf(const ContactModel& model) {
  ContactSwitches on;
  for (const int row : model.rows) {
    const ContactSwitches& r = contactTable()[row].switches;
    ContactVariant& m = on.formula;
    const ContactVariant& v = r.formula;
    m.normal_flipped = m.normal_flipped || v.normal_flipped;
    m.touching_skipped = m.touching_skipped || v.touching_skipped;
    m.separating_pushed = m.separating_pushed || v.separating_pushed;
    m.full_velocity = m.full_velocity || v.full_velocity;
    m.undivided = m.undivided || v.undivided;
    m.massless_fixed = m.massless_fixed || v.massless_fixed;
    m.moves_a = m.moves_a && v.moves_a;
    m.moves_b = m.moves_b && v.moves_b;
    on.first_sphere_only = on.first_sphere_only || r.first_sphere_only;
    on.sphere_zero_for_all = on.sphere_zero_for_all || r.sphere_zero_for_all;
    on.pair_twice = on.pair_twice || r.pair_twice;
    on.fixed_skipped = on.fixed_skipped || r.fixed_skipped;
  }
  return on;
}

}  // namespace

std::vector<ContactRow> contactRows(bool sphere_sphere) {
  std::vector<ContactRow> rows;
  const std::vector<ContactTableRow>& table = contactTable();
  for (std::size_t k = 0; k < table.size(); ++k)
    if (table[k].stubs == kBoth || table[k].stubs == (sphere_sphere ? kSpheres : kCloth))
      rows.push_back({int(k), table[k].cause, table[k].text});
  return rows;
}

ContactRow contactRow(std::string_view cause, int reading) {
  const std::vector<ContactTableRow>& table = contactTable();
  for (std::size_t k = 0; k < table.size(); ++k)
    if (table[k].cause == cause && reading-- == 0) return {int(k), table[k].cause, table[k].text};
  return {};
}

void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, const ContactRow& mistake) {
  collideModel(spheres, cloth, sphere_sphere,
               withMistake(courseContact(restitution, correction), mistake));
}

ContactModel courseContact(float restitution, float correction) {
  ContactModel model;
  model.restitution = restitution;
  model.correction = correction;
  return model;
}

ContactModel withMistake(ContactModel model, const ContactRow& mistake) {
  if (mistake.row < 0) return model;
  const ContactTableRow& row = contactTable()[mistake.row];
  model.rows.push_back(mistake.row);
  if (row.switches.restitution) model.restitution = *row.switches.restitution;
  model.changes.push_back(row.text);
  return model;
}

ContactModel combined(ContactModel model, const ContactModel& other, const ContactModel& course) {
  model.rows.insert(model.rows.end(), other.rows.begin(), other.rows.end());
  if (other.restitution != course.restitution) model.restitution = other.restitution;
  if (other.correction != course.correction) model.correction = other.correction;
  if (other.reach_offset != course.reach_offset) model.reach_offset = other.reach_offset;
  model.divides_by_speed = model.divides_by_speed || other.divides_by_speed;
  model.changes.insert(model.changes.end(), other.changes.begin(), other.changes.end());
  return model;
}

namespace {

// The textbook exchange of normal velocities u_a = n (v_a . n), u_b = n (v_b . n) with masses,
//   u_a' = (m_a u_a + m_b u_b + m_b e (u_b - u_a)) / (m_a + m_b), u_b' likewise,
// a fixed body's 1/m = 0 read as m = 0 (massless), in place of the course's impulse: the course's
// contact test and correction are the library's resolveContact (run on copies of the velocities),
// the normal and approach a copy of its first lines (docs/design.md's table of copies;
// FormulaVariants.TheMasslessExchangeKeepsTheCoursesGeometry).
bool masslessFixedContact(float* x_a, float* v_a, float inverse_mass_a, float* x_b, float* v_b,
                          float inverse_mass_b, float contact_distance, float restitution,
                          float correction, const ContactVariant& variant) {
  float n[4], relative[4];
  for (int k = 0; k < 4; ++k) n[k] = variant.normal_flipped ? -(x_a[k] - x_b[k]) : x_a[k] - x_b[k];
  const float squared = formula::dot4(n, n);
  if (squared > 0.0f) {
    const float length = std::sqrt(squared);
    for (int k = 0; k < 4; ++k) n[k] = n[k] / length;
  }
  for (int k = 0; k < 4; ++k) relative[k] = v_a[k] - v_b[k];
  const float approach = formula::dot4(relative, n);
  float course_v_a[4], course_v_b[4];  // the course's impulse lands here, unused
  for (int k = 0; k < 4; ++k) course_v_a[k] = v_a[k], course_v_b[k] = v_b[k];
  if (!formula::resolveContact(x_a, course_v_a, inverse_mass_a, x_b, course_v_b, inverse_mass_b,
                               contact_distance, restitution, correction, variant))
    return false;
  if (!(approach < 0.0f || variant.separating_pushed)) return true;
  const float m_a = inverse_mass_a > 0.0f ? 1.0f / inverse_mass_a : 0.0f;
  const float m_b = inverse_mass_b > 0.0f ? 1.0f / inverse_mass_b : 0.0f;
  const float normal_a = formula::dot4(v_a, n), normal_b = formula::dot4(v_b, n);
  for (int k = 0; k < 4; ++k) {
    const float u_a = n[k] * normal_a, u_b = n[k] * normal_b;
    const float new_a = (m_a * u_a + m_b * u_b + m_b * restitution * (u_b - u_a)) / (m_a + m_b);
    const float new_b = (m_a * u_a + m_b * u_b + m_a * restitution * (u_a - u_b)) / (m_a + m_b);
    v_a[k] += new_a - u_a;
    v_b[k] += new_b - u_b;
  }
  return true;
}

// One contact of `model`: the course's formula with its switches; with divides_by_speed, a pair
// that approaches with a body at rest gets NaN velocities (that body's normal speed is 0 / 0, and
// the impulse J made from it reaches both bodies).
void modelContact(Particles<float>& a, int i, Particles<float>& b, int j, float reach,
                  const ContactModel& model, const ContactVariant& variant) {
  const Vec4<float> va = a.velocity.col(i), vb = b.velocity.col(j);
  const bool approaching = (va - vb).dot(a.position.col(i) - b.position.col(j)) < 0;
  const auto contact = variant.massless_fixed ? masslessFixedContact
                                              : formula::resolveContact<float, ContactVariant>;
  const bool touched =
      contact(a.position.col(i).data(), a.velocity.col(i).data(), a.inverse_mass[i],
              b.position.col(j).data(), b.velocity.col(j).data(), b.inverse_mass[j],
              reach + model.reach_offset, model.restitution, model.correction, variant);
  if (touched && model.divides_by_speed && approaching && (va.isZero(0) || vb.isZero(0))) {
    a.velocity.col(i).setConstant(std::nanf(""));
    b.velocity.col(j).setConstant(std::nanf(""));
  }
}

}  // namespace

void collideModel(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                  const ContactModel& model) {
  auto& sp = spheres.particles;
  const ContactSwitches on = switchesOf(model);
  const int count = on.first_sphere_only ? 1 : spheres.size();
  // The loops of the library's two collide stubs (core/spheres.cpp), their ranges switchable.
  if (!sphere_sphere) {
    for (int i = 0; i < count; ++i) {
      const int a = on.sphere_zero_for_all ? 0 : i;
      for (int j = 0; j < cloth.particles.size(); ++j)
        if (!on.fixed_skipped || cloth.particles.mass[j] != 0)
          modelContact(sp, a, cloth.particles, j, spheres.radius[a], model, on.formula);
    }
    return;
  }
  for (int i = 0; i < count; ++i)
    for (int j = on.pair_twice ? 0 : i + 1; j < spheres.size(); ++j)
      if (j != i)
        modelContact(sp, i, sp, j, spheres.radius[i] + spheres.radius[j], model, on.formula);
}

std::string contactModelText(const ContactModel& model) {
  std::string text = "the course's collide";
  for (std::size_t k = 0; k < model.changes.size(); ++k)
    text += (k == 0 ? " " : " and ") + model.changes[k];
  return text;
}

}  // namespace clothref::grader
