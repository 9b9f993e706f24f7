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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> px, pv;
  for (const auto &p : particles) {
    px.push_back(p->position());
    pv.push_back(p->velocity());
  }
  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = px[k] + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = pv[k] + particles[k]->acceleration() * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> px, pv;
  for (const auto &p : particles) {
    px.push_back(p->position());
    pv.push_back(p->velocity());
  }
  for (const auto &p : particles) {
    p->position() += 0.5f * (p->velocity() * deltaTime);
    p->velocity() += 0.5f * (p->acceleration() * deltaTime);
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = px[k] + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = pv[k] + particles[k]->acceleration() * deltaTime;
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
  const size_t m = particles.size();
  std::vector<Eigen::Matrix4Xf> px(m), pv(m), kx[4], kv[4];
  for (size_t k = 0; k < m; ++k) {
    px[k] = particles[k]->position();
    pv[k] = particles[k]->velocity();
  }
  const float step[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  for (int s = 0; s < 4; ++s) {
    for (size_t k = 0; k < m; ++k) {
      kx[s].push_back(particles[k]->velocity() * deltaTime);
      kv[s].push_back(particles[k]->acceleration() * deltaTime);
    }
    if (s == 3) break;
    for (size_t k = 0; k < m; ++k) {
      particles[k]->position() = px[k] + kx[s][k] * step[s];
      particles[k]->velocity() = pv[k] + kv[s][k] * step[s];
    }
    simulateOneStep();
  }
  // (k1 + 2k2 + 2k3 + k4) / 6 = (k1 + k4) / 6 + (k2 + k3) / 3
  for (size_t k = 0; k < m; ++k) {
    particles[k]->position() = px[k] + ((kx[0][k] + kx[3][k]) / 6 + (kx[1][k] + kx[2][k]) * (1 / 3));
    particles[k]->velocity() = pv[k] + ((kv[0][k] + kv[3][k]) / 6 + (kv[1][k] + kv[2][k]) * (1 / 3));
  }
}
