#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. You should do this first because it is very simple. Then you can check your collision is correct or not.
  //   3. This can be done in 5 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (auto* p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  std::vector<Particles> old;
  for (auto* p : particles) old.push_back(*p);
  for (auto* p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Integrate velocity and acceleration using explicit euler to get Xn+1.
  //   3. Compute refined Xn+1 using (1.) and (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  std::vector<Particles> old;
  for (auto* p : particles) old.push_back(*p);
  for (auto* p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  const size_t n = particles.size();
  std::vector<Particles> start;
  for (auto* p : particles) start.push_back(*p);
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  const float stageStep[3] = {0.5f, 0.5f, 1.0f};

  for (int s = 0; s < 4; ++s) {
    if (s > 0) simulateOneStep();
    std::vector<Particles> current;
    for (auto* p : particles) current.push_back(*p);
    for (size_t i = 0; i < n; ++i) {
      kx[s].push_back(current[i].velocity() * deltaTime);
      kv[s].push_back(current[i].acceleration() * deltaTime);
    }
    if (s == 3) break;
    // next stage: move from the current stage by k * step
    for (size_t i = 0; i < n; ++i) {
      particles[i]->position() = current[i].position() + kx[s][i] * stageStep[s];
      particles[i]->velocity() = current[i].velocity() + kv[s][i] * stageStep[s];
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = start[i].position() + (kx[0][i] + 3.0f * kx[1][i] + 3.0f * kx[2][i] + kx[3][i]) / 8.0f;
    particles[i]->velocity() = start[i].velocity() + (kv[0][i] + 3.0f * kv[1][i] + 3.0f * kv[2][i] + kv[3][i]) / 8.0f;
  }
}
