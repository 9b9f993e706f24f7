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
  particles[0]->position() += particles[0]->velocity() * deltaTime;
  particles[0]->velocity() += particles[0]->acceleration() * deltaTime;
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
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
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
  // Write code here!
  std::vector<Particles> backup;
  for (auto p : particles) backup.push_back(*p);
  for (auto p : particles) {
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
  // TODO: Integrate velocity and acceleration
  //   1. Backup original particles' data.
  //   2. Compute k1, k2, k3, k4
  //   3. Compute refined Xn+1 using (1.) (2.).
  // Note:
  //   1. Use simulateOneStep with modified position and velocity to get Xn+1.
  // Write code here!
  const auto n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0, v0, sumX, sumV;
  for (auto p : particles) {
    x0.push_back(p->position().eval());
    v0.push_back(p->velocity().eval());
  }
  // k1
  for (size_t i = 0; i < n; ++i) {
    auto k1x = (particles[i]->velocity() * deltaTime).eval();
    auto k1v = (particles[i]->acceleration() * deltaTime).eval();
    sumX.push_back(k1x);
    sumV.push_back(k1v);
    particles[i]->position() = x0[i] + k1x * 0.5f;
    particles[i]->velocity() = v0[i] + k1v * 0.5f;
  }
  simulateOneStep();
  // k2
  for (size_t i = 0; i < n; ++i) {
    auto k2x = (particles[i]->velocity() * deltaTime).eval();
    auto k2v = (particles[i]->acceleration() * deltaTime).eval();
    sumX[i] += 2.0f * k2x;
    sumV[i] += 2.0f * k2v;
    particles[i]->position() = x0[i] + k2x * 0.5f;
    particles[i]->velocity() = v0[i] + k2v * 0.5f;
  }
  simulateOneStep();
  // k3
  for (size_t i = 0; i < n; ++i) {
    auto k3x = (particles[i]->velocity() * deltaTime).eval();
    auto k3v = (particles[i]->acceleration() * deltaTime).eval();
    sumX[i] += 2.0f * k3x;
    sumV[i] += 2.0f * k3v;
    particles[i]->position() = x0[i] + k3x;
    particles[i]->velocity() = v0[i] + k3v;
  }
  simulateOneStep();
  // k4
  for (size_t i = 0; i < n; ++i) {
    sumX[i] += particles[i]->velocity() * deltaTime;
    sumV[i] += particles[i]->acceleration() * deltaTime;
    particles[i]->position() = x0[i] + sumX[i] / 6.0f;
    particles[i]->velocity() = v0[i] + sumV[i] / 6.0f;
  }
}
