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
  // Write code here!
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
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
  // Write code here!
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime / 2;
    p->velocity() += p->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  std::vector<Eigen::Matrix4Xf> k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  for (auto p : particles) {
    k1x.push_back(p->velocity() * deltaTime);
    k1v.push_back(p->acceleration() * deltaTime);
  }
  // k2 = f(x + k1 / 2)
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k1x[i] * (1 / 2);
    particles[i]->velocity() = backup[i].velocity() + k1v[i] * (1 / 2);
  }
  simulateOneStep();
  for (auto p : particles) {
    k2x.push_back(p->velocity() * deltaTime);
    k2v.push_back(p->acceleration() * deltaTime);
  }
  // k3 = f(x + k2 / 2)
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k2x[i] * (1 / 2);
    particles[i]->velocity() = backup[i].velocity() + k2v[i] * (1 / 2);
  }
  simulateOneStep();
  for (auto p : particles) {
    k3x.push_back(p->velocity() * deltaTime);
    k3v.push_back(p->acceleration() * deltaTime);
  }
  // k4 = f(x + k3)
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k3x[i];
    particles[i]->velocity() = backup[i].velocity() + k3v[i];
  }
  simulateOneStep();
  for (auto p : particles) {
    k4x.push_back(p->velocity() * deltaTime);
    k4v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + (k1x[i] + 2 * k2x[i] + 2 * k3x[i] + k4x[i]) / 6;
    particles[i]->velocity() = backup[i].velocity() + (k1v[i] + 2 * k2v[i] + 2 * k3v[i] + k4v[i]) / 6;
  }
}
