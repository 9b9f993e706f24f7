#include "integrator.h"

#include "configs.h"

#include <array>

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
  for (const auto &p : particles)
  {
    // 先位置 (用舊速度) 再速度
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const
{
  // 1. 備份 (整個 Particles 複製一份)
  std::vector<Particles> backup;
  for (Particles *p : particles) backup.push_back(*p);
  // 2. explicit euler 先猜下一步
  for (size_t k = 0; k < particles.size(); ++k)
  {
    particles[k]->position() = backup[k].position() + backup[k].velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + backup[k].acceleration() * deltaTime;
  }
  simulateOneStep();
  // 3. 用猜的那一步的速度、加速度，從備份重新走一步
  for (size_t k = 0; k < particles.size(); ++k)
  {
    particles[k]->position() = backup[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = backup[k].velocity() + particles[k]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const
{
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *p : particles)
  {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  // 走半步到中點
  for (size_t k = 0; k < particles.size(); ++k)
  {
    particles[k]->position() = x0[k] + particles[k]->velocity() * deltaTime * 0.5f;
    particles[k]->velocity() = v0[k] + particles[k]->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  // 用中點的導數走完整一步
  for (size_t k = 0; k < particles.size(); ++k)
  {
    particles[k]->position() = x0[k] + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = v0[k] + particles[k]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const
{
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  std::array<std::vector<Eigen::Matrix4Xf>, 4> kx, kv;  // kx[s][body], kv[s][body]
  for (int s = 0; s < 4; ++s)
  {
    kx[s].resize(n);
    kv[s].resize(n);
  }
  for (size_t b = 0; b < n; ++b)
  {
    x0[b] = particles[b]->position();
    v0[b] = particles[b]->velocity();
    kx[0][b] = particles[b]->velocity() * deltaTime;
    kv[0][b] = particles[b]->acceleration() * deltaTime;
  }
  const std::array<float, 3> scale = {0.5f, 0.5f, 1.0f};  // k2, k3 半步，k4 整步
  for (int s = 1; s < 4; ++s)
  {
    for (size_t b = 0; b < n; ++b)
    {
      particles[b]->position() = x0[b] + kx[s - 1][b] * scale[s - 1];
      particles[b]->velocity() = v0[b] + kv[s - 1][b] * scale[s - 1];
    }
    simulateOneStep();
    for (size_t b = 0; b < n; ++b)
    {
      kx[s][b] = particles[b]->velocity() * deltaTime;
      kv[s][b] = particles[b]->acceleration() * deltaTime;
    }
  }
  for (size_t b = 0; b < n; ++b)
  {
    particles[b]->position() = x0[b] + (kx[0][b] + 2.0f * kx[1][b] + 2.0f * kx[2][b] + kx[3][b]) / 6.0f;
    particles[b]->velocity() = v0[b] + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv[3][b]) / 6.0f;
  }
}
