#include "grader/grade/probes/probes.h"

#include "grader/bridge/probe_keys.h"

namespace clothref::grader {

// The probes (one probe_<name>.cpp each), declared here beside the table that runs them, and
// their check tables, in report order: the one place a check's name and weight are written (each
// in its probe_<name>.cpp, beside the code that makes the tests).
std::vector<PlannedTest> springsChecks();
std::vector<PlannedTest> forcesChecks();
std::vector<PlannedTest> collideChecks(bool sphere_sphere);  // false: Spheres::collide(Cloth*)
std::vector<PlannedTest> integratorChecks(int method);       // method as probeIntegrator's
std::vector<TestResult> probeSprings(const ProbeContext& context);
std::vector<TestResult> probeForces(const ProbeContext& context);
std::vector<TestResult> probeCollideCloth(const ProbeContext& context);
std::vector<TestResult> probeCollideSpheres(const ProbeContext& context);
// method: 0 explicit, 1 implicit, 2 midpoint, 3 RK4 (the course's currentIntegrator).
std::vector<TestResult> probeIntegrator(const ProbeContext& context, int method);
// The student's whole simulation of the course scene against clothref's, via clothref diff.
// Informational only: never scored.
std::vector<TestResult> probeWholeRun(const ProbeContext& context);

std::vector<ProbeGroup> probeGroups(int edition, bool whole_run) {
  std::vector<ProbeGroup> groups;
  groups.push_back({stubName(Stub::InitializeSpring), springsChecks(), probeSprings});
  groups.push_back({stubName(Stub::ComputeSpringForce), forcesChecks(), probeForces});
  groups.push_back({stubName(Stub::CollideCloth), collideChecks(false), probeCollideCloth});
  if (edition == 2022)
    groups.push_back({stubName(Stub::CollideSpheres), collideChecks(true), probeCollideSpheres});
  for (int k = 0; k < 4; ++k)
    groups.push_back({stubName(integratorStub(k)), integratorChecks(k),
                      [k](const ProbeContext& context) { return probeIntegrator(context, k); }});
  if (whole_run) groups.push_back({"", {}, probeWholeRun});
  return groups;
}

std::string integratorFolder(int method, bool course_size) {
  return std::string(probe::group::kIntegrate) + "-" + std::to_string(method) +
         (course_size ? "-course" : "");
}

std::vector<std::pair<std::string, std::string>> probeFolders() {
  namespace group = probe::group;
  const std::string& springs = stubName(Stub::InitializeSpring);
  std::vector<std::pair<std::string, std::string>> folders = {
      {group::kSprings, springs},
      {kSpringsSmallFolder, springs},
      {group::kForces, stubName(Stub::ComputeSpringForce)},
      {group::kCollideCloth, stubName(Stub::CollideCloth)},
      {group::kCollideSpheres, stubName(Stub::CollideSpheres)}};
  for (int k = 0; k < 4; ++k)
    for (const bool course_size : {false, true})
      folders.push_back({integratorFolder(k, course_size), stubName(integratorStub(k))});
  folders.push_back({group::kWholeRun, ""});
  return folders;
}

std::vector<PlannedTest> plannedTests(int edition) {
  std::vector<PlannedTest> tests;
  for (const ProbeGroup& group : probeGroups(edition, false))
    tests.insert(tests.end(), group.checks.begin(), group.checks.end());
  return tests;
}

}  // namespace clothref::grader
