#include "integrator.h"

#include "configs.h"

// helpers
static std::vector<Particles> backupAll(const std::vector<Particles *> &particles) {
  std::vector<Particles> copies;
  copies.reserve(particles.size());
  for (const auto &p : particles) copies.push_back(*p);
  return copies;
}

static void eulerStep(Particles *p, float h) {
  p->position() += p->velocity() * h;
  p->velocity() += p->acceleration() * h;
}

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
    eulerStep(p, deltaTime);
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
  std::vector<Particles> start = backupAll(particles);
  for (const auto &p : particles) eulerStep(p, deltaTime);
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> start = backupAll(particles);
  const float halfStep = (1 / 2) * deltaTime;
  for (const auto &p : particles) eulerStep(p, halfStep);
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + particles[i]->acceleration() * deltaTime;
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
  std::vector<Particles> start = backupAll(particles);
  std::vector<Particles> k1 = backupAll(particles);  // derivative at start (velocity, acceleration)

  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + k1[i].velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = start[i].velocity() + k1[i].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  std::vector<Particles> k2 = backupAll(particles);

  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + k2[i].velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = start[i].velocity() + k2[i].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  std::vector<Particles> k3 = backupAll(particles);

  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + k3[i].velocity() * deltaTime;
    particles[i]->velocity() = start[i].velocity() + k3[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  std::vector<Particles> k4 = backupAll(particles);

  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + (k1[i].velocity() + 2.0f * k2[i].velocity() + 2.0f * k3[i].velocity() + k4[i].velocity()) * (deltaTime / 6.0f);
    particles[i]->velocity() = start[i].velocity() + (k1[i].acceleration() + 2.0f * k2[i].acceleration() + 2.0f * k3[i].acceleration() + k4[i].acceleration()) * (deltaTime / 6.0f);
  }
}
