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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel;
  for (auto p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
  }
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = pos[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = vel[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel;
  for (auto p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
  }
  deltaTime = deltaTime / 2;  // midpoint = half step
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = pos[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = vel[i] + particles[i]->acceleration() * deltaTime;
  }
  deltaTime = 1e-4f;
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel, kx[4], kv[4];
  for (auto p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
    kx[0].push_back(p->velocity() * deltaTime);
    kv[0].push_back(p->acceleration() * deltaTime);
  }
  for (int k = 1; k < 4; ++k) {
    float scale = (k == 3) ? 1.0f : 0.5f;
    for (size_t i = 0; i < particles.size(); ++i) {
      particles[i]->position() = pos[i] + kx[k - 1][i] * scale;
      particles[i]->velocity() = vel[i] + kv[k - 1][i] * scale;
    }
    simulateOneStep();
    for (auto p : particles) {
      kx[k].push_back(p->velocity() * deltaTime);
      kv[k].push_back(p->acceleration() * deltaTime);
    }
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = pos[i] + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() = vel[i] + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
  }
}
