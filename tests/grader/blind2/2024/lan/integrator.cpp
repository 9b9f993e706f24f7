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
  for (auto* p : particles) {
    auto x = p->position();
    auto v = p->velocity();
    auto a = p->acceleration();
    x += v * deltaTime;
    v += a * deltaTime;
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
  for (auto* p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
  }
  for (auto* p : particles) {
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
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto* p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
  }
  for (auto* p : particles) {
    p->position() += 0.5f * deltaTime * p->velocity();
    p->velocity() += 0.5f * deltaTime * p->acceleration();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
  }
  using Ks = std::vector<Eigen::Matrix4Xf>;
  Ks k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  auto evaluate = [&](Ks& kx, Ks& kv) {
    for (size_t i = 0; i < n; ++i) {
      kx[i] = particles[i]->velocity() * deltaTime;
      kv[i] = particles[i]->acceleration() * deltaTime;
    }
  };
  auto setStage = [&](const Ks& kx, const Ks& kv, float f) {
    for (size_t i = 0; i < n; ++i) {
      particles[i]->position() = x0[i] + kx[i] * f;
      particles[i]->velocity() = v0[i] + kv[i] * f;
    }
    simulateOneStep();
  };
  evaluate(k1x, k1v);
  setStage(k1x, k1v, 0.5f);
  evaluate(k2x, k2v);
  setStage(k2x, k2v, 0.5f);
  evaluate(k3x, k3v);
  setStage(k3x, k3v, 1.0f);
  evaluate(k4x, k4v);
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + (k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x[i]) / 6.0f;
    particles[i]->velocity() = v0[i] + (k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v[i]) / 6.0f;
  }
}
