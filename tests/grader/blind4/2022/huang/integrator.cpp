#include "integrator.h"
#include <vector>

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
  //   3. This can be done in 2 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (const auto &p : particles) {
    // Write code here!
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  int n = (int)particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (int i = 0; i < n; i++) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    k1x[i] = particles[i]->velocity() * deltaTime;
    k1v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k1x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (int i = 0; i < n; i++) {
    k2x[i] = particles[i]->velocity() * deltaTime;
    k2v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (int i = 0; i < n; i++) {
    k3x[i] = particles[i]->velocity() * deltaTime;
    k3v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  for (int i = 0; i < n; i++) {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
  }
  for (int i = 0; i < n; i++) {
    particles[i]->position() = x0[i] + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i]) * (1 / 6);
    particles[i]->velocity() = v0[i] + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i]) * (1 / 6);
  }
}
