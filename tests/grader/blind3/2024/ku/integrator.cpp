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
  // semi-implicit (symplectic) Euler: velocity first, then the position with the new velocity
  for (Particles *p : particles)
  {
    p->velocity() += p->acceleration() * deltaTime;
    p->position() += p->velocity() * deltaTime;
  }
}

void ImplicitEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const
{
  std::vector<Particles> initial;
  for (Particles *p : particles) initial.push_back(*p);
  for (Particles *p : particles)
  {
    p->position() += p->velocity() * deltaTime;
    p->velocity() += p->acceleration() * deltaTime;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = initial[b].position() + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = initial[b].velocity() + particles[b]->acceleration() * deltaTime;
  }
}

void MidpointEuler::integrate(const std::vector<Particles *> &particles,
                              std::function<void(void)> simulateOneStep) const
{
  std::vector<Particles> initial;
  for (Particles *p : particles) initial.push_back(*p);
  // half step, velocity first
  for (Particles *p : particles)
  {
    p->velocity() += p->acceleration() * deltaTime * 0.5f;
    p->position() += p->velocity() * deltaTime * 0.5f;
  }
  simulateOneStep();
  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = initial[b].position() + particles[b]->velocity() * deltaTime;
    particles[b]->velocity() = initial[b].velocity() + particles[b]->acceleration() * deltaTime;
  }
}

void RungeKuttaFourth::integrate(const std::vector<Particles *> &particles,
                                 std::function<void(void)> simulateOneStep) const
{
  struct Slope
  {
    Eigen::Matrix4Xf dx, dv;
  };
  std::vector<Particles> initial;
  for (Particles *p : particles) initial.push_back(*p);

  auto slopes = [&]()
  {
    std::vector<Slope> k;
    for (Particles *p : particles) k.push_back({(p->velocity() * deltaTime).eval(), (p->acceleration() * deltaTime).eval()});
    return k;
  };
  auto moveTo = [&](const std::vector<Slope> &k, float h)
  {
    for (std::size_t b = 0; b < particles.size(); ++b)
    {
      particles[b]->position() = initial[b].position() + k[b].dx * h;
      particles[b]->velocity() = initial[b].velocity() + k[b].dv * h;
    }
    simulateOneStep();
  };

  const std::vector<Slope> k1 = slopes();
  moveTo(k1, 0.5f);
  const std::vector<Slope> k2 = slopes();
  moveTo(k2, 0.5f);
  const std::vector<Slope> k3 = slopes();
  moveTo(k3, 1.0f);
  const std::vector<Slope> k4 = slopes();

  for (std::size_t b = 0; b < particles.size(); ++b)
  {
    particles[b]->position() = initial[b].position() + (k1[b].dx + 2 * k2[b].dx + 2 * k3[b].dx + k4[b].dx) / 6;
    particles[b]->velocity() = initial[b].velocity() + (k1[b].dv + 2 * k2[b].dv + 2 * k3[b].dv + k4[b].dv) / 6;
  }
  // std::cout << particles[0]->position(312).transpose() << std::endl;
}
