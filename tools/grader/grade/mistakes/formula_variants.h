// Students' mistakes in the spring force and the contact, as variants of the course's formulas
// (formula::springForce and formula::resolveContact with one switch on), and the loops of stubs 2-4
// that apply them: the probes compare a student's numbers with each variant to name the mistake.
// Expected answers never come from here: they are the library's stubs (computeSpringForce,
// collide); FormulaVariants.* prove the no-mistake variants bit-equal to them.
#pragma once
#include <string>
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"

namespace clothref::grader {

// Run-time switches with the names of formula::CourseSpring's and CourseContact's, and one of
// the grader's own: massless_fixed, the textbook exchange in place of the course's impulse.
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
  DirectionUnnormalised,  // `d.normalized();` discarded: F = d (k_d (v_rel . d) + k_s (|d| - rest))
  Assign,                 // a = -F / m instead of a -= F / m
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
// The cloth's spring_coef and damper_coef are the model's constants (a fitted k_s, k_d: set them
// on a copy); `gravity` (m/s^2) the edition's, which AssignTotalGravity adds back.
Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 ForceMistake mistake, const Vec4<float>& gravity);

// The force probe's rows: every mistake it simulates on each case, in this order, and the cause
// each stands for (the catalogue's "force variant" entries answer to these rows and to the
// probe's candidates, CatalogueModels.*). A new force mistake: its enumerator and comment above,
// its switches in springAccelerations, its text and its row (formula_variants.cpp).
struct ForceRow {
  ForceMistake mistake;
  const char* cause;
};
const std::vector<ForceRow>& forceRows();

// What a mistake's model computes, in a student's words ("the course's spring force with the
// damper's sign flipped"): the head of a replay's proof line (explain/replay.h).
std::string forceModelText(ForceMistake mistake);

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
  ImpulseNotDivided,
  FixedSkipped  // a cloth particle of mass 0 skipped: no contact with it
};

// The collision probe's rows of stub 3 (sphere_sphere false) or stub 4, as forceRows(): a new
// contact mistake is its enumerator, its switches (contactVariant or withMistake), its text and
// its row (formula_variants.cpp).
struct ContactRow {
  ContactMistake mistake;
  const char* cause;
};
std::vector<ContactRow> contactRows(bool sphere_sphere);

// Stub 3 (sphere_sphere false: spheres against the cloth's particles) or stub 4 with one mistake,
// in place, with the course's restitution and correction factor.
void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, ContactMistake mistake);

// A contact model: the course's collide with any number of the mistakes' switches on and its
// constants free (a fitted restitution, correction factor or contact distance), so that a model
// of one mistake, of a fitted constant or of two mistakes at once is replayed on every case of a
// probe (issue 38: a cause is likely only when its model gives the student's numbers everywhere).
struct ContactModel {
  ContactVariant variant;
  float restitution = 0, correction = 0;  // the edition's, set by courseContact
  float reach_offset = 0;  // the contact distance r (+ r_b) + this (m): `radius + 0.1`
  bool first_sphere_only = false, sphere_zero_for_all = false, pair_twice = false,
       fixed_skipped = false;
  // v . n computed as |v| cos(angle), cos = v . n / |v|: NaN for a body at rest in an approaching
  // pair (the impulse's normal part is that body's own v . n, each body's formed apart)
  bool divides_by_speed = false;
  std::vector<std::string> changes;  // what differs from the course's collide, for the text
};

// The course's collide (no switch on) with its restitution and correction factor.
ContactModel courseContact(float restitution, float correction);
// `model` with `mistake` switched on too.
ContactModel withMistake(ContactModel model, ContactMistake mistake);
// `model` with the switches and constants of `other` that differ from the course's too.
ContactModel combined(ContactModel model, const ContactModel& other, const ContactModel& course);

// Stub 3 or 4 as `model` computes it, in place.
void collideModel(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                  const ContactModel& model);
// "the course's collide without the position correction and with restitution 1"
std::string contactModelText(const ContactModel& model);

}  // namespace clothref::grader
