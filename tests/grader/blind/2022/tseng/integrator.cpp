#include "integrator.h"

#include "configs.h"

// curtain test: hang the cloth on its top edge (for the report)
static void constraint(Particles *p)
{
	if (p->getCapacity() != particlesPerEdge * particlesPerEdge) return;  // only the cloth
	for (int j = 0; j < 25; j++)
	{
		p->velocity(j).setZero();
	}
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
  for (const auto &p : particles)
  {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
    constraint(p);
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
  std::vector<Particles> old;
  for (const auto &p : particles) old.push_back(*p);

  for (const auto &p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (size_t i = 0; i < particles.size(); i++)
  {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
    constraint(particles[i]);
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
  std::vector<Particles> old;
  for (const auto &p : particles) old.push_back(*p);

  deltaTime /= 2;  // half step
  for (const auto &p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  deltaTime = 0.0001f;  // back to normal
  for (size_t i = 0; i < particles.size(); i++)
  {
    particles[i]->position() = old[i].position() + particles[i]->velocity() * deltaTime;
    particles[i]->velocity() = old[i].velocity() + particles[i]->acceleration() * deltaTime;
    constraint(particles[i]);
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
  std::vector<Particles> old;
  for (const auto &p : particles) old.push_back(*p);
  size_t n = particles.size();
  std::vector<Eigen::Matrix4Xf> kx[4], kv[4];
  float factor[3] = {0.5f, 0.5f, 1.0f};

  for (int stage = 0; stage < 4; stage++)
  {
    if (stage != 0) simulateOneStep();
    for (size_t i = 0; i < n; i++)
    {
      kx[stage].push_back(particles[i]->velocity() * deltaTime);
      kv[stage].push_back(particles[i]->acceleration() * deltaTime);
      if (stage == 3) continue;
      particles[i]->position() = old[i].position() + kx[stage][i] * factor[stage];
      particles[i]->velocity() = old[i].velocity() + kv[stage][i] * factor[stage];
    }
  }
  for (size_t i = 0; i < n; i++)
  {
    particles[i]->position() = old[i].position() + (kx[0][i] + 2.0f * kx[1][i] + 2.0f * kx[2][i] + kx[3][i]) / 6.0f;
    particles[i]->velocity() = old[i].velocity() + (kv[0][i] + 2.0f * kv[1][i] + 2.0f * kv[2][i] + kv[3][i]) / 6.0f;
    constraint(particles[i]);
  }
}
