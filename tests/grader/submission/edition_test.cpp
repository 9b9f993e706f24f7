// The edition as a record (grade/submission/edition.h): read from clothref's course scene of the
// year, so the two editions differ where the course's programs do (docs/course.md).
#include "grader/grade/submission/edition.h"

#include <gtest/gtest.h>

#include "clothref/io/error.h"
#include "clothref/scene/scene.h"
#include "grader/grade/probes/probes.h"

namespace clothref::grader {
namespace {

TEST(Edition, IsReadFromTheCourseSceneOfTheYear) {
  for (const int year : {2022, 2024}) {
    const Edition edition = courseEdition(year);
    EXPECT_EQ(edition.year, year);
    const Scene* scene = findBuiltinScene(edition.scene);
    ASSERT_TRUE(scene) << edition.scene;
    EXPECT_EQ(edition.spring_coef, scene->cloth->spring_coef);
    EXPECT_EQ(edition.damper_coef, scene->cloth->damper_coef);
    EXPECT_EQ(edition.cloth_height, scene->cloth->grid->y);
    EXPECT_EQ(edition.sphere_count, static_cast<int>(scene->spheres->items.size()));
    EXPECT_EQ(edition.restitution_sphere, scene->spheres->restitution_sphere);
    EXPECT_EQ(edition.correction, scene->spheres->correction);
  }
}

// Where the 2024 program differs from 2022's: a stiffer 2022 cloth at y = 0 over four spheres
// that fall and collide with each other; a 2024 cloth at y = 1 over one sphere that does not.
TEST(Edition, TheTwoEditionsDifferWhereTheCoursesDo) {
  const Edition e2022 = courseEdition(2022), e2024 = courseEdition(2024);
  EXPECT_GT(e2022.spring_coef, e2024.spring_coef);
  EXPECT_LT(e2022.cloth_height, e2024.cloth_height);
  EXPECT_GT(e2022.sphere_count, e2024.sphere_count);
  EXPECT_TRUE(e2022.sphere_sphere_collision);
  EXPECT_FALSE(e2024.sphere_sphere_collision);
  EXPECT_TRUE(e2022.sphere_external_force);
  EXPECT_FALSE(e2024.sphere_external_force);
  // the same gravity, down (the mistakes' variants use one value for both editions)
  EXPECT_EQ(e2022.gravity, e2024.gravity);
  EXPECT_LT(e2022.gravity[1], 0);
  for (const Edition* e : {&e2022, &e2024}) {
    EXPECT_EQ(e->particles_per_edge, 25);
    EXPECT_EQ(e->correction, 0.15);
  }
}

TEST(Edition, AYearWithoutACourseSceneIsAnInputError) {
  EXPECT_THROW(courseEdition(2023), InputError);
}

// A default context carries one edition, as a year and as a record.
TEST(Edition, ADefaultProbeContextAgreesWithItself) {
  const ProbeContext context;
  EXPECT_EQ(context.course.year, context.edition);
}

}  // namespace
}  // namespace clothref::grader
