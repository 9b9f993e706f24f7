#include "integrator.h"

#include "configs.h"

// 取得這一段要走的時間
static float stepSize(float fraction) {
  deltaTime *= fraction;
  return deltaTime;
}

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
  for (Particles *p : particles) {
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (Particles *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (Particles *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * deltaTime;
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
  for (Particles *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  const float half = stepSize(0.5f);
  for (Particles *p : particles) {
    p->position() += p->velocity() * half;
    p->velocity() += p->acceleration() * half;
  }
  simulateOneStep();
  const float full = stepSize(1.0f);
  for (size_t b = 0; b < particles.size(); ++b) {
    particles[b]->position() = x0[b] + particles[b]->velocity() * full;
    particles[b]->velocity() = v0[b] + particles[b]->acceleration() * full;
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
  const size_t count = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(count), v0(count), k1x(count), k1v(count), k2x(count), k2v(count), k3x(count), k3v(count);
  // k1 + 走到一半
  for (size_t b = 0; b < count; ++b) {
    Particles *p = particles[b];
    x0[b] = p->position();
    v0[b] = p->velocity();
    p->position() = x0[b] + p->velocity() * deltaTime * 0.5f;
    p->velocity() = v0[b] + p->acceleration() * deltaTime * 0.5f;
    k1x[b] = p->velocity() * deltaTime;
    k1v[b] = p->acceleration() * deltaTime;
  }
  simulateOneStep();
  // k2
  for (size_t b = 0; b < count; ++b) {
    Particles *p = particles[b];
    k2x[b] = p->velocity() * deltaTime;
    k2v[b] = p->acceleration() * deltaTime;
    p->position() = x0[b] + k2x[b] * 0.5f;
    p->velocity() = v0[b] + k2v[b] * 0.5f;
  }
  simulateOneStep();
  // k3
  for (size_t b = 0; b < count; ++b) {
    Particles *p = particles[b];
    k3x[b] = p->velocity() * deltaTime;
    k3v[b] = p->acceleration() * deltaTime;
    p->position() = x0[b] + k3x[b];
    p->velocity() = v0[b] + k3v[b];
  }
  simulateOneStep();
  // k4 + 合起來
  for (size_t b = 0; b < count; ++b) {
    Particles *p = particles[b];
    Eigen::Matrix4Xf k4x = p->velocity() * deltaTime;
    Eigen::Matrix4Xf k4v = p->acceleration() * deltaTime;
    p->position() = x0[b] + (k1x[b] + 2 * k2x[b] + 2 * k3x[b] + k4x) / 6;
    p->velocity() = v0[b] + (k1v[b] + 2 * k2v[b] + 2 * k3v[b] + k4v) / 6;
  }
}
