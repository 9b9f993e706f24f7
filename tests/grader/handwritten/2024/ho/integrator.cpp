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
  std::vector<Particles> prev;
  for (const auto &p : particles) prev.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = prev[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = prev[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  const float h = deltaTime / 2;  // midpoint: h = dt / 2
  std::vector<Particles> prev;
  for (const auto &p : particles) prev.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * h;
    p->velocity() += p->acceleration() * h;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = prev[i].position() + particles[i]->velocity() * h;
    particles[i]->velocity() = prev[i].velocity() + particles[i]->acceleration() * h;
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
  std::vector<Particles> prev;
  for (const auto &p : particles) prev.push_back(*p);
  std::vector<Eigen::Matrix4Xf> k1x, k1v, k2x, k2v, k3x, k3v;
  for (size_t i = 0; i < particles.size(); ++i) {
    k1x.push_back(particles[i]->velocity() * deltaTime);
    k1v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = prev[i].position() + k1x[i] * 0.5f;
    particles[i]->velocity() = prev[i].velocity() + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k2x.push_back(particles[i]->velocity() * deltaTime);
    k2v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = prev[i].position() + k2x[i] * 0.5f;
    particles[i]->velocity() = prev[i].velocity() + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k3x.push_back(particles[i]->velocity() * deltaTime);
    k3v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = prev[i].position() + k3x[i];
    particles[i]->velocity() = prev[i].velocity() + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    Eigen::Matrix4Xf k4x = particles[i]->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = prev[i].position() + (k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x) / 6.0f;
    particles[i]->velocity() = prev[i].velocity() + (k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v) / 6.0f;
  }
}
