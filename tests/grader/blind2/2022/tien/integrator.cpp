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
    for (int i = 0; i < p->getCapacity(); ++i) {
      p->position(i) += p->velocity(i) * deltaTime;
      p->velocity(i) += p->acceleration(i) * deltaTime;
    }
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
  std::vector<Particles> backup;
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    // new velocity first, then move with it
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
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
  const float half = deltaTime * 0.5f;
  std::vector<Particles> backup;
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->velocity() += p->acceleration() * half;
    p->position() += p->velocity() * half;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  std::vector<Particles> start;
  for (const auto *p : particles) start.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> sumX(n), sumV(n), kx(n), kv(n);
  auto derive = [&]() {
    for (size_t i = 0; i < n; ++i) {
      kx[i] = (particles[i]->velocity() * deltaTime).eval();
      kv[i] = (particles[i]->acceleration() * deltaTime).eval();
    }
  };
  auto moveTo = [&](float f) {
    for (size_t i = 0; i < n; ++i) {
      particles[i]->position() = start[i].position() + kx[i] * f;
      particles[i]->velocity() = start[i].velocity() + kv[i] * f;
    }
  };
  derive();
  for (size_t i = 0; i < n; ++i) {
    sumX[i] = kx[i];
    sumV[i] = kv[i];
  }
  moveTo(0.5f);
  simulateOneStep();
  derive();
  for (size_t i = 0; i < n; ++i) {
    sumX[i] += 2.0f * kx[i];
    sumV[i] += 2.0f * kv[i];
  }
  moveTo(0.5f);
  simulateOneStep();
  derive();
  for (size_t i = 0; i < n; ++i) {
    sumX[i] += 2.0f * kx[i];
    sumV[i] += 2.0f * kv[i];
  }
  moveTo(1.0f);
  simulateOneStep();
  derive();
  for (size_t i = 0; i < n; ++i) {
    sumX[i] += kx[i];
    sumV[i] += kv[i];
    particles[i]->position() = start[i].position() + sumX[i] / 6.0f;
    particles[i]->velocity() = start[i].velocity() + sumV[i] / 6.0f;
  }
}
