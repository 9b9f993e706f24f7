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
    p->velocity() += p->acceleration() * deltaTime;  // 先更新速度
    p->position() += p->velocity() * deltaTime;      // 再用新速度更新位置 (semi-implicit)
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
  std::vector<Particles> start;
  start.reserve(particles.size());
  for (const auto &p : particles) start.push_back(*p);

  // predict with explicit Euler
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + start[k].velocity() * deltaTime;
    particles[k]->velocity() = start[k].velocity() + start[k].acceleration() * deltaTime;
  }
  simulateOneStep();
  // 用預測點的加速度更新速度, 再用新速度更新位置
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->velocity() = start[k].velocity() + particles[k]->acceleration() * deltaTime;
    particles[k]->position() = start[k].position() + particles[k]->velocity() * deltaTime;
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
  std::vector<Particles> start;
  start.reserve(particles.size());
  for (const auto &p : particles) start.push_back(*p);

  const float half = deltaTime * 0.5f;
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->velocity() = start[k].velocity() + start[k].acceleration() * half;
    particles[k]->position() = start[k].position() + particles[k]->velocity() * half;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = start[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  const size_t n = particles.size();
  std::vector<Particles> start;
  for (const auto &p : particles) start.push_back(*p);
  // 存每一階的 v 和 a (不是乘過 dt 的)
  std::vector<Eigen::Matrix4Xf> v[4], a[4];
  const float stageStep[3] = {deltaTime / 2, deltaTime / 2, deltaTime};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t k = 0; k < n; ++k) {
      v[stage].push_back(particles[k]->velocity());
      a[stage].push_back(particles[k]->acceleration());
    }
    if (stage == 3) break;
    for (size_t k = 0; k < n; ++k) {
      particles[k]->position() = start[k].position() + v[stage][k] * stageStep[stage];
      particles[k]->velocity() = start[k].velocity() + a[stage][k] * stageStep[stage];
    }
  }
  for (size_t k = 0; k < n; ++k) {
    particles[k]->position() = start[k].position() + (v[0][k] + 2 * v[1][k] + 2 * v[2][k] + v[3][k]) * (deltaTime / 6);
    particles[k]->velocity() = start[k].velocity() + (a[0][k] + 2 * a[1][k] + 2 * a[2][k] + a[3][k]) * (deltaTime / 6);
  }
}
