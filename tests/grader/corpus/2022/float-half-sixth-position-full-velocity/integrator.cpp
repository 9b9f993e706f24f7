// clothref's reference solution for the 2022 edition, written in course form (see cloth.cpp here).
// Explicit: x += v dt, then v += a dt (forward Euler). Implicit and midpoint: back up full copies,
// predict (the midpoint with (v dt) * 0.5f), simulateOneStep(), then x = x0 + v dt, v = v0 + a dt
// with the derivatives just evaluated. RK4: k = (v dt, a dt) per stage, stage states x0 + k * 0.5f,
// x0 + k * 0.5f, x0 + k, and x0 + (k1 + 2.0f * k2 + 2.0f * k3 + k4) / 6.0f.
#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. Review "particles.h" if you don't know how to access data.
  // Hint:
  //   1. This can be done in 2 lines. (Hint: Operator overloading is available)
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
  // A pointer-vector copy would alias the live state: back up the Particles themselves.
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);

  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
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
  std::vector<Particles> backup;
  for (const auto &p : particles) backup.push_back(*p);

  for (const auto &p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = backup[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = backup[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto p : particles) { x0.push_back(p->position()); v0.push_back(p->velocity()); }
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  const float h[3] = {0.5f, 0.5f, 1.0f};
  for (int k = 0; k < 4; k++) {
    if (k > 0) simulateOneStep();
    for (size_t i = 0; i < particles.size(); i++) {
      kx[k].push_back(particles[i]->velocity() * deltaTime);
      kv[k].push_back(particles[i]->acceleration() * deltaTime);
    }
    if (k == 3) break;
    for (size_t i = 0; i < particles.size(); i++) {
      particles[i]->position() = x0[i] + kx[k][i] * h[k];
      particles[i]->velocity() = v0[i] + kv[k][i] * h[k];
    }
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = x0[i] + (1 / 6) * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
    particles[i]->velocity() = v0[i] + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6.0f;
  }
}
