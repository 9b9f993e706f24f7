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
  for (auto *p : particles) {
    // semi-implicit: new velocity first
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
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
  std::vector<Particles> x0;
  for (auto *p : particles) x0.push_back(*p);
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->velocity() = x0[k].velocity() + x0[k].acceleration() * deltaTime;
    particles[k]->position() = x0[k].position() + particles[k]->velocity() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = x0[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  std::vector<Particles> x0;
  for (auto *p : particles) x0.push_back(*p);
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k].position() + x0[k].velocity() * deltaTime * 0.5f;
    particles[k]->velocity() = x0[k].velocity() + x0[k].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = x0[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (size_t k = 0; k < n; ++k) {
    x0[k] = particles[k]->position();
    v0[k] = particles[k]->velocity();
  }
  // read the increments of the current state, then move every body to x0 + h k
  auto stage = [&](std::vector<Eigen::Matrix4Xf> &kx, std::vector<Eigen::Matrix4Xf> &kv, float h, bool move) {
    for (size_t k = 0; k < n; ++k) {
      kx[k] = particles[k]->velocity() * deltaTime;
      kv[k] = particles[k]->acceleration() * deltaTime;
      if (!move) continue;
      particles[k]->position() = x0[k] + kx[k] * h;
      particles[k]->velocity() = v0[k] + kv[k] * h;
    }
  };
  stage(k1x, k1v, 0.5f, true);
  simulateOneStep();
  stage(k2x, k2v, 0.5f, true);
  simulateOneStep();
  stage(k3x, k3v, 1.0f, true);
  simulateOneStep();
  stage(k4x, k4v, 0.0f, false);
  for (size_t k = 0; k < n; ++k) {
    particles[k]->position() = x0[k] + (k1x[k] + k4x[k] + 2.0f * (k2x[k] + k3x[k])) / 6.0f;
    particles[k]->velocity() = v0[k] + (k1v[k] + k4v[k] + 2.0f * (k2v[k] + k3v[k])) / 6.0f;
  }
}
