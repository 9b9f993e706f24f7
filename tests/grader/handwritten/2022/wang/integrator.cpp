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
    // x(t+h) = x + v h + 1/2 a h^2  (more accurate than x + v h)
    p->position() += p->velocity() * deltaTime + 0.5f * p->acceleration() * deltaTime * deltaTime;
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
  std::vector<Particles> old;
  for (auto p : particles) old.push_back(*p);

  // guess X(n+1) with explicit euler
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();  // a(n+1)

  // backward euler: v(n+1) = v(n) + a(n+1) h, x(n+1) = x(n) + v(n+1) h
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
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
  for (auto p : particles) {
    Particles old = *p;
    // half step
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
    simulateOneStep();
    // full step with midpoint derivative
    p->position() = old.position() + p->velocity() * deltaTime;
    p->velocity() = old.velocity() + p->acceleration() * deltaTime;
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
  std::vector<Particles> s0, s1, s2, s3;
  for (auto p : particles) s0.push_back(*p);

  // stage 2: x0 + k1 / 2
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = s0[i].position() + s0[i].velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = s0[i].velocity() + s0[i].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (auto p : particles) s1.push_back(*p);

  // stage 3: x0 + k2 / 2
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = s0[i].position() + s1[i].velocity() * deltaTime * 0.5f;
    particles[i]->velocity() = s0[i].velocity() + s1[i].acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (auto p : particles) s2.push_back(*p);

  // stage 4: x0 + k3
  for (size_t i = 0; i < particles.size(); i++) {
    particles[i]->position() = s0[i].position() + s2[i].velocity() * deltaTime;
    particles[i]->velocity() = s0[i].velocity() + s2[i].acceleration() * deltaTime;
  }
  simulateOneStep();
  for (auto p : particles) s3.push_back(*p);

  for (size_t i = 0; i < particles.size(); i++) {
    Eigen::Matrix4Xf dx = s0[i].velocity() + 2 * s1[i].velocity() + 2 * s2[i].velocity() + s3[i].velocity();
    Eigen::Matrix4Xf dv = s0[i].acceleration() + 2 * s1[i].acceleration() + 2 * s2[i].acceleration() + s3[i].acceleration();
    particles[i]->position() = s0[i].position() + dx * deltaTime / 6;
    particles[i]->velocity() = s0[i].velocity() + dv * deltaTime / 6;
  }
}
