#include "integrator.h"
#include <algorithm>

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
  std::for_each(particles.begin(), particles.end(), [](Particles *p) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  });
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // velocity first, then move with the new velocity
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t i = 0; i < particles.size(); ++i) {
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
  // Write code here!
  const std::size_t m = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(m), v0(m), sumX(m), sumV(m), kx(m), kv(m);
  auto slopes = [&]() {
    for (std::size_t i = 0; i < m; ++i) {
      kx[i] = particles[i]->velocity() * deltaTime;
      kv[i] = particles[i]->acceleration() * deltaTime;
    }
  };
  auto moveTo = [&](float h) {
    for (std::size_t i = 0; i < m; ++i) {
      particles[i]->position() = x0[i] + kx[i] * h;
      particles[i]->velocity() = v0[i] + kv[i] * h;
    }
    simulateOneStep();
    slopes();
  };
  for (std::size_t i = 0; i < m; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
  }
  slopes();
  sumX = kx;
  sumV = kv;
  moveTo(0.5f);
  for (std::size_t i = 0; i < m; ++i) { sumX[i] += 2 * kx[i]; sumV[i] += 2 * kv[i]; }
  moveTo(0.5f);
  for (std::size_t i = 0; i < m; ++i) { sumX[i] += 2 * kx[i]; sumV[i] += 2 * kv[i]; }
  moveTo(1.0f);
  for (std::size_t i = 0; i < m; ++i) {
    particles[i]->position() = x0[i] + (sumX[i] + kx[i]) / 6;
    particles[i]->velocity() = v0[i] + (sumV[i] + kv[i]) / 6;
  }
}
