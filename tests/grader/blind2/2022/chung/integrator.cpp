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
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += deltaTime * p->velocity();
    p->velocity() += deltaTime * p->acceleration();
  }
  simulateOneStep();
  for (int i = 0; i < (int)particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = backup[i].velocity() + deltaTime * particles[i]->acceleration();
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
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += (1 / 2) * deltaTime * p->velocity();
    p->velocity() += (1 / 2) * deltaTime * p->acceleration();
  }
  simulateOneStep();
  for (int i = 0; i < (int)particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + deltaTime * particles[i]->velocity();
    particles[i]->velocity() = backup[i].velocity() + deltaTime * particles[i]->acceleration();
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
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  const int n = (int)particles.size();
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  for (int s = 0; s < 4; ++s) {
    if (s > 0) {
      float w = (s == 3) ? 1.0f : 0.5f;
      for (int i = 0; i < n; ++i) {
        particles[i]->position() = backup[i].position() + w * kx[s - 1][i];
        particles[i]->velocity() = backup[i].velocity() + w * kv[s - 1][i];
      }
      simulateOneStep();
    }
    for (int i = 0; i < n; ++i) {
      kx[s].push_back(deltaTime * particles[i]->velocity());
      kv[s].push_back(deltaTime * particles[i]->acceleration());
    }
  }
  for (int i = 0; i < n; ++i) {
    particles[i]->position() = backup[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
  }
  // std::cout << "rk4 done" << std::endl;
}
