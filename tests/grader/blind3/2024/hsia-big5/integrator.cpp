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
  std::vector<Eigen::Matrix4Xf> x0, v0, vNext;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  // 先用 explicit euler 算出 x(n+1), v(n+1)
  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf xn = x0[i] + v0[i] * deltaTime;
    Eigen::Matrix4Xf vn = v0[i] + particles[i]->acceleration() * deltaTime;
    particles[i]->position() = xn;
    particles[i]->velocity() = vn;
    vNext.push_back(vn);
  }
  simulateOneStep();
  // x(n+1) = x(n) + v(n+1) dt,  v(n+1) = v(n) + a(n+1) dt
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + vNext[i] * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + v0[i] * deltaTime * 0.5f;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0, k1x, k1v, k2x, k2v, k3x, k3v;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    k1x.push_back(p->velocity() * deltaTime);
    k1v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + k1x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (auto p : particles) {
    k2x.push_back(p->velocity() * deltaTime);
    k2v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (auto p : particles) {
    k3x.push_back(p->velocity() * deltaTime);
    k3v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  // k4 直接用現在的速度、加速度
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->velocity() = v0[i] + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + particles[i]->acceleration() * deltaTime) / 6;
    particles[i]->position() = x0[i] + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + particles[i]->velocity() * deltaTime) / 6;
  }
}
