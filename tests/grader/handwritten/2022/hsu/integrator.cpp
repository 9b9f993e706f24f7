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
  // Write code here!
  std::vector<Particles> saved;
  for (Particles* p : particles) saved.push_back(*p);
  for (Particles* p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    Particles* p = particles[k];
    p->position() = saved[k].position() + p->velocity() * deltaTime;
    p->velocity() = saved[k].velocity() + p->acceleration() * deltaTime;
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
  std::vector<Particles> saved;
  for (Particles* p : particles) saved.push_back(*p);
  for (Particles* p : particles) {
    p->position() += p->velocity() * (deltaTime * 0.5f);
    p->velocity() += p->acceleration() * (deltaTime * 0.5f);
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    Particles* p = particles[k];
    p->position() = saved[k].position() + p->velocity() * deltaTime;
    p->velocity() = saved[k].velocity() + p->acceleration() * deltaTime;
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
  std::vector<Particles> saved;
  for (Particles* p : particles) saved.push_back(*p);
  std::vector<Eigen::Matrix4Xf> dx(particles.size()), dv(particles.size());
  const float stageFactor[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  const float weight[4] = {1.0f, 2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) simulateOneStep();
    for (size_t k = 0; k < particles.size(); ++k) {
      Particles* p = particles[k];
      Eigen::Matrix4Xf kx = p->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = p->acceleration() * deltaTime;
      if (stage == 0) {
        dx[k] = kx;
        dv[k] = kv;
      } else {
        dx[k] += weight[stage] * kx;
        dv[k] += weight[stage] * kv;
      }
      if (stage < 3) {
        p->position() = saved[k].position() + kx * stageFactor[stage];
        p->velocity() = saved[k].velocity() + kv * stageFactor[stage];
      }
    }
  }
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = saved[k].position() + dx[k] / 6.0f;
    particles[k]->velocity() = saved[k].velocity() + dv[k] / 6.0f;
  }
}
