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
}
