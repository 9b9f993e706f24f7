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
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> oldX, oldV;
  for (auto p : particles) {
    oldX.push_back(p->position());
    oldV.push_back(p->velocity());
  }
  // 先算速度再算位置
  for (auto p : particles) {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = oldX[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = oldV[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> oldX, oldV;
  for (auto p : particles) {
    oldX.push_back(p->position());
    oldV.push_back(p->velocity());
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = oldX[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = oldV[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> oldX(n), oldV(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  // k1 就是 v*dt 和 a*dt，直接用就好，不用另外存
  for (size_t i = 0; i < n; ++i) {
    oldX[i] = particles[i]->position();
    oldV[i] = particles[i]->velocity();
    particles[i]->position() = oldX[i] + particles[i]->velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = oldV[i] + particles[i]->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k2x[i] = particles[i]->velocity() * deltaTime;
    k2v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = oldX[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = oldV[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k3x[i] = particles[i]->velocity() * deltaTime;
    k3v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = oldX[i] + k3x[i];
    particles[i]->velocity() = oldV[i] + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = oldX[i] + (particles[i]->velocity() * deltaTime + 2 * k2x[i] + 2 * k3x[i] + k4x[i]) / 6;
    particles[i]->velocity() = oldV[i] + (particles[i]->acceleration() * deltaTime + 2 * k2v[i] + 2 * k3v[i] + k4v[i]) / 6;
  }
}
