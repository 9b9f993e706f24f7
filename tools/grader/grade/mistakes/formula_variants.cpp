#include "grader/grade/mistakes/formula_variants.h"

#include <cmath>

#include "clothref/formula/course_formulas.h"
#include "grader/grade/cause_ids.h"

namespace clothref::grader {

Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 ForceMistake mistake, const Vec4<float>& gravity) {
  SpringVariant variant;
  variant.spring_negated = mistake == ForceMistake::SpringSign;
  variant.damper_negated = mistake == ForceMistake::DamperSign;
  variant.no_damper = mistake == ForceMistake::NoDamper;
  variant.damper_unnormalised = mistake == ForceMistake::DamperUnnormalised;
  const auto& p = cloth.particles;
  Mat4X<float> a = acc0;
  if (mistake == ForceMistake::AssignTotal || mistake == ForceMistake::AssignTotalGravity) {
    const Vec4<float> added =
        mistake == ForceMistake::AssignTotalGravity ? gravity : Vec4<float>::Zero();
    for (int i = 0; i < p.size(); ++i) a.col(i) = p.mass[i] != 0 ? added : Vec4<float>::Zero();
  }
  // The direction left unnormalised is the damper along d with the whole force times |d|.
  variant.damper_unnormalised =
      variant.damper_unnormalised || mistake == ForceMistake::DirectionUnnormalised;
  // The loop of the library's computeSpringForce (core/cloth.cpp), its accumulation switchable.
  for (const auto& s : cloth.springs) {
    const int i = int(s.start), j = int(s.end);
    Vec4<float> f;
    formula::springForce(p.position.col(i).data(), p.position.col(j).data(),
                         p.velocity.col(i).data(), p.velocity.col(j).data(), s.rest_length,
                         cloth.spring_coef, cloth.damper_coef, f.data(), variant);
    if (mistake == ForceMistake::DirectionUnnormalised)
      f *= (p.position.col(i) - p.position.col(j)).norm();
    float wi = p.inverse_mass[i], wj = p.inverse_mass[j];
    if (mistake == ForceMistake::MassNotInverse) wi = p.mass[i], wj = p.mass[j];
    if (mistake == ForceMistake::DivideByMass) wi = 1.0f / p.mass[i], wj = 1.0f / p.mass[j];
    if (mistake == ForceMistake::Assign) {
      a.col(i) = -f * wi;
      a.col(j) = f * wj;
    } else {
      if (mistake != ForceMistake::OtherEndOnly) a.col(i) -= f * wi;
      if (mistake != ForceMistake::OneEnd) a.col(j) += f * wj;
    }
  }
  return a;
}

const std::vector<ForceRow>& forceRows() {
  static const std::vector<ForceRow> rows = {
      {ForceMistake::Assign, cause::kAssignNotAccumulate},
      {ForceMistake::SpringSign, cause::kSpringForceSign},
      {ForceMistake::DamperSign, cause::kDamperSign},
      {ForceMistake::NoDamper, cause::kMissingDamper},
      {ForceMistake::DamperUnnormalised, cause::kDamperNotNormalised},
      {ForceMistake::OneEnd, cause::kForceOneEndOnly},
      {ForceMistake::MassNotInverse, cause::kMassNotInverse},
      {ForceMistake::DivideByMass, cause::kFixedParticleMoves},
      {ForceMistake::OtherEndOnly, cause::kForceOneEndOnly},
      {ForceMistake::AssignTotal, cause::kAssignNotAccumulate},
      {ForceMistake::AssignTotalGravity, cause::kAssignNotAccumulate}};
  return rows;
}

std::string forceModelText(ForceMistake mistake) {
  switch (mistake) {
    case ForceMistake::None:
      return "the course's spring force";
    case ForceMistake::DirectionUnnormalised:
      return "the course's spring force along the unnormalised x_s - x_e (the result of "
             "normalized() discarded)";
    case ForceMistake::Assign:
      return "the course's spring force assigned to the accelerations (=) instead of added";
    case ForceMistake::SpringSign:
      return "the course's spring force with the Hooke term's sign flipped";
    case ForceMistake::DamperSign:
      return "the course's spring force with the damper's sign flipped";
    case ForceMistake::NoDamper:
      return "the course's spring force without the damper";
    case ForceMistake::DamperUnnormalised:
      return "the course's spring force with the damper along the unnormalised x_s - x_e";
    case ForceMistake::OneEnd:
      return "the course's spring force on the start particle only";
    case ForceMistake::MassNotInverse:
      return "the course's spring force times the mass instead of the inverse mass";
    case ForceMistake::DivideByMass:
      return "the course's spring force divided by the mass (infinite for a fixed particle)";
    case ForceMistake::OtherEndOnly:
      return "the course's spring force on the end particle only";
    case ForceMistake::AssignTotal:
      return "the course's spring forces summed and assigned (what was there lost)";
    case ForceMistake::AssignTotalGravity:
      return "the course's spring forces summed and assigned, gravity added back";
  }
  return "";
}

