// verify's peer family: the library's explicit, RK4 and symplectic Euler against Boost.Odeint's
// euler, runge_kutta4 and symplectic_euler (odeint_peer.h) on the course cloth, step by step.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/verify/check_support.h"
#include "clothref/verify/odeint_peer.h"
#include "clothref/verify/verify.h"

namespace clothref {

using namespace verify_support;

namespace {

// The course cloth alone: course2022 without its spheres (25 x 25, corners fixed, gravity, drag).
Scene peerClothScene() {
  Scene scene = *findBuiltinScene("course2022");
  scene.name = "course2022 cloth, no spheres";
  scene.spheres.reset();
  return scene;
}

// The course cloth on a fixed sphere: course2024's cloth (y = 1, k = 20000) and sphere (r = 1 at
// the origin, touching the cloth's centre at the start), the sphere immovable in the impulse
// (mass 0), without the 2024 frame loop. The correction still moves it (it ignores mass).
Scene peerSphereScene() {
  Scene scene = *findBuiltinScene("course2024");
  scene.name = "course2024 cloth on a fixed sphere";
  scene.frame_loop.reset();
  scene.spheres->items[0].mass = 0;
  return scene;
}

// The double world the peer steps beside `ours`: for a double run the same scene again; for a
// float run the float world's own numbers in double (positions, rest lengths, masses, the
// physics), so that the rows see arithmetic alone, not the rounding of the scene's inputs.
template <typename T>
World<double> peerWorld(const Scene& scene, const World<T>& ours) {
  World<double> peer = makeWorld<double>(scene, Method::Explicit);
  if constexpr (std::is_same_v<T, float>) {
    auto widen = [](const Particles<float>& from, Particles<double>& to) {
      to.position = from.position.cast<double>();
      to.velocity = from.velocity.cast<double>();
      to.acceleration = from.acceleration.cast<double>();
      to.mass = from.mass.cast<double>();
      to.inverse_mass = from.inverse_mass.cast<double>();
    };
    if (ours.cloth) {
      widen(ours.cloth->particles, peer.cloth->particles);
      for (std::size_t s = 0; s < ours.cloth->springs.size(); ++s)
        peer.cloth->springs[s].rest_length = double(ours.cloth->springs[s].rest_length);
      peer.cloth->spring_coef = double(ours.cloth->spring_coef);
      peer.cloth->damper_coef = double(ours.cloth->damper_coef);
    }
    if (ours.spheres) {
      widen(ours.spheres->particles, peer.spheres->particles);
      for (std::size_t s = 0; s < ours.spheres->radius.size(); ++s)
        peer.spheres->radius[s] = double(ours.spheres->radius[s]);
    }
    const Physics<float>& from = ours.physics;
    Physics<double>& to = peer.physics;
    to.dt = double(from.dt);
    to.gravity = from.gravity.cast<double>();
    to.viscous_coef = double(from.viscous_coef);
    to.restitution_cloth = double(from.restitution_cloth);
    to.restitution_sphere = double(from.restitution_sphere);
    to.correction = double(from.correction);
    // the fast kernels keep their own copy of the rest lengths: prepare them again
    setExecution(peer, true, fast::defaultSimdPath(), 1);
  }
  return peer;
}

// The largest position difference between the library's run and the peer's over every step and
// particle, and the size its tolerance scales with.
struct Agreement {
  double position = 0;  // max |x - x_peer| (m)
  double x_scale = 0;   // max |x| + T max |v| (m), from the peer's run
  bool finite = true;
};

template <typename T>
void compareBodies(const Particles<T>& ours, const Particles<double>& peer, Agreement& agreement,
                   double& x_max, double& v_max) {
  for (int i = 0; i < ours.size(); ++i) {
    const Eigen::Vector3d xp = xyz(peer.position.col(i));
    agreement.position = std::max(agreement.position, (xyz(ours.position.col(i)) - xp).norm());
    x_max = std::max(x_max, xp.norm());
    v_max = std::max(v_max, xyz(peer.velocity.col(i)).norm());
  }
}

template <typename T>
Agreement agreement(const Scene& scene, PeerStepper stepper, int steps) {
  World<T> ours = makeWorld<T>(scene, peerCounterpart(stepper));
  World<double> peer_world = peerWorld(scene, ours);
  OdeintPeer<double> peer(peer_world, stepper);
  Agreement result;
  double x_max = 0, v_max = 0;
  for (int k = 0; k < steps; ++k) {
    step(ours);
    peer.step();
    if (ours.cloth)
      compareBodies(ours.cloth->particles, peer_world.cloth->particles, result, x_max, v_max);
    if (ours.spheres)
      compareBodies(ours.spheres->particles, peer_world.spheres->particles, result, x_max, v_max);
  }
  result.finite = isFinite(ours) && isFinite(peer_world);
  result.x_scale = x_max + double(steps) * double(ours.physics.dt) * v_max;
  return result;
}

}  // namespace

std::vector<CheckRow> peerChecks() {
  struct Case {
    Scene scene;
    std::vector<PeerStepper> steppers;
    std::vector<Precision> precisions;
  };
  const std::vector<Case> cases = {
      {peerClothScene(),
       {PeerStepper::Euler, PeerStepper::Rk4, PeerStepper::SymplecticEuler},
       {Precision::Double, Precision::Float}},
      {peerSphereScene(), {PeerStepper::Euler, PeerStepper::Rk4}, {Precision::Double}},
  };
  std::vector<CheckRow> rows;
  for (const Case& c : cases) {
    for (Precision precision : c.precisions) {
      for (PeerStepper stepper : c.steppers) {
        const Agreement a = withPrecision(
            precision, [&]<typename T>() { return agreement<T>(c.scene, stepper, kPeerSteps); });
        const Method method = peerCounterpart(stepper);
        // per step and evaluation one rounding of each position and velocity update, as in the
        // closed-form rows (check_support.h roundoffBound; docs/verification.md)
        const double roundings = double(kPeerSteps) * methodInfo(method).evaluations;
        rows.push_back(
            makeRow(fmt::format("odeint peer: max |x - x_{}| (m), {}, {} steps of {:g} s{}",
                                peerStepperName(stepper), c.scene.name, kPeerSteps, c.scene.dt,
                                a.finite ? "" : " (NOT FINITE)"),
                    std::string(methodName(method)), precision, 0,
                    a.finite ? a.position : std::numeric_limits<double>::quiet_NaN(),
                    roundoffEstimate(roundings, precision, a.x_scale)));
      }
    }
  }
  return rows;
}

}  // namespace clothref
