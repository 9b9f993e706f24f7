// The course integrators as coefficient tables (grader/grade/explain/stages/methods.h), proven by
// replay against the library: each course table, run on a system as the course's code runs it
// (probes/integrate/models.h's tableStep), is the library's step of that method. The table's sums
// of h v_k and h a_k round differently from the library's (k1 + 2 k2 + 2 k3 + k4) / 6 by design,
// so the replay agrees within a tolerance, not bit for bit (docs/design.md's table of copies).
#include "grader/grade/explain/stages/methods.h"

#include <gtest/gtest.h>

#include "grader/grade/probes/integrate/models.h"
#include "grader/grade/probes/integrate/systems.h"

namespace clothref::grader::integrators {
namespace {

TEST(StageMethods, EachCourseTableReplaysTheLibrarysMethod) {
  const std::vector<System> systems = {randomSystem(20221, 2022), randomSystem(20228, 2024),
                                       courseSystem(20221, 2022), courseSystem(20235, 2024)};
  for (int index = 0; index < 4; ++index) {
    const Method method = integratorMethod(index);
    TableModel model;
    model.table = &stages::courseTable(index);
    for (const System& s : systems) {
      const System library = stepped(s, clothrefStep(method));
      EXPECT_LE(distance(stepped(s, tableStep(model)), library), 1e-6)
          << methodName(method) << " on " << s.cloth.particles.size() << " particles";
      // the replay sees a method's difference: another course method is far from it
      TableModel other;
      other.table = &stages::courseTable((index + 1) % 4);
      EXPECT_GT(distance(stepped(s, tableStep(other)), library), 1e-5)
          << methodName(method) << " against table " << (index + 1) % 4;
    }
  }
}

}  // namespace
}  // namespace clothref::grader::integrators
