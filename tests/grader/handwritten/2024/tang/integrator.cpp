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
  //   3. This can be done in 5 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
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
  std::vector<Particles> start;
  for (const auto &p : particles) start.emplace_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> start;
  for (const auto &p : particles) start.emplace_back(*p);
  // const float h = deltaTime * 0.5f;
  const float h = deltaTime;  // half step looks jittery, use a full step
  for (const auto &p : particles) {
    p->position() += p->velocity() * h;
    p->velocity() += p->acceleration() * h;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  // backup of x0 / v0
  std::vector<Eigen::Ref<Eigen::Matrix4Xf>> x0, v0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (size_t i = 0; i < n; ++i) {
    k1x[i] = particles[i]->velocity() * deltaTime;
    k1v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k1x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k2x[i] = particles[i]->velocity() * deltaTime;
    k2v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k3x[i] = particles[i]->velocity() * deltaTime;
    k3v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + (k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x[i]) / 6.0f;
    particles[i]->velocity() = v0[i] + (k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v[i]) / 6.0f;
  }
}
