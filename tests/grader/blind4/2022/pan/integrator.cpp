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
    // x = x0 + v t + 1/2 a t^2
    p->position() += p->velocity() * deltaTime + p->acceleration() * deltaTime * deltaTime * 0.5f;
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
  std::vector<Particles> origin;
  for (const auto &p : particles) origin.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (unsigned i = 0; i < particles.size(); ++i) {
    particles[i]->position() = origin[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = origin[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> origin;
  for (const auto &p : particles) origin.push_back(*p);
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime / 2;
    p->velocity() += p->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  for (unsigned i = 0; i < particles.size(); ++i) {
    particles[i]->position() = origin[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = origin[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> origin, k1, k2, k3, k4;
  for (const auto &p : particles) origin.push_back(*p);
  auto derive = [&](std::vector<Particles> &k) {
    k = origin;
    for (unsigned i = 0; i < particles.size(); ++i) {
      k[i].position() = particles[i]->velocity() * deltaTime;
      k[i].velocity() = particles[i]->acceleration() * deltaTime;
    }
  };
  auto jump = [&](std::vector<Particles> &k, float h) {
    for (unsigned i = 0; i < particles.size(); ++i) {
      particles[i]->position() = origin[i].position() + k[i].position() * h;
      particles[i]->velocity() = origin[i].velocity() + k[i].velocity() * h;
    }
    simulateOneStep();
  };
  derive(k1);
  jump(k1, 0.5f);
  derive(k2);
  jump(k2, 0.5f);
  derive(k3);
  jump(k3, 1.0f);
  derive(k4);
  for (unsigned i = 0; i < particles.size(); ++i) {
    particles[i]->position() = origin[i].position() + (k1[i].position() + 2 * k2[i].position() + 2 * k3[i].position() + k4[i].position()) / 6;
    particles[i]->velocity() = origin[i].velocity() + (k1[i].velocity() + 2 * k2[i].velocity() + 2 * k3[i].velocity() + k4[i].velocity()) / 6;
  }
}
