// The whole run's course side: the course's main loop on its default scene, every stub the
// student's.
// Included into probe_driver.cpp's one translation unit (driver_support.h says why), whose dispatch
// calls its function by the group's name.
#pragma once
#include "grader/driver/driver_support.h"

namespace {

// The course's main loop on its default scene, with every stub the student's.
void probeWholeRun(const ProbeMessage& in, ProbeMessage& out) {
  const Integrator& integrator = integratorFor(in.scalarInt(key::kMethod));
  Cloth cloth;
  Spheres& spheres = Spheres::initSpheres();
#ifdef CLOTHREF_GRADER_EDITION_2024
  spheres.addSphere(Eigen::Vector4f(0, 0, 0, 1), 1.0f);
#else
  spheres.addSphere(Eigen::Vector4f(-0.75f, 1, -0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(0.75f, 1, -0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(-0.75f, 1, 0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(0.75f, 1, 0.75f, 1), 0.5f);
#endif
  deltaTime = in.scalar(key::kDt, 1e-4f);
  const std::int64_t steps = in.scalarInt(key::kSteps, 100);
  const std::int64_t stride = std::max<std::int64_t>(1, in.scalarInt(key::kStride, 10));
  std::vector<Particles*> particles{&cloth.particles(), &spheres.particles()};
  std::function<void(void)> simulateOneStep = [&] {
    cloth.computeExternalForce();
#ifdef CLOTHREF_GRADER_EDITION_2024
    cloth.computeSpringForce();
    spheres.collide(&cloth);
#else
    spheres.computeExternalForce();
    cloth.computeSpringForce();
    spheres.collide(&cloth);
    spheres.collide();
#endif
  };
  std::vector<float> clothX, clothV, sphereX, sphereV;
  auto record = [&] {
    for (auto [from, to] :
         {std::pair{&cloth.particles(), &clothX}, std::pair{&spheres.particles(), &sphereX}}) {
      auto x = save(from->position());
      to->insert(to->end(), x.begin(), x.end());
    }
    for (auto [from, to] :
         {std::pair{&cloth.particles(), &clothV}, std::pair{&spheres.particles(), &sphereV}}) {
      auto v = save(from->velocity());
      to->insert(to->end(), v.begin(), v.end());
    }
  };
  record();
  for (std::int64_t step = 1; step <= steps; ++step) {
#ifdef CLOTHREF_GRADER_EDITION_2024
    // the 2024 main loop's per-frame work (docs/course.md §3), every 40 steps (a 60 Hz frame):
    // re-pin the corners, then spheres.setVelocity(0, 0), as clothref's course2024 does
    if ((step - 1) % 40 == 0) {
      constexpr int n = particlesPerEdge;
      for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) {
        cloth.particles().mass(corner) = 0.0f;
        cloth.particles().velocity(corner).setZero();
        cloth.particles().acceleration(corner).setZero();
      }
      spheres.setVelocity(0, Eigen::Vector4f::Zero());
    }
#endif
    simulateOneStep();
    integrator.integrate(particles, simulateOneStep);
    if (step % stride == 0 || step == steps) record();
  }
  out.floats[key::kClothPos] = clothX;
  out.floats[key::kClothVel] = clothV;
  out.floats[key::kSpherePos] = sphereX;
  out.floats[key::kSphereVel] = sphereV;
  out.ints[key::kSphereCapacity] = {spheres.particles().getCapacity()};
}

}  // namespace
