// clothref's reference solution for the 2022 edition, written in course form (see cloth.cpp here).
// Explicit: x += v dt, then v += a dt (forward Euler). Implicit and midpoint: back up full copies,
// predict (the midpoint with (v dt) * 0.5f), simulateOneStep(), then x = x0 + v dt, v = v0 + a dt
// with the derivatives just evaluated. RK4: k = (v dt, a dt) per stage, stage states x0 + k * 0.5f,
// x0 + k * 0.5f, x0 + k, and x0 + (k1 + 2.0f * k2 + 2.0f * k3 + k4) / 6.0f.
#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  Particles* cloth = particles[0];
  cloth->position() += cloth->velocity() * deltaTime;
  cloth->velocity() += cloth->acceleration() * deltaTime;
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
  Particles* p = particles[0];
  Eigen::Matrix4Xf x0 = p->position(), v0 = p->velocity();
  Eigen::Matrix4Xf k1x = p->velocity() * deltaTime, k1v = p->acceleration() * deltaTime;
  p->position() = x0 + k1x * 0.5f;
  p->velocity() = v0 + k1v * 0.5f;
  simulateOneStep();
  Eigen::Matrix4Xf k2x = p->velocity() * deltaTime, k2v = p->acceleration() * deltaTime;
  p->position() = x0 + k2x * 0.5f;
  p->velocity() = v0 + k2v * 0.5f;
  simulateOneStep();
  Eigen::Matrix4Xf k3x = p->velocity() * deltaTime, k3v = p->acceleration() * deltaTime;
  p->position() = x0 + k3x;
  p->velocity() = v0 + k3v;
  simulateOneStep();
  Eigen::Matrix4Xf k4x = p->velocity() * deltaTime, k4v = p->acceleration() * deltaTime;
  p->position() = x0 + (k1x + 2.0f * k2x + 2.0f * k3x + k4x) / 6.0f;
  p->velocity() = v0 + (k1v + 2.0f * k2v + 2.0f * k3v + k4v) / 6.0f;
}
