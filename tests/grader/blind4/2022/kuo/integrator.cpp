#include "integrator.h"
#include <array>

#include "configs.h"

namespace
{
// 一步 explicit euler，順便把上面兩個角固定住（怕角被拉走）
void stepOne(Particles *p, float dt)
{
  p->position() += p->velocity() * dt;
  p->velocity() += p->acceleration() * dt;
  p->velocity(0).setZero();
  if (p->getCapacity() > 24) p->velocity(24).setZero();
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
  for (const auto &p : particles)
  {
    stepOne(p, deltaTime);
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto *p : particles)
  {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t i = 0; i < particles.size(); ++i)
  {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto *p : particles)
  {
    x0.emplace_back(p->position());
    v0.emplace_back(p->velocity());
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t i = 0; i < particles.size(); ++i)
  {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  const std::size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n);
  std::vector<std::array<Eigen::Matrix4Xf, 4>> kx(n), kv(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    x0[i] = particles[i]->position();
    v0[i] = particles[i]->velocity();
  }
  const float h[4] = {0.0f, 0.5f, 0.5f, 1.0f};
  for (int s = 0; s < 4; ++s)
  {
    if (s > 0)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        particles[i]->position() = (x0[i] + kx[i][s - 1] * h[s]).eval();
        particles[i]->velocity() = (v0[i] + kv[i][s - 1] * h[s]).eval();
      }
      simulateOneStep();
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      kx[i][s] = particles[i]->velocity() * deltaTime;
      kv[i][s] = particles[i]->acceleration() * deltaTime;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    particles[i]->position() = x0[i] + (kx[i][0] + 2.0f * kx[i][1] + 2.0f * kx[i][2] + kx[i][3]) / 6.0f;
    particles[i]->velocity() = v0[i] + (kv[i][0] + 2.0f * kv[i][1] + 2.0f * kv[i][2] + kv[i][3]) / 6.0f;
  }
}
