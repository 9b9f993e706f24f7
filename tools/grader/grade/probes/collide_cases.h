// The contacts the collision probes try (grader/grade/probes/collide.cpp): each case places a
// few bodies close together (an approaching pair, a separating one, several spheres, a sphere at
// index 2, a fixed particle, deep penetration, touching exactly, unequal masses), the rest of the
// 25 x 25 cloth parked far away; and the check tables, one row per case, then momentum.
#pragma once
#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/spheres.h"
#include "grader/grade/probes/probes.h"

namespace clothref::grader::contacts {

inline constexpr int kN = 25;                          // particles per cloth edge
inline constexpr float kRadii[] = {0.5f, 0.5f, 1.0f};  // m: the three spheres
inline constexpr float kCorrection = 0.15f;            // the course's position correction

struct State {
  Cloth<float> cloth;
  Spheres<float> spheres;
};

// The library's stub on `s`: the expected answer.
void collideCourse(State& s, bool sphere_sphere, float restitution);

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

std::vector<Case> clothCases(int edition);   // Spheres::collide(Cloth*)
std::vector<Case> sphereCases(int edition);  // Spheres::collide()
std::vector<PlannedTest> checkTable(bool sphere_sphere);

}  // namespace clothref::grader::contacts
