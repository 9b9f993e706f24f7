#include "integrator.h"

#include "configs.h"

namespace {
// 四個角固定不動
void pinCorners(Particles *p) {
  if (p->getCapacity() != particlesPerEdge * particlesPerEdge) return;  // 球不用
  const int corners[4] = {0, particlesPerEdge - 1, particlesPerEdge * (particlesPerEdge - 1),
                          particlesPerEdge * particlesPerEdge - 1};
  for (int c : corners) p->velocity(c).setZero();
}
}  // namespace
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
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Matrix4Xf> x0, v0;
  for (auto *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Eigen::Ref<Eigen::Matrix4Xf>> x0, v0;
  for (auto *p : particles) {
    x0.push_back(p->position());
    v0.push_back(p->velocity());
  }
  for (auto *p : particles) {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = x0[i] + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = v0[i] + particles[i]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const {
  // Write code here!
  std::vector<Particles> start;
  for (auto *p : particles) start.push_back(*p);
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  for (auto *p : particles) {
    kx[0].push_back(p->velocity() * deltaTime);
    kv[0].push_back(p->acceleration() * deltaTime);
  }
  const float half[3] = {0.5f, 0.5f, 1.0f};
  for (int s = 1; s < 4; ++s) {
    for (size_t i = 0; i < particles.size(); ++i) {
      particles[i]->position() = start[i].position() + kx[s - 1][i] * half[s - 1];
      particles[i]->velocity() = start[i].velocity() + kv[s - 1][i] * half[s - 1];
      pinCorners(particles[i]);
    }
    simulateOneStep();
    for (auto *p : particles) {
      kx[s].push_back(p->velocity() * deltaTime);
      kv[s].push_back(p->acceleration() * deltaTime);
    }
  }
  for (size_t i = 0; i < particles.size(); ++i) {
    particles[i]->position() = start[i].position() + (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]) / 6;
    particles[i]->velocity() = start[i].velocity() + (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]) / 6;
    pinCorners(particles[i]);
  }
}
