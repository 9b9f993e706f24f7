#include "integrator.h"
#include <cstddef>

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
  //   3. This can be done in 5 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (Particles *p : particles)
  {
    for (std::size_t i = 0; i < static_cast<std::size_t>(p->getCapacity()); ++i)
    {
      const int k = static_cast<int>(i);
      p->position(k) += p->velocity(k) * deltaTime;
      p->velocity(k) += p->acceleration(k) * deltaTime;
    }
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
  std::vector<Particles> before;
  for (Particles *p : particles) before.push_back(*p);
  for (Particles *p : particles)
  {
    for (int k = 0; k < p->getCapacity(); ++k)
    {
      p->position(k) += p->velocity(k) * deltaTime;
      p->velocity(k) += p->acceleration(k) * deltaTime;
    }
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    for (int k = 0; k < p->getCapacity(); ++k)
    {
      p->position(k) = before[b].position(k) + p->velocity(k) * deltaTime;
      p->velocity(k) = before[b].velocity(k) + p->acceleration(k) * deltaTime;
    }
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
  std::vector<Particles> before;
  for (Particles *p : particles) before.push_back(*p);
  const float half = deltaTime * 0.5f;
  for (Particles *p : particles)
  {
    for (int k = 0; k < p->getCapacity(); ++k)
    {
      // velocity to the midpoint first, then move with it
      p->velocity(k) += p->acceleration(k) * half;
      p->position(k) += p->velocity(k) * half;
    }
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    for (int k = 0; k < p->getCapacity(); ++k)
    {
      p->position(k) = before[b].position(k) + p->velocity(k) * deltaTime;
      p->velocity(k) = before[b].velocity(k) + p->acceleration(k) * deltaTime;
    }
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
  std::vector<Particles> before;
  for (Particles *p : particles) before.push_back(*p);
  std::vector<Eigen::Matrix4Xf> sumX, sumV, kx, kv;
  for (Particles *p : particles)
  {
    kx.push_back(p->velocity() * deltaTime);
    kv.push_back(p->acceleration() * deltaTime);
  }
  sumX = kx;
  sumV = kv;
  const float reach[3] = {0.5f, 0.5f, 1.0f};
  const float weight[3] = {2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 3; ++stage)
  {
    for (std::size_t b = 0; b < particles.size(); ++b)
    {
      particles[b]->position() = before[b].position() + kx[b] * reach[stage];
      particles[b]->velocity() = before[b].velocity() + kv[b] * reach[stage];
    }
    simulateOneStep();
    for (std::size_t b = 0; b < particles.size(); ++b)
    {
      kx[b] = particles[b]->velocity() * deltaTime;
      kv[b] = particles[b]->acceleration() * deltaTime;
      sumX[b] += weight[stage] * kx[b];
      sumV[b] += weight[stage] * kv[b];
    }
  }
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = before[b].position() + sumX[b] / 6.0f;
    particles[b]->velocity() = before[b].velocity() + sumV[b] / 6.0f;
  }
}
