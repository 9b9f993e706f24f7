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
  //   3. This can be done in 2 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (const auto &p : particles) {
    // Write code here!
    p->position() += deltaTime * p->velocity();
    p->velocity() += deltaTime * p->acceleration();
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel;
  for (const auto &p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
    p->position() += deltaTime * p->velocity();
    p->velocity() += deltaTime * p->acceleration();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = pos[i] + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = vel[i] + deltaTime * particles[i]->acceleration();
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel;
  for (const auto &p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
    // 走半步
    p->position() += deltaTime * (1 / 2) * p->velocity();
    p->velocity() += deltaTime * (1 / 2) * p->acceleration();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = pos[i] + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = vel[i] + deltaTime * particles[i]->acceleration();
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> pos, vel;
  std::vector<Eigen::Matrix4Xf> k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  auto moveTo = [&](const std::vector<Eigen::Matrix4Xf> &dx, const std::vector<Eigen::Matrix4Xf> &dv, float scale) {
    for (size_t i = 0; i < particles.size(); i++) {
      particles[i]->position() = pos[i] + dx[i] * scale;
      particles[i]->velocity() = vel[i] + dv[i] * scale;
    }
  };
  auto grab = [&](std::vector<Eigen::Matrix4Xf> &kx, std::vector<Eigen::Matrix4Xf> &kv) {
    kx.clear();
    kv.clear();
    for (const auto &p : particles) {
      kx.push_back(p->velocity() * deltaTime);
      kv.push_back(p->acceleration() * deltaTime);
    }
  };
  for (const auto &p : particles) {
    pos.push_back(p->position());
    vel.push_back(p->velocity());
  }
  grab(k1x, k1v);
  moveTo(k1x, k1v, 0.5f);
  simulateOneStep();
  grab(k2x, k2v);
  moveTo(k2x, k2v, 0.5f);
  simulateOneStep();
  grab(k3x, k3v);
  moveTo(k3x, k3v, 1.0f);
  simulateOneStep();
  grab(k4x, k4v);
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = pos[i] + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i]) / 6;
    particles[i]->velocity() = vel[i] + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i]) / 6;
  }
}
