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
  std::vector<Particles> orig;
  for (const auto &p : particles) orig.push_back(*p);
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = orig[i].position() + orig[i].velocity() * deltaTime;
    particles[i]->velocity() = orig[i].velocity() + orig[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = orig[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = orig[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> orig;
  for (const auto &p : particles) orig.push_back(*p);
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = orig[i].position() + orig[i].velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = orig[i].velocity() + orig[i].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = orig[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = orig[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> orig;
  for (const auto &p : particles) orig.push_back(*p);
  const size_t bodies = particles.size();
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  // stage 1..4
  for (int s = 0; s < 4; ++s) {
    if (s > 0) simulateOneStep();
    for (size_t i = 0; i < bodies; ++i) {
      kx[s].push_back(particles[i]->velocity() * deltaTime);
      kv[s].push_back(particles[i]->acceleration() * deltaTime);
    }
    if (s == 3) break;
    float h = (s == 2) ? 1.0f : 0.5f;
    for (size_t i = 0; i < bodies; ++i) {
      particles[i]->position() = orig[i].position() + kx[s][i] * h;
      particles[i]->velocity() = orig[i].velocity() + kv[s][i] * h;
    }
  }
  // 每個質點: x = x0 + (k1 + 2k2 + 2k3 + k4) / 6
  for (size_t i = 0; i < bodies; ++i) {
    for (int j = 0; j < particles[i]->getCapacity(); ++j) {
      Eigen::Vector4f sumX, sumV;
      sumX += kx[0][i].col(j) + 2 * kx[1][i].col(j) + 2 * kx[2][i].col(j) + kx[3][i].col(j);
      sumV += kv[0][i].col(j) + 2 * kv[1][i].col(j) + 2 * kv[2][i].col(j) + kv[3][i].col(j);
      particles[i]->position(j) = orig[i].position(j) + sumX / 6;
      particles[i]->velocity(j) = orig[i].velocity(j) + sumV / 6;
    }
  }
}
