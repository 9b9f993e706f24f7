#include "integrator.h"

#include "configs.h"

namespace {
// move one body forward by dt; the cloth hangs from its top edge, so keep that row still
void advance(Particles *p, float dt) {
  p->position() += p->velocity() * dt;
  p->velocity() += p->acceleration() * dt;
  if (p->getCapacity() == particlesPerEdge * particlesPerEdge) {
    for (int j = 0; j < particlesPerEdge; ++j) p->velocity(j).setZero();
  }
}
}  // namespace
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
    advance(p, deltaTime);
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() = x0.back() + v0.back() * deltaTime;
    p->velocity() = v0.back() + p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() = x0.back() + v0.back() * deltaTime * 0.5f;
    p->velocity() = v0.back() + p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  const size_t m = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(m), v0(m), k1x(m), k1v(m), k2x(m), k2v(m), k3x(m), k3v(m), k4x(m), k4v(m);
  for (size_t i = 0; i < m; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    k1x[i] = particles[i]->velocity() * deltaTime;
    k1v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k1x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k1v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < m; ++i) {
    k2x[i] = particles[i]->velocity() * deltaTime;
    k2v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k2x[i] * 0.5f;
    particles[i]->velocity() = v0[i] + k2v[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < m; ++i) {
    k3x[i] = particles[i]->velocity() * deltaTime;
    k3v[i] = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < m; ++i) {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
    // x1 = x0 + k1/6 + k2/3 + k3/3 + k4/6
    particles[i]->position() = x0[i] + k1x[i] / 6 + k2x[i] * (1 / 3) + k3x[i] * (1 / 3) + k4x[i] / 6;
    particles[i]->velocity() = v0[i] + k1v[i] / 6 + k2v[i] * (1 / 3) + k3v[i] * (1 / 3) + k4v[i] / 6;
  }
}
