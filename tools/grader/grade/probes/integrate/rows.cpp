// The integrator probe's rows of the probe table (probes.h): one per course integrator, each
// with its retry on the course's cloth.
#include <string>
#include <vector>

#include "clothref/core/method.h"
#include "grader/bridge/probe_keys.h"
#include "grader/grade/probes/probes.h"

namespace clothref::grader {

std::vector<PlannedTest> integratorChecks(int method);  // method as probeIntegrator's
// method: the row of clothref's method table (core/method.h) of a course integrator, 0 explicit,
// 1 implicit, 2 midpoint, 3 RK4 (the course's currentIntegrator).
std::vector<TestResult> probeIntegrator(const ProbeContext& context, int method);

std::vector<ProbeGroup> probeRowsIntegrate() {
  std::vector<ProbeGroup> rows;
  // the rows of clothref's method table that are the course's integrators, in the table's order
  for (std::size_t row = 0; row < kMethods.size(); ++row) {
    if (kMethods[row].origin != MethodOrigin::Course) continue;
    const int method = static_cast<int>(row);
    rows.push_back(
        {probe::group::kIntegrate,
         stubName(integratorStub(method)),
         integratorChecks(method),
         [method](const ProbeContext& context) { return probeIntegrator(context, method); },
         {integratorFolder(method, false), integratorFolder(method, true)}});
  }
  return rows;
}

}  // namespace clothref::grader
