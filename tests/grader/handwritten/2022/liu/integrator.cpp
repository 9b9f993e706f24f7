#include "integrator.h"

#include "configs.h"

void ExplicitEuler::integrate(const std::vector<Particles *> &particles, std::function<void(void)>) const {
  // TODO: Integrate velocity and acceleration
  //   1. Integrate velocity.
  //   2. Integrate acceleration.
  //   3. You should not compute position using acceleration. Since some part only update velocity. (e.g. impulse)
  // Note:
  //   1. You don't need the simulation function in explicit euler.
  //   2. You should do this first because it is very simple. Then you can check your collision is correct or not.
  //   3. This can be done in 2 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (auto p : particles) {
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> X, V;
  for (auto p : particles) {
    X.emplace_back(p->position());
    V.emplace_back(p->velocity());
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = X[i] + V[i] * deltaTime;
    particles[i]->velocity() = V[i] + particles[i]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = X[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = V[i] + particles[i]->acceleration() * deltaTime;
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
  // Write code here!
  std::vector<Eigen::Matrix4Xf> X, V;
  for (auto p : particles) {
    X.emplace_back(p->position());
    V.emplace_back(p->velocity());
  }
  // go to the midpoint
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = X[i] + V[i] * deltaTime;
    particles[i]->velocity() = V[i] + particles[i]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = X[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = V[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
  std::vector<Eigen::Matrix4Xf> X, V, sx, sv;
  for (auto p : particles) {
    X.emplace_back(p->position());
    V.emplace_back(p->velocity());
  }
  // k1
  for (auto p : particles) {
    Eigen::Matrix4Xf kx = p->velocity() * deltaTime, kv = p->acceleration() * deltaTime;
    sx.push_back(kx);
    sv.push_back(kv);
    p->position() += kx * 0.5f;
    p->velocity() += kv * 0.5f;
  }
  simulateOneStep();
  // k2
  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime, kv = particles[i]->acceleration() * deltaTime;
    sx[i] += 2 * kx;
    sv[i] += 2 * kv;
    particles[i]->position() += kx * 0.5f;
    particles[i]->velocity() += kv * 0.5f;
  }
  simulateOneStep();
  // k3
  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime, kv = particles[i]->acceleration() * deltaTime;
    sx[i] += 2 * kx;
    sv[i] += 2 * kv;
    particles[i]->position() += kx;
    particles[i]->velocity() += kv;
  }
  simulateOneStep();
  // k4
  for (size_t i = 0; i < particles.size(); i++) {
    sx[i] += particles[i]->velocity() * deltaTime;
    sv[i] += particles[i]->acceleration() * deltaTime;
    particles[i]->position() = X[i] + sx[i] / 6;
    particles[i]->velocity() = V[i] + sv[i] / 6;
  }
}
