#include "integrator.h"

#include "configs.h"
#include <array>

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
    p->position() += deltaTime * p->velocity();
    p->velocity() += deltaTime * p->acceleration();
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += deltaTime * particles[i]->velocity();
    particles[i]->velocity() += deltaTime * particles[i]->acceleration();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = v0[i] + deltaTime * particles[i]->acceleration();
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += deltaTime * particles[i]->velocity() / 2.0f;
    particles[i]->velocity() += deltaTime * particles[i]->acceleration() / 2.0f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = v0[i] + deltaTime * particles[i]->acceleration();
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
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  std::vector<std::array<Eigen::Matrix4Xf, 4>> kx(n), kv(n);
  const float stageScale[3] = {0.5f, 0.5f, 1.0f};
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    kx[i][0] = deltaTime * particles[i]->velocity();
    kv[i][0] = deltaTime * particles[i]->acceleration();
  }
  for (int s = 1; s < 4; ++s) {
    for (size_t i = 0; i < n; ++i) {
      particles[i]->position() = x0[i] + stageScale[s - 1] * kx[i][s - 1];
      particles[i]->velocity() = v0[i] + stageScale[s - 1] * kv[i][s - 1];
    }
    simulateOneStep();
    for (size_t i = 0; i < n; ++i) {
      kx[i][s] = deltaTime * particles[i]->velocity();
      kv[i][s] = deltaTime * particles[i]->acceleration();
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + (kx[i][0] + 2.0f * kx[i][1] + 2.0f * kx[i][2] + kx[i][3]) / 6.0f;
    particles[i]->velocity() = v0[i] + (kv[i][0] + 2.0f * kv[i][1] + 2.0f * kv[i][2] + kv[i][3]) / 6.0f;
  }
}
