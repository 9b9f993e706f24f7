#include "integrator.h"

#include "configs.h"

// 半步的時間
static float halfStep() { return deltaTime /= 2; }
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
    p->position() = p->position() + p->velocity() * deltaTime;
    p->velocity() = p->velocity() + p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> before;
  for (auto *p : particles) before.emplace_back(*p);
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = before[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = before[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> before;
  for (auto *p : particles) before.emplace_back(*p);
  const float h = halfStep();
  for (auto *p : particles) {
    p->position() += p->velocity() * h;
    p->velocity() += p->acceleration() * h;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = before[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = before[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> before;
  for (auto *p : particles) before.emplace_back(*p);
  std::vector<std::vector<Eigen::Matrix4Xf>> kx(4), kv(4);
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) {
      float w = (stage == 3) ? 1.0f : 0.5f;
      for (size_t i = 0; i < particles.size(); ++i) {
        particles[i]->position() = before[i].position() + kx[stage - 1][i] * w;
        particles[i]->velocity() = before[i].velocity() + kv[stage - 1][i] * w;
      }
      simulateOneStep();
    }
    for (auto *p : particles) {
      kx[stage].push_back(p->velocity() * deltaTime);
      kv[stage].push_back(p->acceleration() * deltaTime);
    }
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = before[i].position() + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() = before[i].velocity() + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
  }
}
