#include "integrator.h"

#include "configs.h"

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
  for (auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Particles> old;
  for (auto &p : particles) old.push_back(*p);
  for (auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Particles> old;
  for (auto &p : particles) old.push_back(*p);
  for (auto &p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Compute k1, k2, k3, k4.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Particles> old;
  for (auto &p : particles) old.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> kx1(n), kv1(n), kx2(n), kv2(n), kx3(n), kv3(n), kx4(n), kv4(n);
  for (size_t i = 0; i < n; i++) {
    kx1[i] = particles[i]->velocity() * deltaTime;
    kv1[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = old[i].position() + kx1[i] * 0.5f;
    particles[i]->velocity() = old[i].velocity() + kv1[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    kx2[i] = particles[i]->velocity() * deltaTime;
    kv2[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = old[i].position() + kx2[i] * 0.5f;
    particles[i]->velocity() = old[i].velocity() + kv2[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    kx3[i] = particles[i]->velocity() * deltaTime;
    kv3[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = old[i].position() + kx3[i] * 0.5f;
    particles[i]->velocity() = old[i].velocity() + kv3[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    kx4[i] = particles[i]->velocity() * deltaTime;
    kv4[i] = particles[i]->acceleration() * deltaTime;
  }
  // x = x0 + (k1 + 2 k2 + 2 k3 + k4) / 6
  for (size_t i = 0; i < n; i++) {
    particles[i]->position() = old[i].position() + (kx1[i] + kx4[i]) / 6 + (1 / 3) * (kx2[i] + kx3[i]);
    particles[i]->velocity() = old[i].velocity() + (kv1[i] + kv4[i]) / 6 + (1 / 3) * (kv2[i] + kv3[i]);
  }
}
