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
  for (const auto &p : particles) {
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
  // 1. 備份
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  // 2. 預測 (先速度後位置)
  for (const auto &p : particles) {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
  simulateOneStep();
  // 3. 用 X(n+1) 的導數從 X(n) 走一步
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  // 中點的狀態
  std::vector<Eigen::Matrix4Xf> midX, midV;
  for (const auto &p : particles) {
    midX.push_back(p->position() + p->velocity() * deltaTime * 0.5f);
    midV.push_back(p->velocity() + p->acceleration() * deltaTime * 0.5f);
  }
  simulateOneStep();  // 中點的加速度
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += midV[i] * deltaTime;
    particles[i]->velocity() += particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  const float c[3] = {0.5f, 0.5f, 1.0f};
  for (int s = 0; s < 4; ++s) {
    if (s > 0) simulateOneStep();
    for (size_t i = 0; i < n; ++i) {
      kx[s].push_back(particles[i]->velocity() * deltaTime);
      kv[s].push_back(particles[i]->acceleration() * deltaTime);
      if (s < 3) {
        particles[i]->position() = backup[i].position() + kx[s][i] * c[s];
        particles[i]->velocity() = backup[i].velocity() + kv[s][i] * c[s];
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = backup[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
  }
}
