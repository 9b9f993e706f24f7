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
  //   3. This can be done in 2 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (const auto &p : particles) {
    // 先更新速度再更新位置
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
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
  // Write code here!
  // 1. 備份
  auto tmp = particles;
  // 2. explicit euler 得到 X_{n+1} 的估計
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  // 用估計的 X_{n+1} 算力
  simulateOneStep();
  // 3. X_{n+1} = X_n + dt * f(X_{n+1})
  //    估計值已經是 X_n + dt * f(X_n)，所以只要補上 f(X_{n+1}) - f(X_n) 的差
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() += (particles[i]->velocity() - tmp[i]->velocity()) * deltaTime;
    particles[i]->velocity() += (particles[i]->acceleration() - tmp[i]->acceleration()) * deltaTime;
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
  // Write code here!
  // 1. 備份原本的狀態
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);
  // 2. 走半步到中點
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime / 2;
    p->velocity() += p->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  // 3. 用中點的速度、加速度從原本的狀態走一整步
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);

  std::vector<Eigen::Matrix4Xf> k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
  // k1
  for (const auto &p : particles) {
    k1x.push_back(p->velocity() * deltaTime);
    k1v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k1x[i] * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + k1v[i] * 0.5f;
  }
  simulateOneStep();
  // k2
  for (const auto &p : particles) {
    k2x.push_back(p->velocity() * deltaTime);
    k2v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k2x[i] * 0.5f;
    particles[i]->velocity() = backup[i].velocity() + k2v[i] * 0.5f;
  }
  simulateOneStep();
  // k3
  for (const auto &p : particles) {
    k3x.push_back(p->velocity() * deltaTime);
    k3v.push_back(p->acceleration() * deltaTime);
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + k3x[i];
    particles[i]->velocity() = backup[i].velocity() + k3v[i];
  }
  simulateOneStep();
  // k4
  for (const auto &p : particles) {
    k4x.push_back(p->velocity() * deltaTime);
    k4v.push_back(p->acceleration() * deltaTime);
  }
  // 最後加權平均
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + (k1x[i] + 2.0f * k2x[i] + 2.0f * k3x[i] + k4x[i]) / 6.0f;
    particles[i]->velocity() = backup[i].velocity() + (k1v[i] + 2.0f * k2v[i] + 2.0f * k3v[i] + k4v[i]) / 6.0f;
  }
}
