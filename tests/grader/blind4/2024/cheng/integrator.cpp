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
  //   3. This can be done in 5 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (Particles *p : particles)
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
  // Write code here!
  std::vector<Particles> start;
  for (Particles *p : particles) start.push_back(*p);
  for (Particles *p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = start[b].position() + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = start[b].velocity() + particles[b]->acceleration() * deltaTime;
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
  std::vector<Particles> start;
  for (Particles *p : particles) start.push_back(*p);
  for (Particles *p : particles)
  {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = start[b].position() + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = start[b].velocity() + particles[b]->acceleration() * deltaTime;
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
  std::vector<Particles> start;
  for (Particles *p : particles) start.push_back(*p);
  std::vector<Eigen::Matrix4Xf> k1x, k2x, k3x, k4x;
  // accelerations of each stage, multiplied by dt at the end
  std::vector<Eigen::Ref<Eigen::Matrix4Xf>> a1, a2, a3, a4;

  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    k1x.push_back(p->velocity() * deltaTime);
    a1.push_back(p->acceleration());
    p->position() = start[b].position() + k1x[b] * 0.5f;
    p->velocity() = start[b].velocity() + a1[b] * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    k2x.push_back(p->velocity() * deltaTime);
    a2.push_back(p->acceleration());
    p->position() = start[b].position() + k2x[b] * 0.5f;
    p->velocity() = start[b].velocity() + a2[b] * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    k3x.push_back(p->velocity() * deltaTime);
    a3.push_back(p->acceleration());
    p->position() = start[b].position() + k3x[b];
    p->velocity() = start[b].velocity() + a3[b] * deltaTime;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles *p = particles[b];
    k4x.push_back(p->velocity() * deltaTime);
    a4.push_back(p->acceleration());
    p->position() = start[b].position() + (k1x[b] + 2 * k2x[b] + 2 * k3x[b] + k4x[b]) / 6;
    p->velocity() = start[b].velocity() + (a1[b] + 2 * a2[b] + 2 * a3[b] + a4[b]) * deltaTime / 6;
  }
}
