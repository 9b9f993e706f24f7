// The built-in scenes. The two course scenes reproduce docs/course.md §2-3; the small ones model
// only what they test. `clothref golden --update` writes each to golden/scenes/NAME.json.
#include "clothref/scene/scene.h"

namespace clothref {

namespace {

// The course's grid corners, fixed by initializeVertex (mass 0).
std::vector<int> gridCorners(int n) { return {0, n - 1, n * (n - 1), n * n - 1}; }

ClothSpec courseCloth(double y, double spring_coef) {
  ClothSpec cloth;
  cloth.grid = GridSpec{25, 2, y, 1};
  cloth.fixed = gridCorners(25);
  cloth.spring_coef = spring_coef;
  cloth.damper_coef = 750;
  return cloth;
}

Scene course2022() {
  Scene scene;
  scene.name = "course2022";
  scene.description =
      "Course 2022 default: 25x25 cloth (4x4 m, y = 0, corners fixed) and four spheres r = 0.5 "
      "falling onto it";
  scene.dt = 1e-4;
  scene.gravity = {0, -9.8, 0};
  scene.viscous_coef = 3.4e-4;
  scene.cloth = courseCloth(0, 25000);
  SpheresSpec spheres;
  for (const Vector3& center : {Vector3{-0.75, 1, -0.75}, Vector3{0.75, 1, -0.75},
                                Vector3{-0.75, 1, 0.75}, Vector3{0.75, 1, 0.75}})
    spheres.items.push_back(SphereSpec{center, 0.5, {0, 0, 0}, std::nullopt});
  spheres.density = 1000;
  spheres.external_force = true;
  spheres.sphere_sphere_collision = true;
  spheres.restitution_cloth = 0;
  spheres.restitution_sphere = 0.8;
  spheres.correction = 0.15;
  scene.spheres = spheres;
  return scene;
}

Scene course2024() {
  Scene scene = course2022();
  scene.name = "course2024";
  scene.description =
      "Course 2024 default: 25x25 cloth at y = 1 draped over one sphere r = 1 at the origin; the "
      "sphere gets no external force and there is no sphere-sphere collision; every 40 steps (one "
      "frame on a 60 Hz monitor) the corners are re-pinned and the sphere's velocity is set to 0";
  scene.cloth = courseCloth(1, 20000);
  scene.spheres->items = {SphereSpec{{0, 0, 0}, 1, {0, 0, 0}, std::nullopt}};
  scene.spheres->external_force = false;
  scene.spheres->sphere_sphere_collision = false;
  scene.frame_loop = FrameLoopSpec{40, {0, 0, 0}};
  return scene;
}

// One fixed anchor at the origin and one unit mass on one spring along x, released at rest from
// 0.2 m past the rest length: omega = sqrt(k / m) = 10 rad/s, zeta = c / (2 sqrt(k m)).
Scene spring(const std::string& name, double damper_coef, const std::string& what) {
  Scene scene;
  scene.name = name;
  scene.description = "One anchor and one 1 kg particle on one " + what +
                      " spring (k = 100 N/m, rest 1 m, released at x = 1.2 m); no gravity, no drag";
  scene.dt = 1e-3;
  scene.gravity = {0, 0, 0};
  scene.viscous_coef = 0;
  ClothSpec cloth;
  cloth.particles = {ParticleSpec{{0, 0, 0}, {0, 0, 0}, 0},
                     ParticleSpec{{1.2, 0, 0}, {0, 0, 0}, 1}};
  cloth.springs = {SpringSpec{0, 1, 1}};
  cloth.spring_coef = 100;
  cloth.damper_coef = damper_coef;
  scene.cloth = cloth;
  return scene;
}

Scene freeFall() {
  Scene scene;
  scene.name = "free-fall";
  scene.description =
      "One 1 kg particle thrown at (2, 5, 0) m/s from (0, 10, 0) under gravity and linear drag "
      "0.5 kg/s";
  scene.dt = 1e-3;
  scene.gravity = {0, -9.8, 0};
  scene.viscous_coef = 0.5;
  ClothSpec cloth;
  cloth.particles = {ParticleSpec{{0, 10, 0}, {2, 5, 0}, 1}};
  cloth.spring_coef = 0;
  cloth.damper_coef = 0;
  scene.cloth = cloth;
  return scene;
}

Scene twoSpheres() {
  Scene scene;
  scene.name = "two-spheres";
  scene.description =
      "Two spheres r = 0.5 (125 kg) meeting head-on at 2 m/s each along x, restitution 0.8; no "
      "gravity, no drag";
  scene.dt = 1e-3;
  scene.gravity = {0, 0, 0};
  scene.viscous_coef = 0;
  SpheresSpec spheres;
  spheres.items = {SphereSpec{{-1, 0, 0}, 0.5, {2, 0, 0}, std::nullopt},
                   SphereSpec{{1, 0, 0}, 0.5, {-2, 0, 0}, std::nullopt}};
  spheres.density = 1000;
  spheres.external_force = false;
  spheres.sphere_sphere_collision = true;
  spheres.restitution_cloth = 0;
  spheres.restitution_sphere = 0.8;
  spheres.correction = 0.15;
  scene.spheres = spheres;
  return scene;
}

// Two spheres of different sizes (125 kg and 27 kg) meeting off-axis with restitution 0.8: at the
// contact (~0.29 s) the normal has three non-zero components and both velocities have tangential
// parts, so the impulse's float evaluation order shows in the last bits (e != 0, n not +-1).
Scene twoSpheresOblique() {
  Scene scene = twoSpheres();
  scene.name = "two-spheres-oblique";
  scene.description =
      "Two spheres r = 0.5 (125 kg) and r = 0.3 (27 kg) meeting off-axis (contact normal oblique "
      "to both velocities at ~0.29 s), restitution 0.8; no gravity, no drag";
  scene.spheres->items = {SphereSpec{{-1, 0.2, -0.1}, 0.5, {2, -0.2, 0.4}, std::nullopt},
                          SphereSpec{{0.8, -0.15, 0.25}, 0.3, {-1.5, 0.6, -0.2}, std::nullopt}};
  return scene;
}

Scene smallCloth() {
  Scene scene = course2022();
  scene.name = "small-cloth";
  scene.description =
      "9x9 cloth (2x2 m, y = 0, corners fixed, course springs) and one sphere r = 0.4 falling onto "
      "its centre";
  ClothSpec cloth;
  cloth.grid = GridSpec{9, 1, 0, 1};
  cloth.fixed = gridCorners(9);
  cloth.spring_coef = 25000;
  cloth.damper_coef = 750;
  scene.cloth = cloth;
  scene.spheres->items = {SphereSpec{{0, 0.6, 0}, 0.4, {0, 0, 0}, std::nullopt}};
  return scene;
}

}  // namespace

const std::vector<Scene>& builtinScenes() {
  static const std::vector<Scene> scenes = {
      course2022(),
      course2024(),
      spring("spring", 2, "damped (c = 2 N s/m, zeta = 0.1)"),
      spring("spring-undamped", 0, "undamped"),
      freeFall(),
      twoSpheres(),
      smallCloth(),
      twoSpheresOblique(),
  };
  return scenes;
}

}  // namespace clothref
