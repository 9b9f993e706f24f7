// The course edition the probes grade against, as one record: the year and the values of that
// year's course scene (clothref's built-in course2022 / course2024), so that a probe reads a
// course value here instead of writing it by hand.
#pragma once
#include <array>
#include <string>

namespace clothref::grader {

struct Edition {
  int year = 0;                     // 2022 or 2024
  std::string scene;                // the built-in scene's name (scene::findBuiltinScene)
  double dt = 0;                    // s: the course's deltaTime
  std::array<double, 3> gravity{};  // m/s^2
  double viscous_coef = 0;          // kg/s: linear drag on every free particle
  // The cloth: an n x n grid spanning [-h, h] in x and z at height y, corners fixed.
  int particles_per_edge = 0;
  double cloth_half_extent = 0;  // m
  double cloth_height = 0;       // m
  double particle_mass = 0;      // kg
  double spring_coef = 0;        // N/m: springCoef
  double damper_coef = 0;        // N s/m: damperCoef
  // The spheres and their contacts.
  int sphere_count = 0;
  double sphere_density = 0;             // kg/m^3: a sphere's mass is density r^3
  bool sphere_external_force = false;    // gravity and drag on spheres (2022)
  bool sphere_sphere_collision = false;  // Spheres::collide() (2022)
  double restitution_cloth = 0;          // coefRestitution of Spheres::collide(Cloth*)
  double restitution_sphere = 0;         // coefRestitution of Spheres::collide()
  double correction = 0;                 // fraction of the penetration undone per contact (0.15)
};

// The edition of `year`, read from clothref's course scene of that year; throws InputError for a
// year without one.
Edition courseEdition(int year);

}  // namespace clothref::grader