namespace {

ContactVariant contactVariant(ContactMistake m) {
  ContactVariant v;
  v.normal_flipped = m == ContactMistake::NormalSign;
  v.touching_skipped = m == ContactMistake::TouchingSkipped;
  v.separating_pushed = m == ContactMistake::NoApproachCheck;
  v.full_velocity = m == ContactMistake::RestitutionFull;
  v.undivided = m == ContactMistake::ImpulseNotDivided;
  v.massless_fixed = m == ContactMistake::FixedMassless;
  v.moves_a = m != ContactMistake::CorrectionOtherOnly && m != ContactMistake::NoCorrection;
  v.moves_b = m != ContactMistake::CorrectionSphereOnly && m != ContactMistake::NoCorrection;
  return v;
}

}  // namespace

std::vector<ContactRow> contactRows(bool sphere_sphere) {
  std::vector<ContactRow> rows = {
      {ContactMistake::NoApproachCheck, cause::kNoApproachCheck},
      {ContactMistake::RestitutionFull, cause::kRestitutionFullVelocity},
      {ContactMistake::CorrectionSphereOnly, cause::kCorrectionOneBody},
      {ContactMistake::CorrectionOtherOnly, cause::kCorrectionOneBody},
      {ContactMistake::NoCorrection, cause::kNoPositionCorrection},
      {ContactMistake::FirstSphereOnly, cause::kFirstSphereOnly},
      {ContactMistake::NormalSign, cause::kCollisionNormalSign},
      {ContactMistake::TouchingSkipped, cause::kTouchingSkipped},
      {ContactMistake::ImpulseNotDivided, cause::kWrongMassSplit},
      // coefRestitution overwritten (e = 0 or 1); a case where it cannot matter is skipped
      {ContactMistake::RestitutionZero, cause::kRestitutionIgnored},
      {ContactMistake::RestitutionOne, cause::kRestitutionIgnored}};
  // a pair twice only where there are pairs of spheres; a fixed particle and sphere 0's
  // position only where there is a cloth
  const std::vector<ContactRow> sphere_rows = {
      {ContactMistake::PairTwice, cause::kPairProcessedTwice}};
  const std::vector<ContactRow> cloth_rows = {
      {ContactMistake::FixedMassless, cause::kFixedParticleMassless},
      {ContactMistake::FixedSkipped, cause::kFixedParticleSkipped},
      {ContactMistake::SphereZeroForAll, cause::kFirstSphereOnly}};
  for (const ContactRow& row : sphere_sphere ? sphere_rows : cloth_rows) rows.push_back(row);
  return rows;
}

void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, ContactMistake mistake) {
  collideModel(spheres, cloth, sphere_sphere,
               withMistake(courseContact(restitution, correction), mistake));
}

ContactModel courseContact(float restitution, float correction) {
  ContactModel model;
  model.restitution = restitution;
  model.correction = correction;
  return model;
}

ContactModel withMistake(ContactModel model, ContactMistake mistake) {
  const ContactVariant v = contactVariant(mistake);
  ContactVariant& m = model.variant;
  m.normal_flipped = m.normal_flipped || v.normal_flipped;
  m.touching_skipped = m.touching_skipped || v.touching_skipped;
  m.separating_pushed = m.separating_pushed || v.separating_pushed;
  m.full_velocity = m.full_velocity || v.full_velocity;
  m.undivided = m.undivided || v.undivided;
  m.massless_fixed = m.massless_fixed || v.massless_fixed;
  m.moves_a = m.moves_a && v.moves_a;
  m.moves_b = m.moves_b && v.moves_b;
  if (mistake == ContactMistake::RestitutionZero) model.restitution = 0;
  if (mistake == ContactMistake::RestitutionOne) model.restitution = 1;
  model.first_sphere_only = model.first_sphere_only || mistake == ContactMistake::FirstSphereOnly;
  model.sphere_zero_for_all =
      model.sphere_zero_for_all || mistake == ContactMistake::SphereZeroForAll;
  model.pair_twice = model.pair_twice || mistake == ContactMistake::PairTwice;
  model.fixed_skipped = model.fixed_skipped || mistake == ContactMistake::FixedSkipped;
  static const std::pair<ContactMistake, const char*> texts[] = {
      {ContactMistake::NoApproachCheck, "with an impulse for separating bodies too"},
      {ContactMistake::RestitutionFull, "with the impulse from the whole relative velocity"},
      {ContactMistake::CorrectionSphereOnly, "with the position correction on the sphere only"},
      {ContactMistake::CorrectionOtherOnly, "with the position correction on the other body only"},
      {ContactMistake::NoCorrection, "without the position correction"},
      {ContactMistake::FixedMassless, "with a fixed particle as massless"},
      {ContactMistake::FirstSphereOnly, "for sphere 0 only"},
      {ContactMistake::SphereZeroForAll, "with sphere 0's position and radius for every sphere"},
      {ContactMistake::NormalSign, "with the normal reversed"},
      {ContactMistake::TouchingSkipped, "skipping bodies that exactly touch"},
      {ContactMistake::RestitutionZero, "with restitution 0"},
      {ContactMistake::RestitutionOne, "with restitution 1"},
      {ContactMistake::PairTwice, "with every pair processed twice"},
      {ContactMistake::ImpulseNotDivided, "with the impulse not divided by 1/m_a + 1/m_b"},
      {ContactMistake::FixedSkipped, "skipping the fixed particles"}};
  for (const auto& [which, text] : texts)
    if (which == mistake) model.changes.push_back(text);
  return model;
}

