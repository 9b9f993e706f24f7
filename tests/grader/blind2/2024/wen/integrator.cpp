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
  for (auto p : particles) {
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
  std::vector<Particles> backup;
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  std::vector<Particles> backup;
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  std::vector<Particles> init;
  for (auto p : particles) init.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (size_t i = 0; i < n; i++) {
    k1x[i] = particles[i]->velocity() * deltaTime;
    k1v[i] = particles[i]->acceleration() * deltaTime;
  }
  // k2: state at t + dt/2
  for (size_t i = 0; i < n; i++) {
    particles[i]->velocity() = init[i].velocity() + k1v[i] * 0.5f;
    particles[i]->position() = init[i].position() + particles[i]->velocity() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    k2x[i] = particles[i]->velocity() * deltaTime;
    k2v[i] = particles[i]->acceleration() * deltaTime;
  }
  // k3
  for (size_t i = 0; i < n; i++) {
    particles[i]->velocity() = init[i].velocity() + k2v[i] * 0.5f;
    particles[i]->position() = init[i].position() + particles[i]->velocity() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    k3x[i] = particles[i]->velocity() * deltaTime;
    k3v[i] = particles[i]->acceleration() * deltaTime;
  }
  // k4: state at t + dt
  for (size_t i = 0; i < n; i++) {
    particles[i]->velocity() = init[i].velocity() + k3v[i];
    particles[i]->position() = init[i].position() + particles[i]->velocity() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; i++) {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; i++) {
    particles[i]->position() = init[i].position() + (k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x[i]) / 6.0f;
    particles[i]->velocity() = init[i].velocity() + (k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v[i]) / 6.0f;
  }
}
