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
  // Write code here!
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
  // TODO: Integrate velocity and acceleration.
  //   1. Back up the original particles' data.
  //   2. Integrate the velocity and the acceleration using explicit Euler to get Xn+1.
  //   3. Compute the refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with the modified position and velocity to get Xn+1.
  // Write code here!
  struct Saved {
    Eigen::Ref<Eigen::Matrix4Xf> x;
    Eigen::Ref<Eigen::Matrix4Xf> v;
  };
  std::vector<Saved> saved;
  for (auto p : particles) saved.push_back({p->position(), p->velocity()});
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = saved[i].x + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = saved[i].v + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> backup, k1, k2, k3;
  for (auto p : particles) backup.push_back(*p);
  k1 = backup; k2 = backup; k3 = backup;
  // k1
  for (size_t i = 0; i < particles.size(); i++) {
    k1[i].position() = particles[i]->velocity() * deltaTime;
    k1[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k1[i].position() * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + k1[i].velocity() * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    k2[i].position() = particles[i]->velocity() * deltaTime;
    k2[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k2[i].position() * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + k2[i].velocity() * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    k3[i].position() = particles[i]->velocity() * deltaTime;
    k3[i].velocity() = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + k3[i].position();
    particles[i]->velocity() = backup[i].velocity() + k3[i].velocity();
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf k4x = particles[i]->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = particles[i]->acceleration() * deltaTime;
    particles[i]->position() = backup[i].position() + (k1[i].position() + 2 * k2[i].position() + 2 * k3[i].position() + k4x) / 6;
    particles[i]->velocity() = backup[i].velocity() + (k1[i].velocity() + 2 * k2[i].velocity() + 2 * k3[i].velocity() + k4v) / 6;
  }
}
