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
  std::vector<Particles> start;
  for (auto *p : particles) start.push_back(*p);
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + start[k].velocity() * deltaTime;
    particles[k]->velocity() = start[k].velocity() + start[k].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = start[k].velocity() + particles[k]->acceleration() * deltaTime;
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
  for (auto *p : particles) start.push_back(*p);
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + start[k].velocity() * deltaTime * 0.5f;
    particles[k]->velocity() = start[k].velocity() + start[k].acceleration() * deltaTime * 0.5f;
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
  std::vector<Particles> start;
  for (auto *p : particles) start.push_back(*p);
  std::vector<Eigen::Matrix4Xf> dx[4], dv[4];
  const float w[3] = {0.5f, 0.5f, 1.0f};  // how far the next stage goes
  for (int s = 0; s < 4; ++s) {
    if (s > 0) simulateOneStep();
    for (size_t k = 0; k < particles.size(); ++k) {
      Particles *p = particles[k];
      dv[s].push_back(p->acceleration() * deltaTime);
      // velocity of this stage
      if (s > 0) p->velocity() = start[k].velocity() + dv[s][k] * w[s - 1];
      dx[s].push_back(p->velocity() * deltaTime);
      if (s < 3) {
        p->position() = start[k].position() + dx[s][k] * w[s];
        p->velocity() = start[k].velocity() + dv[s][k] * w[s];
      }
    }
  }
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = start[k].position() + (dx[0][k] + 2.0f * dx[1][k] + 2.0f * dx[2][k] + dx[3][k]) / 6.0f;
    particles[k]->velocity() = start[k].velocity() + (dv[0][k] + 2.0f * dv[1][k] + 2.0f * dv[2][k] + dv[3][k]) / 6.0f;
  }
}
