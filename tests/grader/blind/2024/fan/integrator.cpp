#include "integrator.h"

#include "configs.h"

// The spec says we can assume the sphere is stationary.
static void holdSphere(Particles *spheres) { spheres->velocity().setZero(); }

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Integrate the velocity.
  //   2. Integrate the acceleration.
  //   3. You should not compute the position using the acceleration, since some parts only update the
  //      velocity (e.g. impulses).
  // Note:
  //   1. You don't need the simulation function in explicit Euler.
  //   2. Do this first: it is very simple, and then you can check whether your collisions are correct.
  //   3. This can be done in 5 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  holdSphere(particles[1]);
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  Particles *cloth = particles[0];
  Particles *sphere = particles[1];
  auto clothX0 = cloth->position();
  auto clothV0 = cloth->velocity();
  auto sphereX0 = sphere->position();
  auto sphereV0 = sphere->velocity();
  // predict
  cloth->position() = clothX0 + clothV0 * deltaTime;
  cloth->velocity() = clothV0 + cloth->acceleration() * deltaTime;
  sphere->position() = sphereX0 + sphereV0 * deltaTime;
  sphere->velocity() = sphereV0 + sphere->acceleration() * deltaTime;
  simulateOneStep();
  // correct
  cloth->position() = clothX0 + cloth->velocity() * deltaTime;
  cloth->velocity() = clothV0 + cloth->acceleration() * deltaTime;
  sphere->position() = sphereX0 + sphere->velocity() * deltaTime;
  sphere->velocity() = sphereV0 + sphere->acceleration() * deltaTime;
  holdSphere(sphere);
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
  holdSphere(particles[1]);
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Compute k1, k2, k3, k4.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> kx1(n), kv1(n), kx2(n), kv2(n), kx3(n), kv3(n), kx4(n), kv4(n);
  for (size_t i = 0; i < n; ++i) {
    kx1[i] = particles[i]->velocity() * deltaTime;
    kv1[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + kx1[i] * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + kv1[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    kx2[i] = particles[i]->velocity() * deltaTime;
    kv2[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + kx2[i] * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + kv2[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    kx3[i] = particles[i]->velocity() * deltaTime;
    kv3[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + kx3[i];
    particles[i]->velocity() = backup[i].velocity() + kv3[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    kx4[i] = particles[i]->velocity() * deltaTime;
    kv4[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = backup[i].position() + (kx1[i] + 2.0f * kx2[i] + 2.0f * kx3[i] + kx4[i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (kv1[i] + 2.0f * kv2[i] + 2.0f * kv3[i] + kv4[i]) / 6.0f;
  }
  holdSphere(particles[1]);
}
