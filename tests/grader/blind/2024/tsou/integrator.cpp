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
  for (size_t i = 0; i < particles.size(); ++i) {
    Particles *p = particles[i];
    Eigen::Matrix4Xf velocity = p->velocity();
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += velocity * deltaTime;
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
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + v0[i] * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  const float half = 0.5f * deltaTime;
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * half;
    particles[i]->position() = x0[i] + particles[i]->velocity() * half;
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
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  const size_t bodies = particles.size();
  std::vector<std::vector<Eigen::Matrix4Xf>> kx(4, std::vector<Eigen::Matrix4Xf>(bodies)), kv = kx;
  auto evaluate = [&](int stage) {
    for (size_t i = 0; i < bodies; ++i) {
      kx[stage][i] = particles[i]->velocity() * deltaTime;
      kv[stage][i] = particles[i]->acceleration() * deltaTime;
    }
  };
  auto moveTo = [&](int stage, float h) {
    for (size_t i = 0; i < bodies; ++i) {
      particles[i]->position() = backup[i].position() + kx[stage][i] * h;
      particles[i]->velocity() = backup[i].velocity() + kv[stage][i] * h;
    }
  };
  evaluate(0);
  moveTo(0, 0.5f);
  simulateOneStep();
  evaluate(1);
  moveTo(1, 0.5f);
  simulateOneStep();
  evaluate(2);
  moveTo(2, 1.0f);
  simulateOneStep();
  evaluate(3);
  for (size_t i = 0; i < bodies; ++i) {
    particles[i]->position() = backup[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
  }
}
