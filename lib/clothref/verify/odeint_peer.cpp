// The odeint peer (odeint_peer.h): the world's bodies as odeint state vectors, the library's
// evaluation as odeint's system function, odeint's steppers doing the stepping.
#include "clothref/verify/odeint_peer.h"

#include <array>
#include <boost/numeric/odeint/stepper/euler.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/symplectic_euler.hpp>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "clothref/io/error.h"

namespace clothref {

namespace odeint = boost::numeric::odeint;

template <typename T>
struct OdeintPeer<T>::Odeint {
  using State = std::vector<T>;
  odeint::euler<State, T, State, T> euler;
  odeint::runge_kutta4<State, T, State, T> rk4;
  odeint::symplectic_euler<State, State, T, State, State, T> symplectic;
  State y;     // (x, v): 3N positions, then 3N velocities
  State dydt;  // (v after contacts, a) at y
  State x, v;  // symplectic Euler's halves
  T time = T(0);
};

namespace {

// Every body in the course's order (cloth, then spheres).
template <typename T>
std::vector<Particles<T>*> bodyList(World<T>& world) {
  std::array<Particles<T>*, 2> storage{};
  const Bodies<T> all = bodies(world, storage);
  return {all.begin(), all.end()};
}

template <typename T>
std::size_t particleCount(World<T>& world) {
  std::size_t count = 0;
  for (Particles<T>* p : bodyList(world)) count += std::size_t(p->size());
  return count;
}

// Copies the rows 0..2 of `column` (position, velocity or acceleration) of every particle into
// out[offset ...], 3 values per particle.
template <typename T>
void gather(World<T>& world, Mat4X<T> Particles<T>::*column, std::vector<T>& out,
            std::size_t offset) {
  for (Particles<T>* p : bodyList(world))
    for (int i = 0; i < p->size(); ++i)
      for (int k = 0; k < 3; ++k) out[offset++] = ((*p).*column)(k, i);
}

// The inverse: rows 0..2 of `column` from in[offset ...]; w stays as it is (1 for positions,
// 0 for velocities).
template <typename T>
void scatter(World<T>& world, Mat4X<T> Particles<T>::*column, const std::vector<T>& in,
             std::size_t offset) {
  for (Particles<T>* p : bodyList(world))
    for (int i = 0; i < p->size(); ++i)
      for (int k = 0; k < 3; ++k) ((*p).*column)(k, i) = in[offset++];
}

}  // namespace

template <typename T>
OdeintPeer<T>::OdeintPeer(World<T>& world, PeerStepper stepper)
    : world_(world), stepper_(stepper), odeint_(std::make_unique<Odeint>()) {
  const std::string name(peerStepperName(stepper));
  if (world.frame_loop.steps_per_frame > 0)
    throw InputError(name +
                     ": the peer steps worlds without a frame loop (the 2024 per-frame "
                     "work is the course program's, not the integrator's)");
  if (stepper == PeerStepper::SymplecticEuler && world.cloth && world.spheres)
    throw InputError(name +
                     ": odeint's symplectic Euler cannot take the contacts' position "
                     "correction (a world with cloth and spheres)");
  const std::size_t n = 3 * particleCount(world);
  odeint_->y.assign(2 * n, T(0));
  odeint_->dydt.assign(2 * n, T(0));
  odeint_->x.assign(n, T(0));
  odeint_->v.assign(n, T(0));
}

template <typename T>
OdeintPeer<T>::~OdeintPeer() = default;

template <typename T>
void OdeintPeer<T>::step() {
  using State = typename Odeint::State;
  Odeint& o = *odeint_;
  World<T>& world = world_;
  const T dt = world.physics.dt;
  const std::size_t n = o.x.size();
  if (stepper_ == PeerStepper::SymplecticEuler) {
    gather(world, &Particles<T>::position, o.x, 0);
    gather(world, &Particles<T>::velocity, o.v, 0);
    // q = v, p = x: q += dt a(x, v) with v read from the state being stepped; then p += dt q
    State& v = o.v;
    auto acceleration = [&world, &v](const State& x, State& dvdt) {
      scatter(world, &Particles<T>::position, x, 0);
      scatter(world, &Particles<T>::velocity, v, 0);
      simulateOneStep(world);
      gather(world, &Particles<T>::acceleration, dvdt, 0);
    };
    auto velocity = [](const State& q, State& dxdt) { dxdt = q; };
    o.symplectic.do_step(std::make_pair(acceleration, velocity),
                         std::make_pair(std::ref(o.v), std::ref(o.x)), o.time, dt);
    scatter(world, &Particles<T>::position, o.x, 0);
    scatter(world, &Particles<T>::velocity, o.v, 0);
  } else {
    // the system: the library's evaluation at y; its contacts change the derivative only
    auto system = [&world, n](const State& y, State& dydt, T /*t*/) {
      scatter(world, &Particles<T>::position, y, 0);
      scatter(world, &Particles<T>::velocity, y, n);
      simulateOneStep(world);
      gather(world, &Particles<T>::velocity, dydt, 0);
      gather(world, &Particles<T>::acceleration, dydt, n);
    };
    // the step's start: evaluate at y_n; its contacts are the force-free step y_n -> C(y_n)
    gather(world, &Particles<T>::position, o.y, 0);
    gather(world, &Particles<T>::velocity, o.y, n);
    system(o.y, o.dydt, o.time);
    gather(world, &Particles<T>::position, o.y, 0);
    gather(world, &Particles<T>::velocity, o.y, n);
    if (stepper_ == PeerStepper::Euler)
      o.euler.do_step(system, o.y, o.dydt, o.time, dt);
    else
      o.rk4.do_step(system, o.y, o.dydt, o.time, dt);
    scatter(world, &Particles<T>::position, o.y, 0);
    scatter(world, &Particles<T>::velocity, o.y, n);
  }
  o.time += dt;
  ++world.step;
}

template class OdeintPeer<float>;
template class OdeintPeer<double>;

}  // namespace clothref
