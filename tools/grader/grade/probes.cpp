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

std::vector<PlannedTest> plannedTests(int edition) {
  std::vector<PlannedTest> tests;
  const std::string springs = "Cloth::initializeSpring";
  tests.push_back({springs, "connections at N = 25", 2});
  tests.push_back({springs, "rest lengths at N = 25", 1});
  tests.push_back({springs, "type labels at N = 25", 1});
  tests.push_back({springs, "all springs at N = 10", 1});
  for (const char* check : {"random perturbed state", "moving state (damper)",
                            "accumulates into existing accelerations", "fixed and heavy particles"})
    tests.push_back({"Cloth::computeSpringForce", check, 1});
  for (const char* check :
       {"approaching pair", "separating pair", "several spheres", "sphere at index 2",
        "fixed particle", "deep penetration", "touching exactly", "momentum conserved"})
    tests.push_back({"Spheres::collide(Cloth*)", check, 1});
  if (edition == 2022)
    for (const char* check : {"approaching pair", "separating pair", "three spheres in a chain",
                              "pair without sphere 0", "deep penetration", "touching exactly",
                              "unequal masses", "momentum conserved"})
      tests.push_back({"Spheres::collide()", check, 1});
  const char* integrators[] = {"ExplicitEuler::integrate", "ImplicitEuler::integrate",
                               "MidpointEuler::integrate", "RungeKuttaFourth::integrate"};
  for (int k = 0; k < 4; ++k) {
    tests.push_back({integrators[k], "one step on a random state", 2});
    tests.push_back({integrators[k], "every body integrated", 1});
    tests.push_back({integrators[k], "deltaTime unchanged", 1});
    if (k > 0) tests.push_back({integrators[k], "backups are copies", 1});
    tests.push_back({integrators[k], "convergence order", 1});
    tests.push_back({integrators[k], "stable below the stability limit", 1});
  }
  return tests;
}

}  // namespace clothref::grader
