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
  //   3. This can be done in 5 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (auto p : particles) {
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
  std::vector<Eigen::Matrix4Xf> oldX, oldV;
  for (auto p : particles) {
    oldX.push_back(p->position());
    oldV.push_back(p->velocity());
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < particles.size(); i++) {
    particles[i]->position() = oldX[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = oldV[i] + particles[i]->acceleration() * deltaTime;
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
  const float half = 1 / 2;
  std::vector<Eigen::Matrix4Xf> oldX, oldV;
  for (auto p : particles) {
    oldX.push_back(p->position());
    oldV.push_back(p->velocity());
    p->position() += p->velocity() * deltaTime * half;
    p->velocity() += p->acceleration() * deltaTime * half;
  }
  simulateOneStep();
  for (int i = 0; i < particles.size(); i++) {
    particles[i]->position() = oldX[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = oldV[i] + particles[i]->acceleration() * deltaTime;
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
  std::vector<Eigen::Matrix4Xf> oldX, oldV, kx[4], kv[4];
  for (auto p : particles) {
    oldX.push_back(p->position());
    oldV.push_back(p->velocity());
  }
  float scale[4] = {0, 0.5, 0.5, 1};
  for (int s = 0; s < 4; s++) {
    if (s != 0) {
      for (int i = 0; i < particles.size(); i++) {
        particles[i]->position() = oldX[i] + kx[s - 1][i] * scale[s];
        particles[i]->velocity() = oldV[i] + kv[s - 1][i] * scale[s];
      }
      simulateOneStep();
    }
    for (auto p : particles) {
      kx[s].push_back(p->velocity() * deltaTime);
      kv[s].push_back(p->acceleration() * deltaTime);
    }
  }
  for (int i = 0; i < particles.size(); i++) {
    particles[i]->position() = oldX[i] + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() = oldV[i] + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
  }
}
