// The course's formulas, written once (formula/course_formulas.h), against the course's own
// Eigen idiom on random states, bit for bit, in float and double: the external force of
// Shape::computeExternalForce, the spring force of
// Cloth::computeSpringForce and the contact of Spheres::collide as the instructor writes them
// (Eigen::Vector4 columns, norm(), normalize(), dot()), which is also the shape of the copies that
// must remain on the course side (the grader's driver and reference files, docs/design.md). And the
// grid topology's push order.
#include "clothref/formula/course_formulas.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <tuple>
#include <vector>

#include "test_util.h"

namespace clothref {
namespace {

template <typename T>
using Vector4 = Eigen::Matrix<T, 4, 1>;

template <typename T>
Vector4<T> courseSpringForce(const Vector4<T>& xs, const Vector4<T>& xe, const Vector4<T>& vs,
                             const Vector4<T>& ve, T rest, T springCoef, T damperCoef) {
  Vector4<T> d = xs - xe;
  const T length = d.norm();
  d.normalize();
  return d * (damperCoef * (vs - ve).dot(d) + springCoef * (length - rest));
}

template <typename T>
bool courseContact(Vector4<T>& xa, Vector4<T>& va, T inverseMassA, Vector4<T>& xb, Vector4<T>& vb,
                   T inverseMassB, T distance, T coefRestitution, T correction) {
  Vector4<T> normal = xa - xb;
  const T penetration = distance - normal.norm();
  if (penetration < 0) return false;
  normal.normalize();
  const T approach = (va - vb).dot(normal);
  if (approach < 0) {
    const Vector4<T> normalVelocity = normal * approach;
    const Vector4<T> impulse =
        (-(1 + coefRestitution) * normalVelocity) / (inverseMassB + inverseMassA);
    va += impulse * inverseMassA;
    vb -= impulse * inverseMassB;
  }
  const Vector4<T> c = (penetration * normal) * correction;
  xa += c;
  xb -= c;
  return true;
}

// Shape::computeExternalForce for one particle, as the course writes it.
template <typename T>
Vector4<T> courseExternalAcceleration(const Vector4<T>& velocity, T mass, T inverseMass,
                                      const Vector4<T>& gravity, T viscousCoef) {
  Vector4<T> acceleration;
  if (mass == 0) {
    acceleration.setZero();
  } else {
    acceleration = gravity;
    acceleration -= velocity * viscousCoef * inverseMass;
  }
  return acceleration;
}

template <typename T>
Vector4<T> randomColumn(std::mt19937& random, T scale, T w) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Vector4<T>(T(scale * u(random)), T(scale * u(random)), T(scale * u(random)), w);
}

template <typename T>
void expectSameBits(const Vector4<T>& a, const Vector4<T>& b, const char* what, int trial) {
  for (int k = 0; k < 4; ++k)
    ASSERT_EQ(test::bits(a[k]), test::bits(b[k])) << what << " lane " << k << " trial " << trial;
}

template <typename T>
class CourseFormulas : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(CourseFormulas, Precisions);

TYPED_TEST(CourseFormulas, ExternalAccelerationHasTheCoursesBitsOnRandomStates) {
  using T = TypeParam;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector4<T> v = randomColumn<T>(random, 3, 0), g = randomColumn<T>(random, 10, 0);
    const T mass = trial % 5 == 0 ? T(0) : T(0.1 + 3 * u(random));
    const T inverse = mass == T(0) ? T(0) : T(1) / mass, viscous = T(1e-3 * u(random));
    Vector4<T> a;
    formula::externalAcceleration(v.data(), mass, inverse, g.data(), viscous, a.data());
    expectSameBits<T>(a, courseExternalAcceleration<T>(v, mass, inverse, g, viscous),
                      "acceleration", trial);
  }
}