ContactModel combined(ContactModel model, const ContactModel& other, const ContactModel& course) {
  ContactVariant& m = model.variant;
  const ContactVariant& o = other.variant;
  m.normal_flipped = m.normal_flipped || o.normal_flipped;
  m.touching_skipped = m.touching_skipped || o.touching_skipped;
  m.separating_pushed = m.separating_pushed || o.separating_pushed;
  m.full_velocity = m.full_velocity || o.full_velocity;
  m.undivided = m.undivided || o.undivided;
  m.massless_fixed = m.massless_fixed || o.massless_fixed;
  m.moves_a = m.moves_a && o.moves_a;
  m.moves_b = m.moves_b && o.moves_b;
  if (other.restitution != course.restitution) model.restitution = other.restitution;
  if (other.correction != course.correction) model.correction = other.correction;
  if (other.reach_offset != course.reach_offset) model.reach_offset = other.reach_offset;
  model.first_sphere_only = model.first_sphere_only || other.first_sphere_only;
  model.sphere_zero_for_all = model.sphere_zero_for_all || other.sphere_zero_for_all;
  model.pair_twice = model.pair_twice || other.pair_twice;
  model.fixed_skipped = model.fixed_skipped || other.fixed_skipped;
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
                  const ContactModel& model) {
  const Vec4<float> va = a.velocity.col(i), vb = b.velocity.col(j);
  const bool approaching = (va - vb).dot(a.position.col(i) - b.position.col(j)) < 0;
  const auto contact = model.variant.massless_fixed
                           ? masslessFixedContact
                           : formula::resolveContact<float, ContactVariant>;
  const bool touched =
      contact(a.position.col(i).data(), a.velocity.col(i).data(), a.inverse_mass[i],
              b.position.col(j).data(), b.velocity.col(j).data(), b.inverse_mass[j],
              reach + model.reach_offset, model.restitution, model.correction, model.variant);
  if (touched && model.divides_by_speed && approaching && (va.isZero(0) || vb.isZero(0))) {
    a.velocity.col(i).setConstant(std::nanf(""));
    b.velocity.col(j).setConstant(std::nanf(""));
  }
}

}  // namespace

void collideModel(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                  const ContactModel& model) {
  auto& sp = spheres.particles;
  const int count = model.first_sphere_only ? 1 : spheres.size();
  // The loops of the library's two collide stubs (core/spheres.cpp), their ranges switchable.
  if (!sphere_sphere) {
    for (int i = 0; i < count; ++i) {
      const int a = model.sphere_zero_for_all ? 0 : i;
      for (int j = 0; j < cloth.particles.size(); ++j)
        if (!model.fixed_skipped || cloth.particles.mass[j] != 0)
          modelContact(sp, a, cloth.particles, j, spheres.radius[a], model);
    }
    return;
  }
  for (int i = 0; i < count; ++i)
    for (int j = model.pair_twice ? 0 : i + 1; j < spheres.size(); ++j)
      if (j != i) modelContact(sp, i, sp, j, spheres.radius[i] + spheres.radius[j], model);
}

std::string contactModelText(const ContactModel& model) {
  std::string text = "the course's collide";
  for (std::size_t k = 0; k < model.changes.size(); ++k)
    text += (k == 0 ? " " : " and ") + model.changes[k];
  return text;
}

}  // namespace clothref::grader
