#include "probes.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"

namespace clothref::grader {

std::string Catalogue::cause(const std::string& id, bool guess) const {
  auto it = entries.find(id);
  if (it == entries.end()) return "**Likely cause** (`" + id + "`)";
  const bool is_guess = guess || it->second.recognised_by == "guess";
  return std::string(is_guess ? "**Possible cause (a guess)**" : "**Likely cause**") + " (`" + id +
         "`): " + it->second.text;
}

Catalogue loadCatalogue(const std::filesystem::path& path) {
  Catalogue catalogue;
  try {
    const auto document = readJsonFile(path.string(), "diagnosis catalogue");
    for (const auto& entry : document.at("diagnoses")) {
      Diagnosis d{entry.at("id").get<std::string>(), entry.at("stub").get<std::string>(),
                  entry.at("recognised_by").get<std::string>(),
                  entry.at("text").get<std::string>()};
      catalogue.entries[d.id] = d;
    }
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path.string() + ": malformed diagnosis catalogue (" + error.what() + ")");
  }
  return catalogue;
}

// The probes (one probe_<name>.cpp each), declared here beside the table that runs them.
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
  const auto checks = [](Stub stub, std::vector<std::pair<const char*, double>> named) {
    std::vector<PlannedTest> planned;
    for (const auto& [check, weight] : named) planned.push_back({stubName(stub), check, weight});
    return planned;
  };
  std::vector<ProbeGroup> groups;
  groups.push_back({stubName(Stub::InitializeSpring),
                    checks(Stub::InitializeSpring, {{"connections at N = 25", 2},
                                                    {"rest lengths at N = 25", 1},
                                                    {"type labels at N = 25", 1},
                                                    {"all springs at N = 10", 1}}),
                    probeSprings});
  groups.push_back(
      {stubName(Stub::ComputeSpringForce),
       checks(Stub::ComputeSpringForce, {{"random perturbed state", 1},
                                         {"moving state (damper)", 1},
                                         {"accumulates into existing accelerations", 1},
                                         {"fixed and heavy particles", 1}}),
       probeForces});
  groups.push_back({stubName(Stub::CollideCloth),
                    checks(Stub::CollideCloth, {{"approaching pair", 1},
                                                {"separating pair", 1},
                                                {"several spheres", 1},
                                                {"sphere at index 2", 1},
                                                {"fixed particle", 1},
                                                {"deep penetration", 1},
                                                {"touching exactly", 1},
                                                {"momentum conserved", 1}}),
                    probeCollideCloth});
  if (edition == 2022)
    groups.push_back({stubName(Stub::CollideSpheres),
                      checks(Stub::CollideSpheres, {{"approaching pair", 1},
                                                    {"separating pair", 1},
                                                    {"three spheres in a chain", 1},
                                                    {"pair without sphere 0", 1},
                                                    {"deep penetration", 1},
                                                    {"touching exactly", 1},
                                                    {"unequal masses", 1},
                                                    {"momentum conserved", 1}}),
                      probeCollideSpheres});
  for (int k = 0; k < 4; ++k)
    groups.push_back({stubName(integratorStub(k)), integratorChecks(k),
                      [k](const ProbeContext& context) { return probeIntegrator(context, k); }});
  if (whole_run) groups.push_back({"", {}, probeWholeRun});
  return groups;
}

std::vector<PlannedTest> plannedTests(int edition) {
  std::vector<PlannedTest> tests;
  for (const ProbeGroup& group : probeGroups(edition, false))
    tests.insert(tests.end(), group.checks.begin(), group.checks.end());
  return tests;
}

}  // namespace clothref::grader
