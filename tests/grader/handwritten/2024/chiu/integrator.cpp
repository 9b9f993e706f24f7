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
  //   3. This can be done in 5 lines. (Hint: You can add / multiply all particles at once since it is a large matrix.)
  for (auto p : particles) {
    Eigen::Matrix4Xf a = p->acceleration();
    Eigen::Matrix4Xf v = p->velocity();
    p->position() += v * deltaTime + 0.5f * a * deltaTime * deltaTime;
    p->velocity() += a * deltaTime;
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
  std::vector<Particles> prev;
  for (auto p : particles) prev.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = prev[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = prev[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> prev;
  for (auto p : particles) prev.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime / 2.0f;
    p->velocity() += p->acceleration() * deltaTime / 2.0f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = prev[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = prev[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> prev;
  for (auto p : particles) prev.push_back(*p);
  std::vector<Eigen::Matrix4Xf> sumX, sumV;
  const float stepScale[3] = {0.5f, 0.5f, 1.0f};
  const float weight[4] = {1.0f, 2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 4; stage++) {
    if (stage != 0) simulateOneStep();
    for (size_t i = 0; i < particles.size(); i++) {
      Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = particles[i]->acceleration() * deltaTime;
      if (stage == 0) {
        sumX.push_back(kx);
        sumV.push_back(kv);
      } else {
        sumX[i] += weight[stage] * kx;
        sumV[i] += weight[stage] * kv;
      }
      if (stage < 3) {
        particles[i]->position() = prev[i].position() + kx * stepScale[stage];
        particles[i]->velocity() = prev[i].velocity() + kv * stepScale[stage];
      }
    }
  }
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = prev[i].position() + sumX[i] / 6.0f;
    particles[i]->velocity() = prev[i].velocity() + sumV[i] / 6.0f;
  }
}
