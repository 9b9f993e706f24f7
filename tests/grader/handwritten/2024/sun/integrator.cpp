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
  for (const auto &p : particles) {
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
  std::vector<Particles> backup(particles.size());
  for (size_t i = 0; i < particles.size(); ++i) backup[i] = *particles[i];
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
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
  for (const auto &p : particles) backup.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
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
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> dx1(n), dv1(n), dx2(n), dv2(n), dx3(n), dv3(n), dx4(n), dv4(n);
  for (size_t i = 0; i < n; ++i) {
    dx1[i] = particles[i]->velocity();
    dv1[i] = particles[i]->acceleration();
  }
  deltaTime /= 2;  // stages 2 and 3 are half steps
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = backup[i].position() + dx1[i] * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + dv1[i] * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx2[i] = particles[i]->velocity();
    dv2[i] = particles[i]->acceleration();
    particles[i]->position() = backup[i].position() + dx2[i] * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + dv2[i] * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx3[i] = particles[i]->velocity();
    dv3[i] = particles[i]->acceleration();
    particles[i]->position() = backup[i].position() + dx3[i] * deltaTime * 2;
    particles[i]->velocity() = backup[i].velocity() + dv3[i] * deltaTime * 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx4[i] = particles[i]->velocity();
    dv4[i] = particles[i]->acceleration();
  }
  for (size_t i = 0; i < n; ++i) {
    // (h / 6) with h = 2 * deltaTime
    particles[i]->position() = backup[i].position() + (dx1[i] + 2 * dx2[i] + 2 * dx3[i] + dx4[i]) * deltaTime / 3;
    particles[i]->velocity() = backup[i].velocity() + (dv1[i] + 2 * dv2[i] + 2 * dv3[i] + dv4[i]) * deltaTime / 3;
    deltaTime *= 2;  // restore
  }
}