TYPED_TEST(CourseFormulas, SpringForceHasTheCoursesBitsOnRandomStates) {
  using T = TypeParam;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector4<T> xs = randomColumn<T>(random, 2, 1);
    // every fourth spring coincident or nearly so: the zero vector normalize() leaves alone
    const Vector4<T> xe = trial % 4 == 0 ? xs : randomColumn<T>(random, 2, 1);
    const Vector4<T> vs = randomColumn<T>(random, 3, 0);
    const Vector4<T> ve = randomColumn<T>(random, 3, 0);
    const T rest = T(0.5 * u(random)), ks = T(25000 * u(random)), kd = T(750 * u(random));
    Vector4<T> force;
    formula::springForce(xs.data(), xe.data(), vs.data(), ve.data(), rest, ks, kd, force.data());
    expectSameBits<T>(force, courseSpringForce<T>(xs, xe, vs, ve, rest, ks, kd), "force", trial);
  }
}

TYPED_TEST(CourseFormulas, ContactHasTheCoursesBitsOnRandomStates) {
  using T = TypeParam;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(0, 1);
  int contacts = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Vector4<T> xa = randomColumn<T>(random, 1, 1), va = randomColumn<T>(random, 2, 0);
    Vector4<T> xb = randomColumn<T>(random, 1, 1), vb = randomColumn<T>(random, 2, 0);
    if (trial % 8 == 0) xb = xa;  // coincident centres
    const T inverse_a = T(u(random)), inverse_b = trial % 5 == 0 ? T(0) : T(u(random));
    const T distance = T(1.5 * u(random));
    const T restitution = trial % 2 ? T(0) : T(0.8), correction = T(0.15);
    Vector4<T> cxa = xa, cva = va, cxb = xb, cvb = vb;
    const bool hit = formula::resolveContact(xa.data(), va.data(), inverse_a, xb.data(), vb.data(),
                                             inverse_b, distance, restitution, correction);
    const bool course_hit = courseContact<T>(cxa, cva, inverse_a, cxb, cvb, inverse_b, distance,
                                             restitution, correction);
    ASSERT_EQ(hit, course_hit) << trial;
    contacts += hit;
    expectSameBits<T>(xa, cxa, "x_a", trial);
    expectSameBits<T>(va, cva, "v_a", trial);
    expectSameBits<T>(xb, cxb, "x_b", trial);
    expectSameBits<T>(vb, cvb, "v_b", trial);
  }
  EXPECT_GT(contacts, 1000);  // the random states do reach the contact branch
}

TEST(CourseFormulas, GridSpringsInTheCoursesPushOrder) {
  std::vector<std::tuple<int, int, int>> springs;
  formula::forEachGridSpring(3,
                             [&](int family, int s, int e) { springs.emplace_back(family, s, e); });
  const std::vector<std::tuple<int, int, int>> expected = {
      {0, 0, 1}, {0, 1, 2}, {0, 3, 4}, {0, 4, 5}, {0, 6, 7}, {0, 7, 8},  // rows
      {1, 0, 3}, {1, 1, 4}, {1, 2, 5}, {1, 3, 6}, {1, 4, 7}, {1, 5, 8},  // columns
      {2, 0, 4}, {2, 1, 5}, {2, 3, 7}, {2, 4, 8},                        // shear down-right
      {3, 1, 3}, {3, 2, 4}, {3, 4, 6}, {3, 5, 7},                        // shear down-left
      {4, 0, 2}, {4, 3, 5}, {4, 6, 8},                                   // bend in rows
      {5, 0, 6}, {5, 1, 7}, {5, 2, 8}};                                  // bend in columns
  EXPECT_EQ(springs, expected);
  for (int n : {2, 25}) {
    int count = 0;
    formula::forEachGridSpring(n, [&](int, int, int) { ++count; });
    EXPECT_EQ(count, 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + (n > 2 ? 2 * n * (n - 2) : 0)) << n;
  }
}

}  // namespace
}  // namespace clothref
