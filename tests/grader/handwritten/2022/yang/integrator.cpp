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
    for (int i = 0; i < p->getCapacity(); ++i) {
      p->position(i) += p->velocity(i) * deltaTime;
      p->velocity(i) += p->acceleration(i) * deltaTime;
    }
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
  // backup x_n, v_n, a_n
  std::vector<Eigen::Matrix4Xf> x0, v0, a0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
    a0.push_back(p->acceleration());
  }
  // predict x_{n+1} with explicit euler
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k] + v0[k] * deltaTime;
    particles[k]->velocity() = v0[k] + a0[k] * deltaTime;
  }
  simulateOneStep();
  // average the slope at n and at n+1 (more stable)
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k] + (v0[k] + particles[k]->velocity()) / 2 * deltaTime;
    particles[k]->velocity() = v0[k] + (a0[k] + particles[k]->acceleration()) / 2 * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (const auto &p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k] + particles[k]->velocity() * deltaTime / 2;
    particles[k]->velocity() = v0[k] + particles[k]->acceleration() * deltaTime / 2;
  }
  simulateOneStep();
  for (size_t k = 0; k < particles.size(); ++k) {
    particles[k]->position() = x0[k] + particles[k]->velocity() * deltaTime;
    particles[k]->velocity() = v0[k] + particles[k]->acceleration() * deltaTime;
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
  const size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> x0(n), v0(n), kx(n), kv(n), sumX(n), sumV(n);
  const float dt = deltaTime;

  auto takeK = [&](float w) {
    for (size_t k = 0; k < n; ++k) {
      kx[k] = particles[k]->velocity() * dt;
      kv[k] = particles[k]->acceleration() * dt;
      sumX[k] += w * kx[k];
      sumV[k] += w * kv[k];
    }
  };
  // move to x0 + h * (v0 + kv * c)
  auto moveTo = [&](float c) {
    for (size_t k = 0; k < n; ++k) {
      particles[k]->velocity() = v0[k] + kv[k] * c;
      particles[k]->position() = x0[k] + dt * (v0[k] + kv[k] * c) * c;
    }
  };

  for (size_t k = 0; k < n; ++k) {
    x0[k] = particles[k]->position();
    v0[k] = particles[k]->velocity();
    sumX[k] = Eigen::Matrix4Xf::Zero(4, x0[k].cols());
    sumV[k] = Eigen::Matrix4Xf::Zero(4, x0[k].cols());
  }
  takeK(1.0f);    // k1
  moveTo(0.5f);
  simulateOneStep();
  takeK(2.0f);    // k2
  moveTo(0.5f);
  simulateOneStep();
  takeK(2.0f);    // k3
  moveTo(1.0f);
  simulateOneStep();
  takeK(1.0f);    // k4
  for (size_t k = 0; k < n; ++k) {
    particles[k]->position() = x0[k] + sumX[k] / 6.0f;
    particles[k]->velocity() = v0[k] + sumV[k] / 6.0f;
  }
}
