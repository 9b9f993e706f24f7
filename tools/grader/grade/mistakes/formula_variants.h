// Students' mistakes in the spring force and the contact, as variants of the course's formulas
// (formula::springForce and formula::resolveContact with switches on), and the loops of stubs 2-4
// that apply them, chosen by data: the rows of two tables (formula_variants.cpp). The probes
// compare a student's numbers with each row's model to name the mistake.
// Expected answers never come from here: they are the library's stubs (computeSpringForce,
// collide); FormulaVariants.* prove the no-mistake variants bit-equal to them.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"

namespace clothref::grader {

// A row of a model's table (formula_variants.cpp): one reading of a student's mistake, named by
// the catalogue's id (cause::k…), whose switches of the course's formula and loop are the table's
// data. A new mistake on switches the model already has is its catalogue entry and its row; a new
// switch is a field of that file's switches and its use there. No row (row -1): the course's.
struct ForceRow {
  int row = -1;
  const char* cause = "";
  bool probed = true;  // simulated on every case of the force probe (false: replayed only)
};
struct ContactRow {
  int row = -1;
  const char* cause = "";
  const char* text = "";  // what it changes in the course's collide ("without the position ...")
};

// Every row of the spring force's table, in order: the probe simulates the probed ones on each
// case and replays them all (the catalogue's "force variant" entries answer to these rows,
// CatalogueModels.*).
const std::vector<ForceRow>& forceRows();
// The `reading`-th row named `cause` (0: its first); none: the course's spring force.
ForceRow forceRow(std::string_view cause, int reading = 0);

// Stub 2 with one row's switches: `cloth`'s accelerations are `acc0` plus the springs' (shape 4 x
// N). The cloth's spring_coef and damper_coef are the model's constants (a fitted k_s, k_d: set
// them on a copy); `gravity` (m/s^2) the edition's, which a row that assigns the sum adds back.
Mat4X<float> springAccelerations(const Cloth<float>& cloth, const Mat4X<float>& acc0,
                                 const ForceRow& mistake, const Vec4<float>& gravity);

// What a row's model computes, in a student's words ("the course's spring force with the
// damper's sign flipped"): the head of a replay's proof line (explain/replay.h).
std::string forceModelText(const ForceRow& mistake);

// The collision probe's rows of stub 3 (sphere_sphere false) or stub 4, in the table's order.
std::vector<ContactRow> contactRows(bool sphere_sphere);
// The `reading`-th row named `cause`, of either stub; none: the course's collide.
ContactRow contactRow(std::string_view cause, int reading = 0);

// Stub 3 (sphere_sphere false: spheres against the cloth's particles) or stub 4 with one row's
// switches, in place, with the course's restitution and correction factor.
void collideWithMistake(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                        float restitution, float correction, const ContactRow& mistake);

// A contact model: the course's collide with any number of the table's rows switched on and its
// constants free (a fitted restitution, correction factor or contact distance), so that a model
// of one mistake, of a fitted constant or of two mistakes at once is replayed on every case of a
// probe (issue 38: a cause is likely only when its model gives the student's numbers everywhere).
struct ContactModel {
  std::vector<int> rows;                  // the table's rows switched on
  float restitution = 0, correction = 0;  // the edition's, set by courseContact
  float reach_offset = 0;  // the contact distance r (+ r_b) + this (m): `radius + 0.1`
  // v . n computed as |v| cos(angle), cos = v . n / |v|: NaN for a body at rest in an approaching
  // pair (the impulse's normal part is that body's own v . n, each body's formed apart)
  bool divides_by_speed = false;
  std::vector<std::string> changes;  // what differs from the course's collide, for the text
};

// The course's collide (no row on) with its restitution and correction factor.
ContactModel courseContact(float restitution, float correction);
// `model` with `mistake`'s row switched on too.
ContactModel withMistake(ContactModel model, const ContactRow& mistake);
// `model` with the rows of `other` and its constants that differ from the course's too.
ContactModel combined(ContactModel model, const ContactModel& other, const ContactModel& course);

// Stub 3 or 4 as `model` computes it, in place.
void collideModel(Spheres<float>& spheres, Cloth<float>& cloth, bool sphere_sphere,
                  const ContactModel& model);
// "the course's collide without the position correction and with restitution 1"
std::string contactModelText(const ContactModel& model);

}  // namespace clothref::grader
