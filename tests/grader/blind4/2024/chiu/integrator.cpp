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
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
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
  // Write code here!
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = saved[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  // go to the middle
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = saved[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  std::vector<std::vector<Eigen::Matrix4Xf>> kx(4), kv(4);
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) {
      for (size_t i = 0; i < particles.size(); ++i) {
        particles[i]->position() = saved[i].position() + kx[stage - 1][i] * 0.5f;
        particles[i]->velocity() = saved[i].velocity() + kv[stage - 1][i] * 0.5f;
      }
      simulateOneStep();
    }
    for (auto *p : particles) {
      kx[stage].push_back(p->velocity() * deltaTime);
      kv[stage].push_back(p->acceleration() * deltaTime);
    }
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position() + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() = saved[i].velocity() + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
  }
}
