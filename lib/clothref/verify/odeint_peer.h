// Boost.Odeint as an independent peer of the library's integrators: odeint's `euler`,
// `runge_kutta4` and `symplectic_euler` step a World from the library's own evaluation
// (simulateOneStep), so the only code the peer does not share with the library is the stepping:
// the stages, their weights and the order of the updates (docs/verification.md, "Boost.Odeint").
//
// The state is every particle of every body (cloth, then spheres): y = (x, v), 3N values each, in
// the world's precision T. The derivative of y is (v after the evaluation's contacts, a).
//
// Contacts as a force-free step. The course's step evaluates at the step's start, and that
// evaluation's contacts move the bodies (impulses change v, the correction moves x) before the
// integrator backs up x0 and v0. The peer does the same in odeint's terms: it evaluates at y_n,
// takes the contact-resolved state C(y_n) as the step's start and hands odeint the derivative it
// just evaluated (odeint's do_step(system, x, dxdt, t, dt)); the stage evaluations are odeint's
// calls of the system, whose contacts change the stage's derivative but never the stage's state
// (the course's RK4 also overwrites the stage positions). Euler and RK4 support contacts.
//
// Symplectic Euler. odeint's symplectic_euler updates its first half q from the second, q += dt
// f(p), then the second from the new first, p += dt g(q). With q = v and p = x that is the
// course's symplectic Euler (v += a dt, then x += v dt). odeint's symplectic steppers take
// f(p) alone; the cloth's damper and drag make a depend on v as well, so f reads v from the state
// being stepped in place, which odeint updates only after calling f. No contacts (the stepper
// cannot move x inside f): a world with spheres and cloth is refused.
#pragma once

#include <memory>

#include "clothref/base/enum_table.h"
#include "clothref/core/method.h"
#include "clothref/core/world.h"

namespace clothref {

enum class PeerStepper { Euler, Rk4, SymplecticEuler };

inline constexpr EnumTable<PeerStepper, 3> kPeerStepperNames{{
    {PeerStepper::Euler, "odeint-euler"},
    {PeerStepper::Rk4, "odeint-rk4"},
    {PeerStepper::SymplecticEuler, "odeint-symplectic-euler"},
}};

constexpr std::string_view peerStepperName(PeerStepper stepper) {
  return enumName(kPeerStepperNames, stepper);
}

// The library's method that computes the same step as `stepper` (explicit, rk4, symplectic).
constexpr Method peerCounterpart(PeerStepper stepper) {
  switch (stepper) {
    case PeerStepper::Euler:
      return Method::Explicit;
    case PeerStepper::Rk4:
      return Method::Rk4;
    case PeerStepper::SymplecticEuler:
      return Method::Symplectic;
  }
  return Method::Explicit;
}

// Steps a world with one of odeint's steppers. The world keeps the state between steps (read it
// as after World's step); its `method` is ignored, its step count advances. Construction throws
// InputError for a world the peer cannot step: one with a frame loop (the 2024 per-frame work),
// or contacts under SymplecticEuler.
template <typename T>
class OdeintPeer {
 public:
  OdeintPeer(World<T>& world, PeerStepper stepper);
  ~OdeintPeer();
  OdeintPeer(const OdeintPeer&) = delete;
  OdeintPeer& operator=(const OdeintPeer&) = delete;

  // One step of world.physics.dt.
  void step();

  PeerStepper stepper() const { return stepper_; }

 private:
  struct Odeint;  // odeint's stepper and the state vectors (odeint_peer.cpp)
  World<T>& world_;
  PeerStepper stepper_;
  std::unique_ptr<Odeint> odeint_;
};

}  // namespace clothref
