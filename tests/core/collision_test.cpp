// Collisions: the impact sweeps of verify.h (through World::step) pass, and the two collide stubs,
// called directly on prepared contacts, give the closed-form impact (analytic.h).
#include <gtest/gtest.h>

#include "clothref/core/spheres.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/verify.h"

namespace clothref {
namespace {

void expectAllPass(const std::vector<CheckRow>& rows) {
  ASSERT_FALSE(rows.empty());
  for (const CheckRow& row : rows)
    EXPECT_TRUE(row.pass) << row.check << " [" << precisionName(row.precision) << "]: expected "
                          << row.expected << ", observed " << row.observed << ", tolerance "
                          << row.tolerance;
}

TEST(ImpactSweep, SphereSphereConservesAndRestores) {
  const std::vector<CheckRow> rows = sphereSphereChecks();
  // per precision: 5 restitution rows + momentum, tangential, closed form, 2 energy rows
  EXPECT_EQ(rows.size(), 20u);
  expectAllPass(rows);
}

TEST(ImpactSweep, SphereClothConservesAndFixedParticlesAreImmovable) {
  const std::vector<CheckRow> rows = sphereClothChecks();
  // per precision: 10 rows as for two spheres + 4 for the fixed particle
  EXPECT_EQ(rows.size(), 28u);
  expectAllPass(rows);
}

Eigen::Vector3d xyz(const Vec4<double>& v) { return v.head<3>(); }

// Two overlapping spheres approaching obliquely; one call of the sphere-sphere stub.
TEST(CollideStub, SphereSphereGivesTheClosedFormImpactAndCorrection) {
  for (double e : {0.0, 0.5, 1.0}) {
    Spheres<double> spheres;
    spheres.particles = makeParticles<double>(0, 0);
    addSphere<double>(spheres, Vec4<double>(-0.45, 0.2, 0, 1), 0.5, 1000);
    addSphere<double>(spheres, Vec4<double>(0.45, 0, 0.1, 1), 0.5, 1000);
    setMass(spheres.particles, 1, 1250.0);
    spheres.particles.velocity.col(0) = Vec4<double>(1, 0.3, 0, 0);
    spheres.particles.velocity.col(1) = Vec4<double>(-2, 0, 0.4, 0);
    const Particles<double> before = spheres.particles;
    collide(spheres, e, 0.15);

    const Eigen::Vector3d offset = xyz(before.position.col(0)) - xyz(before.position.col(1));
    const Eigen::Vector3d n = offset.normalized();
    const ImpactVelocities expected =
        impactVelocities(125, xyz(before.velocity.col(0)), 1250, xyz(before.velocity.col(1)), n, e);
    EXPECT_LT((xyz(spheres.particles.velocity.col(0)) - expected.a).norm(), 1e-13) << "e " << e;
    EXPECT_LT((xyz(spheres.particles.velocity.col(1)) - expected.b).norm(), 1e-13) << "e " << e;
    // the correction 0.15 * penetration * n moves both, ignoring mass
    const Eigen::Vector3d shift = 0.15 * (1 - offset.norm()) * n;
    EXPECT_LT((xyz(spheres.particles.position.col(0)) - xyz(before.position.col(0)) - shift).norm(),
              1e-15);
    EXPECT_LT((xyz(spheres.particles.position.col(1)) - xyz(before.position.col(1)) + shift).norm(),
              1e-15);
  }
}

// A fixed particle inside the sphere: the sphere bounces as off a wall, the particle keeps its
// velocity; a free particle beside it gets the two-body impulse.
TEST(CollideStub, SphereClothTreatsFixedParticlesAsImmovable) {
  const double e = 0.5;
  Spheres<double> spheres;
  spheres.particles = makeParticles<double>(0, 0);
  addSphere<double>(spheres, Vec4<double>(0, 0, 0, 1), 0.5, 1000);
  spheres.particles.velocity.col(0) = Vec4<double>(0.3, -1, 0, 0);
  Cloth<double> cloth;
  cloth.particles = makeParticles<double>(1, 0);
  cloth.particles.position.col(0) = Vec4<double>(0.1, -0.45, 0.05, 1);
  const Particles<double> sphere_before = spheres.particles;
  collide(spheres, cloth, e, 0.0);
  EXPECT_EQ(cloth.particles.velocity.col(0), Vec4<double>::Zero());
  const Eigen::Vector3d n = (-xyz(cloth.particles.position.col(0))).normalized();
  const ImpactVelocities wall =
      impactVelocities(125, xyz(sphere_before.velocity.col(0)), 0, Eigen::Vector3d::Zero(), n, e);
  EXPECT_LT((xyz(spheres.particles.velocity.col(0)) - wall.a).norm(), 1e-14);

  // the same contact with a 2 kg particle
  spheres.particles = sphere_before;
  setMass(cloth.particles, 0, 2.0);
  cloth.particles.velocity.col(0) = Vec4<double>(0, 0.5, 0.2, 0);
  collide(spheres, cloth, e, 0.0);
  const ImpactVelocities pair = impactVelocities(125, xyz(sphere_before.velocity.col(0)), 2,
                                                 Eigen::Vector3d(0, 0.5, 0.2), n, e);
  EXPECT_LT((xyz(spheres.particles.velocity.col(0)) - pair.a).norm(), 1e-14);
  EXPECT_LT((xyz(cloth.particles.velocity.col(0)) - pair.b).norm(), 1e-14);
}

}  // namespace
}  // namespace clothref
