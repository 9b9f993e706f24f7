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
    // Write code here!
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x, v;
  for (auto p : particles) {
    x.push_back(p->position());
    v.push_back(p->velocity());
  }
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (int i = 0; i < (int)particles.size(); ++i) {
    particles[i]->position() = x[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x, v;
  for (auto p : particles) {
    x.push_back(p->position());
    v.push_back(p->velocity());
  }
  deltaTime /= 2;  // half step
  for (auto p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  deltaTime = 0.0001f;  // back to full step
  for (int i = 0; i < (int)particles.size(); ++i) {
    particles[i]->position() = x[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x, v;
  std::vector<Eigen::Matrix4Xf> dx[4], dv[4];
  for (auto p : particles) {
    x.push_back(p->position());
    v.push_back(p->velocity());
  }
  for (int k = 0; k < 4; ++k) {
    if (k > 0) {
      for (int i = 0; i < (int)particles.size(); ++i) {
        if (k == 3) {
          particles[i]->position() = x[i] + dx[2][i];
          particles[i]->velocity() = v[i] + dv[2][i];
        } else {
          particles[i]->position() = x[i] + dx[k - 1][i] * 0.5f;
          particles[i]->velocity() = v[i] + dv[k - 1][i] * 0.5f;
        }
      }
      simulateOneStep();
    }
    for (auto p : particles) {
      dx[k].push_back(p->velocity() * deltaTime);
      dv[k].push_back(p->acceleration() * deltaTime);
    }
  }
  for (int i = 0; i < (int)particles.size(); ++i) {
    particles[i]->position() = x[i] + (dx[0][i] + 2 * dx[1][i] + 2 * dx[2][i] + dx[3][i]) / 6;
    particles[i]->velocity() = v[i] + (dv[0][i] + 2 * dv[1][i] + 2 * dv[2][i] + dv[3][i]) / 6;
  }
}
