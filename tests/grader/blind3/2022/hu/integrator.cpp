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
    // Write code here!
    for (int i = 0; i < p->getCapacity(); ++i) {
      p->position(i) += p->velocity(i) * deltaTime;
      p->velocity(i) += p->acceleration(i) * deltaTime;
    }
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  // 1. backup
  std::vector<Particles *> saved(particles.begin(), particles.end());
  // 2. explicit euler
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  // 3. x(n+1) = x(n) + v(n+1) * dt, v(n+1) = v(n) + a(n+1) * dt
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = saved[k]->position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = saved[k]->velocity() + particles[k]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> start;
  for (auto *p : particles) start.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime / 2;
    p->velocity() += p->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = start[k].velocity() + particles[k]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> start, k1, k2, k3, k4;  // k stored as (dx, dv) in position / velocity
  for (auto *p : particles) {
    start.push_back(*p);
    Particles k = *p;
    k.position() = p->velocity() * deltaTime;
    k.velocity() = p->acceleration() * deltaTime;
    k1.push_back(k);
  }
  auto stage = [&](std::vector<Particles> &from, std::vector<Particles> &into, float h) {
    for (size_t b = 0; b < particles.size(); ++b) {
      particles[b]->position() = start[b].position() + from[b].position() * h;
      particles[b]->velocity() = start[b].velocity() + from[b].velocity() * h;
    }
    simulateOneStep();
    for (size_t b = 0; b < particles.size(); ++b) {
      Particles k = *particles[b];
      k.position() = particles[b]->velocity() * deltaTime;
      k.velocity() = particles[b]->acceleration() * deltaTime;
      into.push_back(k);
    }
  };
  stage(k1, k2, 0.5f);
  stage(k2, k3, 0.5f);
  stage(k3, k4, 1.0f);
  for (size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = start[b].position() + (k1[b].position() + 2 * k2[b].position() + 2 * k3[b].position() + k4[b].position()) / 6;
    particles[b]->velocity() = start[b].velocity() + (k1[b].velocity() + 2 * k2[b].velocity() + 2 * k3[b].velocity() + k4[b].velocity()) / 6;
  }
}
