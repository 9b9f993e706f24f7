// HW1, student 0812345. Based on the course template.
#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // ¿n¤À¾¹
  for (Particles* p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    particles[i]->position() += particles[i]->velocity() * deltaTime;
    particles[i]->velocity() += particles[i]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
    particles[i]->position() += particles[i]->velocity() * deltaTime * 0.5f;
    particles[i]->velocity() += particles[i]->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), sumX(n), sumV(n);
  for (size_t i = 0; i < n; ++i) {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
  }
  const float stageScale[3] = {0.5f, 0.5f, 1.0f};
  const float weight[4] = {1.0f, 2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t i = 0; i < n; ++i) {
      Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = particles[i]->acceleration() * deltaTime;
      if (stage == 0) {
        sumX[i] = kx;
        sumV[i] = kv;
      } else {
        sumX[i] += weight[stage] * kx;
        sumV[i] += weight[stage] * kv;
      }
      if (stage < 3) {
        particles[i]->position() = x0[i] + kx * stageScale[stage];
        particles[i]->velocity() = v0[i] + kv * stageScale[stage];
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = x0[i] + sumX[i] / 6.0f;
    particles[i]->velocity() = v0[i] + sumV[i] / 6.0f;
  }
}
