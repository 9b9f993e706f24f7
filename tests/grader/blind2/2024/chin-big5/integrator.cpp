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
  for (auto p : particles) {
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
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  for (const auto *p : particles) backup.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
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
  // 每個物體分別做 RK4
  for (auto p : particles) {
    Particles x0 = *p;
    Eigen::Matrix4Xf k1x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k1v = p->acceleration() * deltaTime;
    p->position() = x0.position() + k1x * 0.5f;
    p->velocity() = x0.velocity() + k1v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k2x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k2v = p->acceleration() * deltaTime;
    p->position() = x0.position() + k2x * 0.5f;
    p->velocity() = x0.velocity() + k2v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k3x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k3v = p->acceleration() * deltaTime;
    p->position() = x0.position() + k3x;
    p->velocity() = x0.velocity() + k3v;
    simulateOneStep();
    Eigen::Matrix4Xf k4x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = p->acceleration() * deltaTime;
    // 加權平均
    p->position() = x0.position() + (k1x + 2 * k2x + 2 * k3x + k4x) / 6;
    p->velocity() = x0.velocity() + (k1v + 2 * k2v + 2 * k3v + k4v) / 6;
  }
}
