#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. You should do this first because it is very simple. Then you can check your collision is correct or not.
  //   3. This can be done in 2 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    p->position() += (p->velocity() * deltaTime) * 0.5f;
    p->velocity() += (p->acceleration() * deltaTime) * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), k1v(n), k1a(n), k2v(n), k2a(n), k3v(n), k3a(n), k4v(n), k4a(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    k1v[i] = particles[i]->velocity();
    k1a[i] = particles[i]->acceleration();
  }
  deltaTime /= 2;  // half step for k2, k3
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + k1v[i] * deltaTime;
    particles[i]->velocity() = v0[i] + k1a[i] * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k2v[i] = particles[i]->velocity();
    k2a[i] = particles[i]->acceleration();
    particles[i]->position() = x0[i] + k2v[i] * deltaTime;
    particles[i]->velocity() = v0[i] + k2a[i] * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k3v[i] = particles[i]->velocity();
    k3a[i] = particles[i]->acceleration();
    particles[i]->position() = x0[i] + k3v[i] * deltaTime * 2;
    particles[i]->velocity() = v0[i] + k3a[i] * deltaTime * 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k4v[i] = particles[i]->velocity();
    k4a[i] = particles[i]->acceleration();
  }
  // average of the four slopes
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + (k1v[i] + k2v[i] + k3v[i] + k4v[i]) / 4 * deltaTime * 2;
    particles[i]->velocity() = v0[i] + (k1a[i] + k2a[i] + k3a[i] + k4a[i]) / 4 * deltaTime * 2;
  }
}
