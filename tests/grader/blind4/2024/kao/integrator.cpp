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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0, a0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    a0.push_back(p->acceleration());
  }
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  // average of the slope at the start and at the end (more accurate)
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + (v0[i] + particles[i]->velocity()) * 0.5f * deltaTime;
    particles[i]->velocity() = v0[i] + (a0[i] + particles[i]->acceleration()) * 0.5f * deltaTime;
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
  for (auto p : particles) {
    Eigen::Matrix4Xf x0 = p->position();
    Eigen::Matrix4Xf v0 = p->velocity();
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
    simulateOneStep();
    p->position() = x0 + p->velocity() * deltaTime;
    p->velocity() = v0 + p->acceleration() * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> x0, v0, k1x, k1v, k2x, k2v, k3x, k3v;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    k1x.push_back(p->velocity() * deltaTime);
    k1v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + k1x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k2x.push_back(particles[i]->velocity() * deltaTime);
    k2v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k3x.push_back(particles[i]->velocity() * deltaTime);
    k3v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    Eigen::Matrix4Xf k4x = particles[i]->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x) / 6;
    particles[i]->velocity() = v0[i] + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v) / 6;
  }
}
