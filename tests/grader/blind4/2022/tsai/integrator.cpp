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
  // Write code here!
  // 1. backup
  std::vector<Particles *> backup = particles;
  // 2. explicit euler
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  // 3. x(n+1) = x(n) + v(n+1) dt
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i]->position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i]->velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
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
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Compute k1, k2, k3, k4.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  // Write code here!
  std::vector<Particles> backup, k1, k2, k3, k4;
  for (auto p : particles) backup.push_back(*p);
  k1 = k2 = k3 = k4 = backup;
  for (size_t i = 0; i < particles.size(); ++i) {
    k1[i].position() = particles[i]->velocity() * deltaTime;
    k1[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k1[i].position() / 2;
    particles[i]->velocity() = backup[i].velocity() + k1[i].velocity() / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k2[i].position() = particles[i]->velocity() * deltaTime;
    k2[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k2[i].position() / 2;
    particles[i]->velocity() = backup[i].velocity() + k2[i].velocity() / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k3[i].position() = particles[i]->velocity() * deltaTime;
    k3[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k3[i].position();
    particles[i]->velocity() = backup[i].velocity() + k3[i].velocity();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    k4[i].position() = particles[i]->velocity() * deltaTime;
    k4[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + (k1[i].position() + 2 * k2[i].position() + 2 * k3[i].position() + k4[i].position()) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (k1[i].velocity() + 2 * k2[i].velocity() + 2 * k3[i].velocity() + k4[i].velocity()) / 6.0f;
  }
}
