// Spheres: rigid balls that hit the cloth and each other. Stubs 3 and 4 of the course live here:
//   collide(spheres, cloth)  sphere-cloth contact (course restitution 0)
//   collide(spheres)         sphere-sphere contact, pairs i < j (course restitution 0.8)
// Both apply an impulse along the contact normal only while the bodies approach, then always the
// course's position correction c = correction * penetration * normal on both bodies.
#pragma once

#include <vector>

#include "clothref/core/cloth.h"
#include "clothref/core/particles.h"

namespace clothref {

// The spheres of a scene; particle i is the centre of sphere i.
//   radius  N, metres
template <typename T>
struct Spheres {
  Particles<T> particles;
  std::vector<T> radius;

  int size() const { return particles.size(); }
};

// The course's Spheres::addSphere: appends a sphere at `center` (w = 1) at rest, with mass
// density * r^3 evaluated as ((density * r) * r) * r (the course's formula, not 4/3 pi r^3).
template <typename T>
void addSphere(Spheres<T>& spheres, const Vec4<T>& center, T radius, T density);

// Stub 3, the course's Spheres::collide(Cloth*): for each sphere i and each cloth particle j,
// n = x_i - x_j, penetration p = r_i - |n|; skip when p < 0 (touching counts). With n normalized
// and v_rel = v_i - v_j: if v_rel . n < 0, the normal velocity u = n * (v_rel . n) is formed first
// and then scaled, J = (-(1 + e) * u) / (invM_j + invM_i) (the course's association order, which
// rounds differently from (-(1 + e) * n) * (v_rel . n) in float: docs/design.md, "Fidelity through
// contacts"), v_i += J * invM_i, v_j -= J * invM_j. Then, always, c = (p * n) * correction:
// x_i += c, x_j -= c.
// A fixed particle (invM 0) is immovable in the impulse; the correction ignores mass. The contact
// is formula::resolveContact (formula/course_formulas.h). With the fast kernels on (the default,
// any cloth) World's step runs its twin instead: fast::collideSpheresWithCloth, a SIMD filter that
// skips far pairs, then the same formula::resolveContact, proven bit-equal by
// SphereClothContacts.* (tests/fast/sphere_cloth_contacts_test.cpp), WorldEquivalence.* and
// verify's course-form rows.
template <typename T>
void collide(Spheres<T>& spheres, Cloth<T>& cloth, T restitution, T correction);

// Stub 4, the course's Spheres::collide(): the same contact between spheres i < j, with
// n = x_i - x_j and p = r_i + r_j - |n|. No fast twin: this stub itself runs.
template <typename T>
void collide(Spheres<T>& spheres, T restitution, T correction);

}  // namespace clothref
