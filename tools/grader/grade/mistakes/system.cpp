// The integrator mistakes' state and clothref's step of it (system.h).
#include "grader/grade/mistakes/system.h"

#include <array>

#include "clothref/core/integrator.h"

namespace clothref::grader::integrators {

void simulate(System& s) {
  computeExternalForce(s.cloth.particles, s.gravity, s.viscous);
  if (s.sphere_gravity)
    computeExternalForce(s.spheres.particles, s.gravity, s.viscous);
  else
    s.spheres.particles.acceleration.setZero();
  computeSpringForce(s.cloth);
  if (s.contact) collide(s.spheres, s.cloth, s.restitution_cloth, s.correction);
}

Step clothrefStep(Method method, int bodies_integrated) {
  return [method, bodies_integrated](System& s) {
    std::array<Particles<float>*, 2> storage{&s.cloth.particles, &s.spheres.particles};
    IntegratorScratch<float> scratch;
    auto sim = [&] { simulate(s); };
    simulate(s);
    integrate(method, Bodies<float>(storage.data(), std::size_t(bodies_integrated)), s.dt,
              FunctionRef<void()>(sim), scratch);
  };
}

}  // namespace clothref::grader::integrators
