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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
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
  std::vector<Eigen::Matrix4Xf> x0, v0, k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  for (auto p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
    k1x.push_back(p->velocity() * deltaTime);
    k1v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + 0.5f * k1x[i];
    particles[i]->velocity() = v0[i] + 0.5f * k1v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k2x.push_back(particles[i]->velocity() * deltaTime);
    k2v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + 0.5f * k2x[i];
    particles[i]->velocity() = v0[i] + 0.5f * k2v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k3x.push_back(particles[i]->velocity() * deltaTime);
    k3v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k3x[i];
    particles[i]->velocity() = v0[i] + k3v[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k4x.push_back(particles[i]->velocity() * deltaTime);
    k4v.push_back(particles[i]->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + (1/6) * (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i]);
    particles[i]->velocity() = v0[i] + (1/6) * (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i]);
  }
}
