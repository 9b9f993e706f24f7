#include "integrator.h"

#include "configs.h"

// bonus: 旗子 (flag) — 最右邊那一排綁在旗桿上
void constraint(Particles* p) {
  for (int i = 0; i < 25; i++) {
    p->velocity(i * 25 + 24).setZero();
    p->acceleration(i * 25 + 24).setZero();
  }
}

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
  for (const auto& p : particles) {
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
  auto backup = particles;  // 備份
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = backup[i]->position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i]->velocity() + particles[i]->acceleration() * deltaTime;
  }
  constraint(particles[0]);
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
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
  constraint(particles[0]);
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Compute k1, k2, k3, k4.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  std::vector<Eigen::Matrix4Xf> x0, v0, k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  for (auto p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  // k1
  for (size_t i = 0; i < particles.size(); i++) {
    k1x.push_back(particles[i]->velocity() * deltaTime);
    k1v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k1x[i] / 2;
    particles[i]->velocity() = v0[i] + k1v[i] / 2;
  }
  simulateOneStep();
  // k2
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime / 2;
    k2x.push_back(particles[i]->velocity() * deltaTime);
    k2v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k2x[i] / 2;
  }
  simulateOneStep();
  // k3
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime / 2;
    k3x.push_back(particles[i]->velocity() * deltaTime);
    k3v.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k3x[i] / 2;
  }
  simulateOneStep();
  // k4
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
    k4x.push_back(particles[i]->velocity() * deltaTime);
    k4v.push_back(particles[i]->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i]) / 6;
    particles[i]->velocity() = v0[i] + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i]) / 6;
  }
  constraint(particles[0]);
}
