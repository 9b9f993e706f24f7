#include "clothref/scene/make_world.h"

#include <algorithm>

#include "clothref/solver/backward_euler.h"

namespace clothref {

namespace {

template <typename T>
Vec4<T> point(const Vector3& v) {
  return Vec4<T>(T(v[0]), T(v[1]), T(v[2]), T(1));
}

template <typename T>
Vec4<T> direction(const Vector3& v) {
  return Vec4<T>(T(v[0]), T(v[1]), T(v[2]), T(0));
}

template <typename T>
Cloth<T> makeCloth(const ClothSpec& spec) {
  Cloth<T> cloth;
  cloth.spring_coef = T(spec.spring_coef);
  cloth.damper_coef = T(spec.damper_coef);
  if (spec.grid) {
    const GridSpec& grid = *spec.grid;
    cloth.particles = initializeVertex<T>(grid.particles_per_edge, T(grid.half_extent), T(grid.y),
                                          T(grid.particle_mass));
    for (int i : spec.fixed) setMass(cloth.particles, i, T(0));
    initializeSpring(cloth, grid.particles_per_edge);
    return cloth;
  }
  const int count = static_cast<int>(spec.particles.size());
  cloth.particles = makeParticles<T>(count, T(0));
  for (int i = 0; i < count; ++i) {
    cloth.particles.position.col(i) = point<T>(spec.particles[i].position);
    cloth.particles.velocity.col(i) = direction<T>(spec.particles[i].velocity);
    setMass(cloth.particles, i, T(spec.particles[i].mass));
  }
  for (int i : spec.fixed) setMass(cloth.particles, i, T(0));
  for (const SpringSpec& s : spec.springs) {
    // the start index is the smaller one, as in the course's grid
    const int start = std::min(s.start, s.end);
    const int end = std::max(s.start, s.end);
    cloth.springs.push_back(Spring<T>{static_cast<std::uint32_t>(start),
                                      static_cast<std::uint32_t>(end), T(s.rest_length),
                                      SpringType::Structural});
  }
  return cloth;
}

template <typename T>
Spheres<T> makeSpheres(const SpheresSpec& spec) {
  Spheres<T> spheres;
  spheres.particles = makeParticles<T>(0, T(0));
  for (const SphereSpec& item : spec.items) {
    const int i = spheres.size();
    addSphere(spheres, point<T>(item.center), T(item.radius), T(spec.density));
    spheres.particles.velocity.col(i) = direction<T>(item.velocity);
    if (item.mass) setMass(spheres.particles, i, T(*item.mass));
  }
  return spheres;
}

}  // namespace

template <typename T>
World<T> makeWorld(const Scene& scene, Method method, std::optional<double> dt) {
  // scenes built in code get the same checks as scene files: a bad index would write out of bounds
  validateScene(scene);
  World<T> world;
  world.method = method;
  Physics<T>& physics = world.physics;
  physics.dt = T(dt.value_or(scene.dt));
  physics.gravity = direction<T>(scene.gravity);
  physics.viscous_coef = T(scene.viscous_coef);
  if (scene.cloth) world.cloth = makeCloth<T>(*scene.cloth);
  if (scene.spheres) {
    const SpheresSpec& spec = *scene.spheres;
    world.spheres = makeSpheres<T>(spec);
    physics.sphere_external_force = spec.external_force;
    physics.sphere_sphere_collision = spec.sphere_sphere_collision;
    physics.restitution_cloth = T(spec.restitution_cloth);
    physics.restitution_sphere = T(spec.restitution_sphere);
    physics.correction = T(spec.correction);
  }
  if (scene.frame_loop) {
    world.frame_loop.steps_per_frame = scene.frame_loop->steps_per_frame;
    world.frame_loop.sphere_velocity = direction<T>(scene.frame_loop->sphere_velocity);
    if (scene.cloth) world.frame_loop.pinned = scene.cloth->fixed;
  }
  // methods the core cannot step get their stepper here, so every caller can simply step()
  if (method == Method::BackwardEuler) installBackwardEuler(world);
  return world;
}

#define CLOTHREF_INSTANTIATE(T) \
  template World<T> makeWorld(const Scene&, Method, std::optional<double>);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref
