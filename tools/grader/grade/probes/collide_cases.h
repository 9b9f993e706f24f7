// The contacts the collision probes try (grader/grade/probes/collide.cpp): each case places a
// few bodies close together (an approaching pair, a separating one, several spheres, a sphere at
// index 2, a fixed particle, deep penetration, touching exactly, unequal masses), the rest of the
// 25 x 25 cloth parked far away; and the check tables, one row per case, then momentum.
#pragma once
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/submission/edition.h"

namespace clothref::grader::contacts {

inline constexpr int kN = 25;                          // particles per cloth edge
inline constexpr float kRadii[] = {0.5f, 0.5f, 1.0f};  // m: the three spheres

struct State {
  Cloth<float> cloth;
  Spheres<float> spheres;
};

// The library's stub on `s` with the course's restitution and position correction (the fraction
// of the overlap undone): the expected answer.
void collideCourse(State& s, bool sphere_sphere, float restitution, float correction);

// Rows of the check tables (checkTable()): one case each, then momentum over them all.
enum ClothCheck {
  kClothApproaching,
  kClothSeparating,
  kSeveralSpheres,
  kSphereAtIndex2,
  kFixedParticle,
  kClothDeep,
  kClothTouching,
  kClothMomentum
};
enum SphereCheck {
  kSpheresApproaching,
  kSpheresSeparating,
  kChain,
  kPairWithoutSphere0,
  kSpheresDeep,
  kSpheresTouching,
  kUnequalMasses,
  kSpheresMomentum
};

struct Case {
  int check;  // a row of the check table
  State state;
  std::vector<int> spheres, particles;  // the bodies the case places (for the report)
  bool free_bodies = true;              // momentum must be conserved
};

// On the edition's course cloth (its half extent, height and particle mass).
std::vector<Case> clothCases(const Edition& course);   // Spheres::collide(Cloth*)
std::vector<Case> sphereCases(const Edition& course);  // Spheres::collide()
std::vector<PlannedTest> checkTable(bool sphere_sphere);

// What a call left: every body's positions (m) and velocities (m/s), cloth then spheres.
struct Outcome {
  Mat4X<float> cloth_x, cloth_v, sphere_x, sphere_v;
};
Outcome outcomeOf(const State& s);

// Largest |a - b| / (1 + |b|) over every value (NaN counts as infinitely far).
double distance(const Outcome& a, const Outcome& b);

// The total momentum (kg m/s) of the case's bodies moving as in `o`.
Vec4<double> momentum(const State& s, const Outcome& o);

// How far the case's total momentum may move: 1e-5 of the momenta involved (float sums).
double momentumTolerance(const Case& c);

// Whether the call left the case's total momentum unchanged (within momentumTolerance).
bool conserves(const Case& c, const Outcome& after);

}  // namespace clothref::grader::contacts
