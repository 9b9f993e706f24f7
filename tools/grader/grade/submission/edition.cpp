#include "grader/grade/submission/edition.h"

#include "clothref/io/error.h"
#include "clothref/scene/scene.h"

namespace clothref::grader {

Edition courseEdition(int year) {
  Edition edition;
  edition.year = year;
  edition.scene = "course" + std::to_string(year);
  const Scene* scene = findBuiltinScene(edition.scene);
  if (!scene || !scene->cloth || !scene->cloth->grid || !scene->spheres)
    throw InputError("no course scene for the edition " + std::to_string(year));
  const ClothSpec& cloth = *scene->cloth;
  const SpheresSpec& spheres = *scene->spheres;
  edition.dt = scene->dt;
  edition.gravity = scene->gravity;
  edition.viscous_coef = scene->viscous_coef;
  edition.particles_per_edge = cloth.grid->particles_per_edge;
  edition.cloth_half_extent = cloth.grid->half_extent;
  edition.cloth_height = cloth.grid->y;
  edition.particle_mass = cloth.grid->particle_mass;
  edition.spring_coef = cloth.spring_coef;
  edition.damper_coef = cloth.damper_coef;
  edition.sphere_count = static_cast<int>(spheres.items.size());
  edition.sphere_density = spheres.density;
  edition.sphere_external_force = spheres.external_force;
  edition.sphere_sphere_collision = spheres.sphere_sphere_collision;
  edition.restitution_cloth = spheres.restitution_cloth;
  edition.restitution_sphere = spheres.restitution_sphere;
  edition.correction = spheres.correction;
  return edition;
}

}  // namespace clothref::grader
