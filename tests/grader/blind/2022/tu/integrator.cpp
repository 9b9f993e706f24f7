#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() = x0.back() + v0.back() * deltaTime;
    p->velocity() = v0.back() + p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() = x0.back() + v0.back() * deltaTime / 2;
    p->velocity() = v0.back() + p->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  std::vector<Eigen::Matrix4Xf> x0, v0, sumX, sumV;
  for (const auto &p : particles) {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    sumX.emplace_back(Eigen::Matrix4Xf::Zero(4, p->getCapacity()));
    sumV.emplace_back(Eigen::Matrix4Xf::Zero(4, p->getCapacity()));
  }
  // weights 1/6, 1/3, 1/3, 1/6; next stage at h = 1/2, 1/2, 1
  const float weight[4] = {1.0f / 6.0f, 1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 6.0f};
  const float next[3] = {0.5f, 0.5f, 1.0f};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t i = 0; i < particles.size(); ++i) {
      Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = particles[i]->acceleration() * deltaTime;
      sumX[i] += kx * weight[stage];
      sumV[i] += kv * weight[stage];
      if (stage < 3) {
        particles[i]->position() = x0[i] + kx * next[stage];
        particles[i]->velocity() = v0[i] + kv * next[stage];
      }
    }
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + sumX[i];
    particles[i]->velocity() = v0[i] + sumV[i];
  }
}
