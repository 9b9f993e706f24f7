// Students' mistakes in the spring force and the contact, as variants of the course's formulas
// (formula::springForce and formula::resolveContact with one switch on), and the loops of stubs 2-4
// that apply them: the probes compare a student's numbers with each variant to name the mistake.
// Expected answers never come from here: they are the library's stubs (computeSpringForce,
// collide); FormulaVariants.* prove the no-mistake variants bit-equal to them.
#pragma once
#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"

namespace clothref::grader {

// Run-time switches with the names of formula::CourseSpring's and CourseContact's.
struct SpringVariant {
  bool spring_negated = false, damper_negated = false, no_damper = false,
       damper_unnormalised = false;
};
struct ContactVariant {
  bool normal_flipped = false, touching_skipped = false, separating_pushed = false,
       full_velocity = false, undivided = false, massless_fixed = false, moves_a = true,
       moves_b = true;
};

enum class ForceMistake {
  None,
  Assign,  // a = -F / m instead of a -= F / m
  SpringSign,
  DamperSign,
  NoDamper,
  DamperUnnormalised,
  OneEnd,             // only the start particle gets its force
  MassNotInverse,     // F * m
  DivideByMass,       // F / m: a fixed particle (m = 0) gets infinity
  OtherEndOnly,       // only the end particle gets its force
  AssignTotal,        // the springs' sum assigned: a = sum F / m, what was there is lost
  AssignTotalGravity  // ... and gravity added back by hand to every free particle
};

// Stub 2 with one mistake: `cloth`'s accelerations are `acc0` plus the springs' (shape 4 x N).
Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 ForceMistake mistake);

enum class ContactMistake {
  None,
  NoApproachCheck,
  RestitutionFull,
  CorrectionSphereOnly,
  CorrectionOtherOnly,
  NoCorrection,
  FixedMassless,
  FirstSphereOnly,   // only sphere 0 is tested
  SphereZeroForAll,  // the loop over i uses position(0), radius(0): sphere 0 once per sphere
  NormalSign,
  TouchingSkipped,
  RestitutionZero,  // coefRestitution overwritten
  RestitutionOne,
  PairTwice,  // stub 4's pairs (i, j) and (j, i)
  ImpulseNotDivided
};

// Stub 3 (sphere_sphere false: spheres against the cloth's particles) or stub 4 with one mistake,
// in place, with the course's restitution and correction factor.
void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, ContactMistake mistake);

}  // namespace clothref::grader
