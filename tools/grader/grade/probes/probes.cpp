#include "grader/grade/probes/probes.h"

#include "clothref/core/method.h"
#include "grader/bridge/probe_keys.h"

namespace clothref::grader {

// The probes (one <name>.cpp each), declared here beside the table that runs them, and their
// check tables, in report order: the one place a check's name and weight are written (each in
// its <name>.cpp, beside the code that makes the tests).
std::vector<PlannedTest> springsChecks();
std::vector<PlannedTest> forcesChecks();
std::vector<PlannedTest> collideChecks(bool sphere_sphere);  // false: Spheres::collide(Cloth*)
std::vector<PlannedTest> integratorChecks(int method);       // method as probeIntegrator's
std::vector<TestResult> probeSprings(const ProbeContext& context);
std::vector<TestResult> probeForces(const ProbeContext& context);
std::vector<TestResult> probeCollideCloth(const ProbeContext& context);
std::vector<TestResult> probeCollideSpheres(const ProbeContext& context);
// method: the row of clothref's method table (core/method.h) of a course integrator, 0 explicit,
// 1 implicit, 2 midpoint, 3 RK4 (the course's currentIntegrator).
std::vector<TestResult> probeIntegrator(const ProbeContext& context, int method);
// The student's whole simulation of the course scene against clothref's, via clothref diff.
// Informational only: never scored.
std::vector<TestResult> probeWholeRun(const ProbeContext& context);

namespace {

// The rows of clothref's method table that are the course's integrators, in the table's order.
std::vector<int> courseMethods() {
  std::vector<int> rows;
  for (std::size_t row = 0; row < kMethods.size(); ++row)
    if (kMethods[row].origin == MethodOrigin::Course) rows.push_back(static_cast<int>(row));
  return rows;
}

// Whether `edition` grades `stub`: it has points in that edition's column of stubTable().
bool gradedIn(const std::string& stub, int edition) {
  for (const StubInfo& info : stubTable())
    if (stub == info.name) return (edition == 2024 ? info.points_2024 : info.points_2022) > 0;
  return false;
}

}  // namespace

std::vector<ProbeGroup> probeTable() {
  namespace group = probe::group;
  std::vector<ProbeGroup> table = {{group::kSprings,
                                    stubName(Stub::InitializeSpring),
                                    springsChecks(),
                                    probeSprings,
                                    {group::kSprings, kSpringsSmallFolder}},
                                   {group::kForces,
                                    stubName(Stub::ComputeSpringForce),
                                    forcesChecks(),
                                    probeForces,
                                    {group::kForces}},
                                   {group::kCollideCloth,
                                    stubName(Stub::CollideCloth),
                                    collideChecks(false),
                                    probeCollideCloth,
                                    {group::kCollideCloth}},
                                   {group::kCollideSpheres,
                                    stubName(Stub::CollideSpheres),
                                    collideChecks(true),
                                    probeCollideSpheres,
                                    {group::kCollideSpheres}}};
  for (const int method : courseMethods())
    table.push_back(
        {group::kIntegrate,
         stubName(integratorStub(method)),
         integratorChecks(method),
         [method](const ProbeContext& context) { return probeIntegrator(context, method); },
         {integratorFolder(method, false), integratorFolder(method, true)}});
  table.push_back({group::kWholeRun, "", {}, probeWholeRun, {group::kWholeRun}});
  return table;
}

std::vector<ProbeGroup> probeGroups(int edition, bool information) {
  std::vector<ProbeGroup> groups;
  for (ProbeGroup& row : probeTable())
    if (row.stub.empty() ? information : gradedIn(row.stub, edition))
      groups.push_back(std::move(row));
  return groups;
}

std::string integratorFolder(int method, bool course_size) {
  return std::string(probe::group::kIntegrate) + "-" + std::to_string(method) +
         (course_size ? "-course" : "");
}

std::vector<std::pair<std::string, std::string>> probeFolders() {
  std::vector<std::pair<std::string, std::string>> folders;
  for (const ProbeGroup& row : probeTable())
    for (const std::string& folder : row.folders) folders.push_back({folder, row.stub});
  return folders;
}

std::vector<PlannedTest> plannedTests(int edition) {
  std::vector<PlannedTest> tests;
  for (const ProbeGroup& group : probeGroups(edition, false))
    tests.insert(tests.end(), group.checks.begin(), group.checks.end());
  return tests;
}

}  // namespace clothref::grader
