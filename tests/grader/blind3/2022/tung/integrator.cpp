#include "integrator.h"

#include "configs.h"

namespace {
// put every body back to the saved state
void restore(const std::vector<Particles *> &particles, std::vector<Particles> &saved) {
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position();
    particles[i]->velocity() = saved[i].velocity();
  }
}
}  // namespace
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
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = saved[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = saved[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = saved[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> saved;
  for (auto *p : particles) saved.push_back(*p);
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  for (auto *p : particles) {
    kx[0].push_back(p->velocity() * deltaTime);
    kv[0].push_back(p->acceleration() * deltaTime);
  }
  const float factor[3] = {0.5f, 0.5f, 1.0f};
  for (int s = 1; s < 4; ++s) {
    for (size_t i = 0; i < particles.size(); ++i) {
      restore(particles, saved);  // start every stage from x0, v0
      particles[i]->position() += kx[s - 1][i] * factor[s - 1];
      particles[i]->velocity() += kv[s - 1][i] * factor[s - 1];
    }
    simulateOneStep();
    for (auto *p : particles) {
      kx[s].push_back(p->velocity() * deltaTime);
      kv[s].push_back(p->acceleration() * deltaTime);
    }
  }
  restore(particles, saved);
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() += (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
  }
}
