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
  //   3. This can be done in 2 lines. (Hint: you can add / multiply all the particles at once, they are
  //      one large matrix.)
  for (const auto &p : particles) {
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < (int)particles.size(); i++) {
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
  for (int i = 0; i < (int)particles.size(); i++) {
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
  // 先存原本的位置、速度
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);
  // 加權總和 (k1 + 2k2 + 2k3 + k4)
  std::vector<Eigen::Matrix4Xf> sumX, sumV;
  for (auto p : particles) {
    sumX.emplace_back(4, p->getCapacity());
    sumV.emplace_back(4, p->getCapacity());
  }
  const float half[4] = {0.5f, 0.5f, 1.0f, 0.0f};
  const float weight[4] = {1.0f, 2.0f, 2.0f, 1.0f};
  for (int stage = 0; stage < 4; stage++) {
    for (int i = 0; i < (int)particles.size(); i++) {
      Eigen::Matrix4Xf kx = particles[i]->velocity() * deltaTime;
      Eigen::Matrix4Xf kv = particles[i]->acceleration() * deltaTime;
      sumX[i] += weight[stage] * kx;
      sumV[i] += weight[stage] * kv;
      if (stage < 3) {
        particles[i]->position() = old[i].position() + kx * half[stage];
        particles[i]->velocity() = old[i].velocity() + kv * half[stage];
      }
    }
    if (stage < 3) simulateOneStep();
  }
  for (int i = 0; i < (int)particles.size(); i++) {
    particles[i]->position() = old[i].position() + sumX[i] / 6;
    particles[i]->velocity() = old[i].velocity() + sumV[i] / 6;
  }
}
