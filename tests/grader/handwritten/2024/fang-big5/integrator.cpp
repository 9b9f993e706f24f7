#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. You should do this first because it is very simple. Then you can check your collision is correct or not.
  //   3. This can be done in 5 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * (0.5f * deltaTime);
    p->velocity() += p->acceleration() * (0.5f * deltaTime);
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // 每個物體分開做 RK4
  for (auto p : particles) {
    Particles backup = *p;
    Eigen::Matrix4Xf k1x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k1v = p->acceleration() * deltaTime;

    p->position() = backup.position() + k1x * 0.5f;
    p->velocity() = backup.velocity() + k1v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k2x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k2v = p->acceleration() * deltaTime;

    p->position() = backup.position() + k2x * 0.5f;
    p->velocity() = backup.velocity() + k2v * 0.5f;
    simulateOneStep();
    Eigen::Matrix4Xf k3x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k3v = p->acceleration() * deltaTime;

    p->position() = backup.position() + k3x;
    p->velocity() = backup.velocity() + k3v;
    simulateOneStep();
    Eigen::Matrix4Xf k4x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = p->acceleration() * deltaTime;

    p->position() = backup.position() + (k1x + 2.0f * k2x + 2.0f * k3x + k4x) / 6.0f;
    p->velocity() = backup.velocity() + (k1v + 2.0f * k2v + 2.0f * k3v + k4v) / 6.0f;
  }
}
