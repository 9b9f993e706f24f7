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
    // x(t + dt) = x + v dt + 1/2 a dt^2
    p->position() += p->velocity() * deltaTime + 0.5f * p->acceleration() * deltaTime * deltaTime;
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
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime * 0.5f;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime * 0.5f;
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
  std::vector<Particles> backup;
  for (const auto *p : particles) backup.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (size_t k = 0; k < n; ++k) {
    k1x[k] = particles[k]->velocity() * deltaTime;
    k1v[k] = particles[k]->acceleration() * deltaTime;
    particles[k]->position() = backup[k].position() + k1x[k] * 0.5f;
    particles[k]->velocity() = backup[k].velocity() + k1v[k] * 0.5f;
  }
  simulateOneStep();
  for (size_t k = 0; k < n; ++k) {
    k2x[k] = particles[k]->velocity() * deltaTime;
    k2v[k] = particles[k]->acceleration() * deltaTime;
    particles[k]->position() = backup[k].position() + k2x[k] * 0.5f;
    particles[k]->velocity() = backup[k].velocity() + k2v[k] * 0.5f;
  }
  simulateOneStep();
  for (size_t k = 0; k < n; ++k) {
    k3x[k] = particles[k]->velocity() * deltaTime;
    k3v[k] = particles[k]->acceleration() * deltaTime;
    particles[k]->position() = backup[k].position() + k3x[k];
    particles[k]->velocity() = backup[k].velocity() + k3v[k];
  }
  simulateOneStep();
  for (size_t k = 0; k < n; ++k) {
    k4x[k] = particles[k]->velocity() * deltaTime;
    k4v[k] = particles[k]->acceleration() * deltaTime;
    particles[k]->position() = backup[k].position() + (k1x[k] + 2.0f * k2x[k] + 2.0f * k3x[k] + k4x[k]) / 6.0f;
    particles[k]->velocity() = backup[k].velocity() + (k1v[k] + 2.0f * k2v[k] + 2.0f * k3v[k] + k4v[k]) / 6.0f;
  }
}
