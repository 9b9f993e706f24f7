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
  for (Particles *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> old;
  for (Particles *p : particles) old.push_back(*p);
  for (Particles *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> old;
  for (Particles *p : particles) old.push_back(*p);
  for (Particles *p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  // particles[0] = cloth, particles[1] = sphere
  Particles *cloth = particles[0];
  Particles *ball = particles[1];
  auto clothX = cloth->position();
  auto clothV = cloth->velocity();
  auto ballX = ball->position();
  auto ballV = ball->velocity();

  Eigen::Matrix4Xf k1x = cloth->velocity() * deltaTime, k1v = cloth->acceleration() * deltaTime;
  Eigen::Matrix4Xf b1x = ball->velocity() * deltaTime, b1v = ball->acceleration() * deltaTime;
  cloth->position() = clothX + k1x / 2;
  cloth->velocity() = clothV + k1v / 2;
  ball->position() = ballX + b1x / 2;
  ball->velocity() = ballV + b1v / 2;
  simulateOneStep();

  Eigen::Matrix4Xf k2x = cloth->velocity() * deltaTime, k2v = cloth->acceleration() * deltaTime;
  Eigen::Matrix4Xf b2x = ball->velocity() * deltaTime, b2v = ball->acceleration() * deltaTime;
  cloth->position() = clothX + k2x / 2;
  cloth->velocity() = clothV + k2v / 2;
  ball->position() = ballX + b2x / 2;
  ball->velocity() = ballV + b2v / 2;
  simulateOneStep();

  Eigen::Matrix4Xf k3x = cloth->velocity() * deltaTime, k3v = cloth->acceleration() * deltaTime;
  Eigen::Matrix4Xf b3x = ball->velocity() * deltaTime, b3v = ball->acceleration() * deltaTime;
  cloth->position() = clothX + k3x;
  cloth->velocity() = clothV + k3v;
  ball->position() = ballX + b3x;
  ball->velocity() = ballV + b3v;
  simulateOneStep();

  Eigen::Matrix4Xf k4x = cloth->velocity() * deltaTime, k4v = cloth->acceleration() * deltaTime;
  Eigen::Matrix4Xf b4x = ball->velocity() * deltaTime, b4v = ball->acceleration() * deltaTime;
  cloth->position() = clothX + (k1x + 2 * k2x + 2 * k3x + k4x) / 6;
  cloth->velocity() = clothV + (k1v + 2 * k2v + 2 * k3v + k4v) / 6;
  ball->position() = ballX + (b1x + 2 * b2x + 2 * b3x + b4x) / 6;
  ball->velocity() = ballV + (b1v + 2 * b2v + 2 * b3v + b4v) / 6;
}
