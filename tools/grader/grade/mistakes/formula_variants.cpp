#include "grader/grade/mistakes/formula_variants.h"

#include "clothref/formula/course_formulas.h"
#include "grader/grade/submission/edition.h"

namespace clothref::grader {

Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 ForceMistake mistake) {
  SpringVariant variant;
  variant.spring_negated = mistake == ForceMistake::SpringSign;
  variant.damper_negated = mistake == ForceMistake::DamperSign;
  variant.no_damper = mistake == ForceMistake::NoDamper;
  variant.damper_unnormalised = mistake == ForceMistake::DamperUnnormalised;
  const auto& p = cloth.particles;
  Mat4X<float> a = acc0;
  if (mistake == ForceMistake::AssignTotal || mistake == ForceMistake::AssignTotalGravity) {
    // The course's gravity (m/s^2), the same in both editions' scenes (edition_test checks).
    static const float course_gravity = static_cast<float>(courseEdition(2022).gravity[1]);
    const Vec4<float> gravity(
        0.0f, mistake == ForceMistake::AssignTotalGravity ? course_gravity : 0.0f, 0.0f, 0.0f);
    for (int i = 0; i < p.size(); ++i) a.col(i) = p.mass[i] != 0 ? gravity : Vec4<float>::Zero();
  }
  // The loop of the library's computeSpringForce (core/cloth.cpp), its accumulation switchable.
  for (const auto& s : cloth.springs) {
    const int i = int(s.start), j = int(s.end);
    Vec4<float> f;
    formula::springForce(p.position.col(i).data(), p.position.col(j).data(),
                         p.velocity.col(i).data(), p.velocity.col(j).data(), s.rest_length,
                         cloth.spring_coef, cloth.damper_coef, f.data(), variant);
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

void contact(Particles<float>& a, int i, Particles<float>& b, int j, float reach, float e,
             float correction, const ContactVariant& variant) {
  formula::resolveContact(a.position.col(i).data(), a.velocity.col(i).data(), a.inverse_mass[i],
                          b.position.col(j).data(), b.velocity.col(j).data(), b.inverse_mass[j],
                          reach, e, correction, variant);
}

}  // namespace

void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, ContactMistake mistake) {
  const ContactVariant variant = contactVariant(mistake);
  if (mistake == ContactMistake::RestitutionZero) restitution = 0;
  if (mistake == ContactMistake::RestitutionOne) restitution = 1;
  auto& sp = spheres.particles;
  const int count = mistake == ContactMistake::FirstSphereOnly ? 1 : spheres.size();
  // The loops of the library's two collide stubs (core/spheres.cpp), their ranges switchable.
  if (!sphere_sphere) {
    for (int i = 0; i < count; ++i) {
      const int a = mistake == ContactMistake::SphereZeroForAll ? 0 : i;
      for (int j = 0; j < cloth.particles.size(); ++j)
        contact(sp, a, cloth.particles, j, spheres.radius[a], restitution, correction, variant);
    }
    return;
  }
  for (int i = 0; i < count; ++i)
    for (int j = mistake == ContactMistake::PairTwice ? 0 : i + 1; j < spheres.size(); ++j)
      if (j != i)
        contact(sp, i, sp, j, spheres.radius[i] + spheres.radius[j], restitution, correction,
                variant);
}

}  // namespace clothref::grader
