// The probes: each runs one group of the student's stubs in a child process (the probe driver)
// on inputs built here, computes the reference with the clothref library in this process, and
// turns the comparison into tests with feedback (state tried, expected vs actual, likely cause).
//
// The reference never enters the child: the child receives only inputs and returns only outputs.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "child_process.h"
#include "results.h"
#include "rubric.h"

namespace clothref::grader {

// The catalogue of known mistakes (tools/grader/diagnoses.json).
struct Diagnosis {
  std::string id, stub, recognised_by, text;
};
struct Catalogue {
  std::map<std::string, Diagnosis> entries;
  // "Likely cause (`id`): text", marked as a guess when `guess` or the entry is a guess.
  std::string cause(const std::string& id, bool guess = false) const;
};
// Throws InputError when the file is missing or malformed.
Catalogue loadCatalogue(const std::filesystem::path& path);

struct ProbeContext {
  int edition = 2022;
  Rubric rubric;
  const Catalogue* catalogue = nullptr;
  std::filesystem::path probe;        // the linked probe executable (N = 25)
  std::filesystem::path probe_small;  // the second-size springs probe, or empty
  std::string small_problem;          // why there is no second-size probe
  std::filesystem::path work_dir;     // scratch; one sub-folder per group
  ChildLimits limits;
  std::uint64_t seed = 20221;  // random states are reproducible
};

std::vector<TestResult> probeSprings(const ProbeContext& context);
std::vector<TestResult> probeForces(const ProbeContext& context);
std::vector<TestResult> probeCollideCloth(const ProbeContext& context);
std::vector<TestResult> probeCollideSpheres(const ProbeContext& context);
// method: 0 explicit, 1 implicit, 2 midpoint, 3 RK4 (the course's currentIntegrator).
std::vector<TestResult> probeIntegrator(const ProbeContext& context, int method);
// The student's whole simulation of the course scene against clothref's, via clothref diff.
// Informational only: never scored.
std::vector<TestResult> probeWholeRun(const ProbeContext& context);

// Test names of each group, in order (used for compile errors and crashes, where the group did
// not run): {stub, check, weight}.
struct PlannedTest {
  std::string stub, check;
  double weight;
};
std::vector<PlannedTest> plannedTests(int edition);

}  // namespace clothref::grader
