// The odeint peer (odeint_peer.h) is what it claims: odeint's RK4 has order 4 on the spring's
// closed form, odeint's euler and symplectic_euler make exactly the library's explicit and
// symplectic steps (same roundings, so the same bits), contacts included for euler, and the peer
// refuses the worlds it cannot step.
#include "clothref/verify/odeint_peer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/scene/make_world.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/verify.h"

namespace clothref {
namespace {

Scene clothScene() {
  Scene scene = *findBuiltinScene("course2022");
  scene.spheres.reset();
  return scene;
}

// course2024's cloth on its sphere from the first step, without the frame loop.
Scene sphereScene() {
  Scene scene = *findBuiltinScene("course2024");
  scene.frame_loop.reset();
  return scene;
}

template <typename T>
void expectSameBits(const Particles<T>& a, const Particles<T>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (int i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(a.position(k, i), b.position(k, i)) << "particle " << i << " axis " << k;
      ASSERT_EQ(a.velocity(k, i), b.velocity(k, i)) << "particle " << i << " axis " << k;
    }
}

template <typename T>
void expectPeerIsTheLibrarysStep(const Scene& scene, PeerStepper stepper, int steps) {
  World<T> ours = makeWorld<T>(scene, peerCounterpart(stepper));
  World<T> theirs = makeWorld<T>(scene, Method::Explicit);
  OdeintPeer<T> peer(theirs, stepper);
  for (int k = 0; k < steps; ++k) {
    step(ours);
    peer.step();
  }
  EXPECT_EQ(theirs.step, steps);
  expectSameBits(ours.cloth->particles, theirs.cloth->particles);
  if (ours.spheres) expectSameBits(ours.spheres->particles, theirs.spheres->particles);
  // and the run went somewhere: a particle off the sphere fell
  const int particle = 6 * 25 + 6;
  const World<T> start = makeWorld<T>(scene, Method::Explicit);
  EXPECT_LT(double(ours.cloth->particles.position(1, particle)),
            double(start.cloth->particles.position(1, particle)) - 1e-4);
}

TEST(OdeintPeer, EulerAndSymplecticEulerMakeTheLibrarysStepsBitForBit) {
  for (PeerStepper stepper : {PeerStepper::Euler, PeerStepper::SymplecticEuler}) {
    SCOPED_TRACE(std::string(peerStepperName(stepper)));
    expectPeerIsTheLibrarysStep<double>(clothScene(), stepper, 200);
    expectPeerIsTheLibrarysStep<float>(clothScene(), stepper, 200);
  }
}

// Contacts as a force-free step: euler from the contact-resolved start state with the derivative
// evaluated before the contacts is the course's explicit step, sphere moved by the correction too.
TEST(OdeintPeer, EulerWithContactsIsTheLibrarysExplicitStep) {
  expectPeerIsTheLibrarysStep<double>(sphereScene(), PeerStepper::Euler, 200);
  expectPeerIsTheLibrarysStep<float>(sphereScene(), PeerStepper::Euler, 200);
}

// odeint's RK4 is RK4: on the damped spring its error against the closed form falls as dt^4.
TEST(OdeintPeer, Rk4HasOrderFourOnTheSpring) {
  const Scene scene = *findBuiltinScene("spring");
  const SpringProblem problem = springProblem(scene);
  std::vector<double> dts, errors;
  for (double dt : {0.04, 0.02, 0.01, 0.005}) {
    World<double> world = makeWorld<double>(scene, Method::Explicit, dt);
    OdeintPeer<double> peer(world, PeerStepper::Rk4);
    double error = 0;
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    for (int k = 1; k <= steps; ++k) {
      peer.step();
      const Eigen::Vector3d x(world.cloth->particles.position(0, problem.particle),
                              world.cloth->particles.position(1, problem.particle),
                              world.cloth->particles.position(2, problem.particle));
      error = std::max(error, (x - springState(problem, k * dt).position).norm());
    }
    dts.push_back(dt);
    errors.push_back(error);
  }
  EXPECT_NEAR(fitOrder(dts, errors), 4, 0.2);
  // the library's RK4 ladder reaches 1.5e-10 m at 1.25e-3 s (docs/verification.md): 4^4 times
  // that at 5e-3 s is 3.8e-8 m
  EXPECT_LT(errors.back(), 1e-7);
}

TEST(OdeintPeer, RefusesAFrameLoopAndSymplecticContacts) {
  World<double> course2024 = makeWorld<double>(*findBuiltinScene("course2024"), Method::Explicit);
  EXPECT_THROW(OdeintPeer<double>(course2024, PeerStepper::Rk4), InputError);
  World<double> contacts = makeWorld<double>(sphereScene(), Method::Explicit);
  EXPECT_THROW(OdeintPeer<double>(contacts, PeerStepper::SymplecticEuler), InputError);
  EXPECT_NO_THROW(OdeintPeer<double>(contacts, PeerStepper::Rk4));
}

}  // namespace
}  // namespace clothref
