#include "integrator.h"

#include "configs.h"

// 備份用：整個 Particles 複製一份（不是指標）
static std::vector<Particles> snapshot(const std::vector<Particles *> &particles)
{
  std::vector<Particles> copies;
  copies.reserve(particles.size());
  for (Particles *p : particles)
  {
    copies.push_back(*p);
  }
  return copies;
}

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
  // 先更新速度再用新速度更新位置（symplectic，助教說也可以）
  for (Particles *p : particles)
  {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
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
  const std::vector<Particles> start = snapshot(particles);
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() += particles[b]->velocity() * deltaTime;
    particles[b]->velocity() += particles[b]->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    Particles start_b = start[b];
    particles[b]->position() = start_b.position() + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = start_b.velocity() + particles[b]->acceleration() * deltaTime;
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
  const std::vector<Particles> start = snapshot(particles);
  for (Particles *p : particles)
  {
    p->position() += p->velocity() * deltaTime * 0.5f;
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
  }
  simulateOneStep();
  int b = 0;
  for (Particles *p : particles)
  {
    Particles s = start[b++];
    p->position() = s.position() + p->velocity() * deltaTime;
    p->velocity() = s.velocity() + p->acceleration() * deltaTime;
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
  std::vector<Particles> start = snapshot(particles);
  // k[stage][body]，用 Particles 當容器：position 放 dx，velocity 放 dv
  std::vector<std::vector<Particles>> k(4, start);
  const float stageScale[3] = {0.5f, 0.5f, 1.0f};

  auto grab = [&](int stage)
  {
    for (std::size_t b = 0; b < particles.size(); ++b)
    {
      k[stage][b].position() = particles[b]->velocity() * deltaTime;
      k[stage][b].velocity() = particles[b]->acceleration() * deltaTime;
    }
  };

  grab(0);
  for (int stage = 1; stage < 4; ++stage)
  {
    for (std::size_t b = 0; b < particles.size(); ++b)
    {
      particles[b]->position() = start[b].position() + k[stage - 1][b].position() * stageScale[stage - 1];
      particles[b]->velocity() = start[b].velocity() + k[stage - 1][b].velocity() * stageScale[stage - 1];
    }
    simulateOneStep();
    grab(stage);
  }
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = start[b].position() + (k[0][b].position() + 2 * k[1][b].position() + 2 * k[2][b].position() + k[3][b].position()) / 6;
    particles[b]->velocity() = start[b].velocity() + (k[0][b].velocity() + 2 * k[1][b].velocity() + 2 * k[2][b].velocity() + k[3][b].velocity()) / 6;
  }
}
