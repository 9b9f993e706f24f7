// Issue 38's repairs, run (probes.h, proveByRepair; the patterns and the judgement:
// explain/repair_proof.h).
#include <algorithm>

#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/repair_proof.h"
#include "grader/grade/explain/replay.h"
#include "grader/grade/probes/probes.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

// The tests the stub's groups give on the repaired probe, in the order the probes make them.
std::vector<TestResult> probeAgain(const ProbeContext& context, const std::string& stub,
                                   const fs::path& probe, const std::string& file,
                                   const std::string& bytes, const std::string& folder) {
  ProbeContext again = context;
  again.probe = probe;
  again.probe_small.clear();
  again.small_problem = "not run for a repair";
  again.work_dir = context.work_dir / folder;
  again.sanitizer = nullptr;
  again.rebuild = nullptr;
  again.explain_later = nullptr;
  again.limits.log = nullptr;  // it proves or disproves a cause; it never decides a verdict
  again.sources[file] = bytes;
  std::vector<TestResult> tests;
  for (const ProbeGroup& group : probeTable())
    if (group.stub == stub)
      for (TestResult& t : group.run(again)) tests.push_back(std::move(t));
  return tests;
}

}  // namespace

void proveByRepair(const ProbeContext& context, std::vector<TestResult>& tests) {
  int made = 0;
  for (const StubInfo& info : stubTable()) {
    std::vector<std::size_t> of_stub;
    for (std::size_t k = 0; k < tests.size(); ++k)
      if (tests[k].stub == info.name && !tests[k].informational) of_stub.push_back(k);
    const bool failed = std::any_of(of_stub.begin(), of_stub.end(),
                                    [&](std::size_t k) { return !tests[k].passed(); });
    const auto source = context.sources.find(info.file);
    if (source == context.sources.end() || !context.rebuild) continue;
    if (!failed) {
      // A passing stub may pass by luck: a local it never sets, which its build happened to
      // start at what the course's sum starts at.
      const std::optional<Repair> start = unsetStartProbe(info.file, source->second, info.name);
      if (!start || of_stub.empty()) continue;
      const std::string folder = "repair-" + std::to_string(++made);
      const ProbeBuild build = context.rebuild(info.file, start->patched);
      std::vector<TestResult> stub_tests;
      for (std::size_t k : of_stub) stub_tests.push_back(tests[k]);
      const std::vector<TestResult> started =
          build.ok ? probeAgain(context, info.name, build.probe, info.file, start->patched, folder)
                   : std::vector<TestResult>{};
      if (applyUnsetStart(*start, build.ok, started, stub_tests))
        for (std::size_t j = 0; j < of_stub.size(); ++j) tests[of_stub[j]] = stub_tests[j];
      continue;
    }
    for (const Repair& repair : repairsOf(info.file, source->second, info.name)) {
      // A cause a replay proved already needs no build.
      const bool proven = std::any_of(of_stub.begin(), of_stub.end(), [&](std::size_t k) {
        for (const Cause& c : tests[k].causes)
          if (c.id == repair.cause && c.proven()) return true;
        return false;
      });
      if (proven) continue;
      std::vector<TestResult> stub_tests;
      for (std::size_t k : of_stub) stub_tests.push_back(tests[k]);
      if (std::all_of(stub_tests.begin(), stub_tests.end(),
                      [](const TestResult& t) { return t.passed(); }))
        break;
      const std::string folder = "repair-" + std::to_string(++made);
      const ProbeBuild build = context.rebuild(info.file, repair.patched);
      const std::vector<TestResult> repaired =
          build.ok ? probeAgain(context, info.name, build.probe, info.file, repair.patched, folder)
                   : std::vector<TestResult>{};
      applyRepair(repair, build.ok, build.problem, repaired, stub_tests);
      for (std::size_t j = 0; j < of_stub.size(); ++j) tests[of_stub[j]] = stub_tests[j];
    }
  }
  // Likely means proven: what no replay or repair proved is a guess, but what is read directly.
  std::vector<std::string> observed = {cause::kHardCodedN25, cause::kWrongSpringEndpoints};
  if (context.catalogue)
    for (const auto& [id, entry] : context.catalogue->entries)
      if (entry.recognised_by == "property") observed.push_back(id);
  requireProofs(tests, observed);
  // `unknown` ("matches no known mistake") beside a likely cause says nothing more.
  for (TestResult& t : tests)
    if (std::any_of(t.causes.begin(), t.causes.end(), [](const Cause& c) { return c.likely; }))
      t.causes.erase(std::remove_if(t.causes.begin(), t.causes.end(),
                                    [](const Cause& c) { return c.id == cause::kUnknown; }),
                     t.causes.end());
}

}  // namespace clothref::grader
