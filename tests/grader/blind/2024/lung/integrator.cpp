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
  for (Particles *p : particles) {
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (Particles *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  for (Particles *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (Particles *p : particles) {
    p->position() += p->velocity() * (deltaTime / 2);
    p->velocity() += p->acceleration() * (deltaTime / 2);
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + v0[i] * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> x0, v0, a0;
  for (Particles *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    a0.push_back(p->acceleration());
  }
  std::vector<Eigen::Matrix4Xf> k1, k2, k3, k4;  // position increments
  std::vector<Eigen::Matrix4Xf> l1, l2, l3, l4;  // velocity increments
  for (size_t i = 0; i < particles.size(); i++) {
    k1.push_back(v0[i] * deltaTime);
    l1.push_back(a0[i] * deltaTime);
    particles[i]->position() = x0[i] + k1[i] / 2;
    particles[i]->velocity() = v0[i] + l1[i] / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    k2.push_back(particles[i]->velocity() * deltaTime);
    l2.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k2[i] / 2;
    particles[i]->velocity() = v0[i] + l2[i] / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    k3.push_back(particles[i]->velocity() * deltaTime);
    l3.push_back(particles[i]->acceleration() * deltaTime);
    particles[i]->position() = x0[i] + k3[i];
    particles[i]->velocity() = v0[i] + l3[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    k4.push_back(particles[i]->velocity() * deltaTime);
    l4.push_back(particles[i]->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + k1[i];
    particles[i]->velocity() = v0[i] + a0[i] * deltaTime;
    // particles[i]->position() = x0[i] + (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]) / 6;
    // particles[i]->velocity() = v0[i] + (l1[i] + 2 * l2[i] + 2 * l3[i] + l4[i]) / 6;
  }
}
