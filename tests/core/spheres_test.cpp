#include "clothref/core/spheres.h"

#include <gtest/gtest.h>

namespace clothref {
namespace {

// One sphere (r = 0.5, 125 kg) above one cloth particle, in double.
struct Contact {
  Spheres<double> spheres;
  Cloth<double> cloth;

  Contact(double gap, double sphere_vy, double particle_mass) {
    spheres.particles = makeParticles<double>(0, 0.0);
    addSphere(spheres, Vec4<double>(0, 0.5 + gap, 0, 1), 0.5, 1000.0);
    spheres.particles.velocity(1, 0) = sphere_vy;
    cloth.particles = makeParticles<double>(1, particle_mass);
  }
};

TEST(AddSphere, MassIsDensityTimesRadiusCubed) {
  Spheres<float> spheres;
  spheres.particles = makeParticles<float>(0, 0.0f);
  addSphere(spheres, Vec4<float>(0, 1, 0, 1), 0.5f, 1000.0f);
  addSphere(spheres, Vec4<float>(0, 0, 0, 1), 1.0f, 1000.0f);
  EXPECT_EQ(spheres.particles.mass[0], 125.0f);
  EXPECT_EQ(spheres.particles.mass[1], 1000.0f);
  EXPECT_EQ(spheres.radius, (std::vector<float>{0.5f, 1.0f}));
  EXPECT_EQ(spheres.particles.velocity.col(0), Vec4<float>::Zero());
}

TEST(CollideSphereCloth, SeparatedPairIsUntouched) {
  Contact c(1e-9, -1.0, 1.0);
  const auto sphere = c.spheres.particles;
  collide(c.spheres, c.cloth, 0.0, 0.15);
  EXPECT_EQ(c.spheres.particles.position, sphere.position);
  EXPECT_EQ(c.spheres.particles.velocity, sphere.velocity);
}

TEST(CollideSphereCloth, TouchingCountsAndRestitutionZeroStopsTheNormalMotion) {
  Contact c(0.0, -2.0, 1.0);  // distance exactly r: penetration 0 is a collision
  collide(c.spheres, c.cloth, 0.0, 0.15);
  // e = 0: both move with the centre-of-mass normal velocity afterwards
  const double common = 125.0 * -2.0 / 126.0;
  EXPECT_NEAR(c.spheres.particles.velocity(1, 0), common, 1e-12);
  EXPECT_NEAR(c.cloth.particles.velocity(1, 0), common, 1e-12);
}

TEST(CollideSphereCloth, NoImpulseWhenSeparatingButCorrectionAlways) {
  Contact c(-0.1, +1.0, 1.0);  // 0.1 m penetration, sphere already moving away
  collide(c.spheres, c.cloth, 0.0, 0.15);
  EXPECT_EQ(c.spheres.particles.velocity(1, 0), 1.0);
  EXPECT_EQ(c.cloth.particles.velocity(1, 0), 0.0);
  // c = 0.15 * p * n with n from the particle to the sphere (+y): sphere up, particle down
  EXPECT_NEAR(c.spheres.particles.position(1, 0), 0.4 + 0.015, 1e-12);
  EXPECT_NEAR(c.cloth.particles.position(1, 0), -0.015, 1e-12);
}

TEST(CollideSphereCloth, FixedParticleIsImmovableInTheImpulseButCorrected) {
  Contact c(-0.1, -2.0, 0.0);
  setMass(c.cloth.particles, 0, 0.0);
  collide(c.spheres, c.cloth, 0.0, 0.15);
  EXPECT_NEAR(c.spheres.particles.velocity(1, 0), 0.0, 1e-15);  // e = 0 against a wall
  EXPECT_EQ(c.cloth.particles.velocity(1, 0), 0.0);
  EXPECT_NEAR(c.cloth.particles.position(1, 0), -0.015, 1e-12);  // the correction ignores mass
}

TEST(CollideSphereSphere, EachPairOnceWithRestitution) {
  Spheres<double> s;
  s.particles = makeParticles<double>(0, 0.0);
  addSphere(s, Vec4<double>(-0.5, 0, 0, 1), 0.5, 1000.0);
  addSphere(s, Vec4<double>(0.5, 0, 0, 1), 0.5, 1000.0);
  addSphere(s, Vec4<double>(10, 0, 0, 1), 0.5, 1000.0);
  s.particles.velocity(0, 0) = 1.0;
  s.particles.velocity(0, 1) = -1.0;
  collide(s, 0.8, 0.15);
  // equal masses: velocities swap, scaled by e (applied once, not twice)
  EXPECT_NEAR(s.particles.velocity(0, 0), -0.8, 1e-12);
  EXPECT_NEAR(s.particles.velocity(0, 1), 0.8, 1e-12);
  EXPECT_EQ(s.particles.velocity(0, 2), 0.0);
}

}  // namespace
}  // namespace clothref
