// The edition as a record (grade/submission/edition.h): read from clothref's course scene of the
// year, so the two editions differ where the course's programs do (docs/course.md).
#include "grader/grade/submission/edition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/scene/scene.h"
#include "grader/grade/probes/probes.h"
#include "test_util.h"

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
    EXPECT_EQ(edition.sphere_density, scene->spheres->density);
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

// `source` with its comments blanked and its string and character literals emptied (newlines
// kept, so a match's line is the source's).
std::string codeOnly(const std::string& source) {
  std::string code;
  const std::size_t n = source.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = source[i];
    const bool word_before =
        i > 0 && (std::isalnum(static_cast<unsigned char>(source[i - 1])) || source[i - 1] == '_');
    std::size_t end = i;  // the last character of a comment or literal starting at i
    if (source.compare(i, 2, "//") == 0) {
      end = std::min(source.find('\n', i), n) - 1;
    } else if (source.compare(i, 2, "/*") == 0) {
      end = std::min(source.find("*/", i + 2), n - 2) + 1;
    } else if (c == 'R' && i + 1 < n && source[i + 1] == '"' && !word_before) {
      const std::size_t open = source.find('(', i);
      const std::string close = ")" + source.substr(i + 2, open - i - 2) + "\"";
      end = std::min(source.find(close, open), n - close.size()) + close.size() - 1;
    } else if (c == '"' || (c == '\'' && !word_before)) {
      for (end = i + 1; end < n && source[end] != c; ++end)
        if (source[end] == '\\') ++end;
    } else {
      code += c;
      continue;
    }
    for (std::size_t k = i; k <= end && k < n; ++k)
      if (source[k] == '\n') code += '\n';
    code += ' ';
    i = end;
  }
  return code;
}

// The course's values live in the Edition record (read from clothref's course scenes): a probe, a
// mistake's model or a system that writes one by hand (9.8f, 0.15f, 0.8f, 25000, 3.4e-4f, ...)
// keeps a copy the record cannot correct. Every numeric literal in the code of
// tools/grader/grade (comments and strings left out) is compared with the record's values of both
// editions: gravity, drag, the spring and damper coefficients, the restitution and the correction
// factor in any form; the step, the sphere density and the spheres' masses as float literals
// (1e-4 and 1000 as doubles are tolerances and unit conversions).
TEST(Edition, NoCourseValueIsWrittenInTheGrader) {
  std::vector<double> any_form, as_float;
  for (const int year : {2022, 2024}) {
    const Edition e = courseEdition(year);
    for (const double v : {std::abs(e.gravity[1]), e.viscous_coef, e.spring_coef, e.damper_coef,
                           e.restitution_sphere, e.correction})
      any_form.push_back(v);
    for (const SphereSpec& sphere : findBuiltinScene(e.scene)->spheres->items)
      as_float.push_back(sphere.mass.value_or(e.sphere_density * std::pow(sphere.radius, 3)));
    as_float.push_back(e.dt);
    as_float.push_back(e.sphere_density);
  }
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
  const std::regex literal(R"((^|[^\w.])((\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)([fF]?)(?![\w.]))");
  const std::filesystem::path root = CLOTHREF_SOURCE_DIR;
  int files = 0, literals = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(root / "tools/grader/grade")) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
    ++files;
    const std::string code = codeOnly(test::readText(entry.path()));
    int line = 1;
    std::size_t from = 0;
    for (auto it = std::sregex_iterator(code.begin(), code.end(), literal);
         it != std::sregex_iterator(); ++it) {
      line += int(std::count(code.begin() + long(from), code.begin() + it->position(2), '\n'));
      from = std::size_t(it->position(2));
      ++literals;
      const double value = std::stod((*it)[2]);
      bool course = false;
      for (const double v : any_form) course = course || same(value, v);
      if ((*it)[5].length() > 0)
        for (const double v : as_float) course = course || same(value, v);
      if (course)
        ADD_FAILURE() << std::filesystem::relative(entry.path(), root).string() << ":" << line
                      << ": " << (*it)[2] << (*it)[5]
                      << " is a course value: read it from the Edition record";
    }
  }
  EXPECT_GT(files, 100);  // the walk found the grader
  EXPECT_GT(literals, 1000);
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
