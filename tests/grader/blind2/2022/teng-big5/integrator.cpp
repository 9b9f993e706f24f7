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
  for (const auto &p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < particles.size(); i++)
  {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles)
  {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (int i = 0; i < particles.size(); i++)
  {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  int n = particles.size();
  std::vector<Eigen::Matrix4Xf> k1x(n), k1v(n), k2x(n), k2v(n), k3x(n), k3v(n), k4x(n), k4v(n);
  for (int i = 0; i < n; i++)
  {
    k1x[i] = particles[i]->velocity() * deltaTime;
    k1v[i] = particles[i]->acceleration() * deltaTime;
  }
  deltaTime /= 2;  // 中間兩個 stage 走半步
  for (int i = 0; i < n; i++)
  {
    particles[i]->position() = old[i].position() + old[i].velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + old[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < n; i++)
  {
    k2x[i] = particles[i]->velocity() * deltaTime * 2;
    k2v[i] = particles[i]->acceleration() * deltaTime * 2;
  }
  for (int i = 0; i < n; i++)
  {
    particles[i]->position() = old[i].position() + k2x[i] / 2;
    particles[i]->velocity() = old[i].velocity() + k2v[i] / 2;
  }
  simulateOneStep();
  for (int i = 0; i < n; i++)
  {
    k3x[i] = particles[i]->velocity() * deltaTime * 2;
    k3v[i] = particles[i]->acceleration() * deltaTime * 2;
  }
  deltaTime = 0.0001f;  // 改回來
  for (int i = 0; i < n; i++)
  {
    particles[i]->position() = old[i].position() + k3x[i];
    particles[i]->velocity() = old[i].velocity() + k3v[i];
  }
  simulateOneStep();
  for (int i = 0; i < n; i++)
  {
    k4x[i] = particles[i]->velocity() * deltaTime;
    k4v[i] = particles[i]->acceleration() * deltaTime;
  }
  // 四個 k 平均
  for (int i = 0; i < n; i++)
  {
    particles[i]->position() = old[i].position() + (k1x[i] + k2x[i] + k3x[i] + k4x[i]) / 4;
    particles[i]->velocity() = old[i].velocity() + (k1v[i] + k2v[i] + k3v[i] + k4v[i]) / 4;
  }
}
