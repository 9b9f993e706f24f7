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
  for (Particles *body : particles) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(body->getCapacity()); ++i) {
      body->position(static_cast<int>(i)) += body->velocity(static_cast<int>(i)) * deltaTime;
      body->velocity(static_cast<int>(i)) += body->acceleration(static_cast<int>(i)) * deltaTime;
    }
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Backward Euler, one fixed-point iteration:
  //   v1 = v0 + a(x~) dt, then x1 = x0 + v1 dt (the new velocity)
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *body : particles) {
    x0.emplace_back(body->position());
    v0.emplace_back(body->velocity());
  }
  for (std::size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + v0[b] * deltaTime;
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b) {
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * deltaTime;
    particles[b]->position() = x0[b] + particles[b]->velocity() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *body : particles) {
    x0.emplace_back(body->position());
    v0.emplace_back(body->velocity());
  }
  for (std::size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + v0[b] * deltaTime * 0.5f;
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // sumX / sumV collect k1 + 2 k2 + 2 k3 + k4 as we go
  std::vector<Eigen::Matrix4Xf> x0, v0, kx, kv, sumX, sumV;
  for (Particles *body : particles) {
    x0.emplace_back(body->position());
    v0.emplace_back(body->velocity());
    kx.emplace_back(body->velocity() * deltaTime);
    kv.emplace_back(body->acceleration() * deltaTime);
  }
  sumX = kx;
  sumV = kv;
  const float stepScale[3] = {0.5f, 0.5f, 1.0f};
  const float weight[3] = {2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 3; ++stage) {
    for (std::size_t b = 0; b < particles.size(); ++b) {
      particles[b]->position() = x0[b] + kx[b] * stepScale[stage];
      particles[b]->velocity() = v0[b] + kv[b] * stepScale[stage];
    }
    simulateOneStep();
    for (std::size_t b = 0; b < particles.size(); ++b) {
      kx[b] = particles[b]->velocity() * deltaTime;
      kv[b] = particles[b]->acceleration() * deltaTime;
      sumX[b] += weight[stage] * kx[b];
      sumV[b] += weight[stage] * kv[b];
    }
  }
  for (std::size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + sumX[b] / 6.0f;
    particles[b]->velocity() = v0[b] + sumV[b] / 6.0f;
  }
}
