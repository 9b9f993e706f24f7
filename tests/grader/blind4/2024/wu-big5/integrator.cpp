#include "integrator.h"

#include "configs.h"

namespace {
// 四個角固定住
void pinCorners(Particles *p) {
  const int n = particlesPerEdge;
  if (p->getCapacity() != n * n) return;
  for (int c : {0, n - 1, n * (n - 1), n * n - 1}) {
    p->mass(c) = 0.0f;
    p->velocity(c).setZero();
  }
}

// explicit euler 一步 (預測用)
void predict(Particles *p, float h) {
  p->position() += p->velocity() * h;
  p->velocity() += p->acceleration() * h;
  pinCorners(p);
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
  //   3. This can be done in 5 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (auto p : particles) {
    auto dx = p->velocity() * deltaTime;
    auto dv = p->acceleration() * deltaTime;
    p->position() += dx;
    p->velocity() += dv;
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles) predict(p, deltaTime);
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
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
  // Write code here!
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
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
  // Write code here!
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> dx1(n), dv1(n), dx2(n), dv2(n), dx3(n), dv3(n), dx4(n), dv4(n);
  for (size_t i = 0; i < n; ++i) {
    dx1[i] = particles[i]->velocity() * deltaTime;
    dv1[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = old[i].position() + dx1[i] * 0.5f;
    particles[i]->velocity() = old[i].velocity() + dv1[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx2[i] = particles[i]->velocity() * deltaTime;
    dv2[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = old[i].position() + dx2[i] * 0.5f;
    particles[i]->velocity() = old[i].velocity() + dv2[i] * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx3[i] = particles[i]->velocity() * deltaTime;
    dv3[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = old[i].position() + dx3[i];
    particles[i]->velocity() = old[i].velocity() + dv3[i];
  }
  simulateOneStep();
  for (size_t i = 0; i < n; ++i) {
    dx4[i] = particles[i]->velocity() * deltaTime;
    dv4[i] = particles[i]->acceleration() * deltaTime;
  }
  for (size_t i = 0; i < n; ++i) {
    particles[i]->position() = old[i].position() + (dx1[i] + 2 * dx2[i] + 2 * dx3[i] + dx4[i]) / 6;
    particles[i]->velocity() = old[i].velocity() + (dv1[i] + 2 * dv2[i] + 2 * dv3[i] + dv4[i]) / 6;
  }
}
