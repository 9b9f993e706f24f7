// The probes: each runs one group of the student's stubs in a child process (the probe driver)
// on inputs built here, computes the reference with the clothref library in this process, and
// turns the comparison into tests with feedback (state tried, expected vs actual, likely cause).
//
// The reference never enters the child: the child receives only inputs and returns only outputs.
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "grader/bridge/probe_keys.h"
#include "grader/grade/catalogue.h"
#include "grader/grade/results.h"
#include "grader/grade/rubric.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/sanitize.h"
#include "grader/grade/submission/edition.h"

namespace clothref::grader {

struct ProbeContext {
  int edition = 2022;
  Edition course = courseEdition(2022);  // the same edition as a record: its course scene's values
  Rubric rubric;
  const Catalogue* catalogue = nullptr;
  std::filesystem::path probe;        // the linked probe executable (N = 25)
  std::filesystem::path probe_small;  // the second-size springs probe, or empty
  std::string small_problem;          // why there is no second-size probe
  std::filesystem::path work_dir;     // scratch; one sub-folder per group
  ChildLimits limits;
  std::uint64_t seed = 20221;  // random states are reproducible
  // The student's compiled files, by name ("integrator.cpp"): source patterns refine a finding
  // the probes measured (e.g. integer division), never make one.
  std::map<std::string, std::string> sources;
  // The sanitizer run a crashing or varying probe gets (run/sanitize.h); null: none.
  SanitizedProbes* sanitizer = nullptr;
  // A repair's probe (proveByRepair below): the probe rebuilt with one student file replaced by
  // the given bytes (run/build.h, rebuildWithFile), published for the probe uid. Empty: no
  // repairs (a repaired probe's own run).
  std::function<ProbeBuild(const std::string& file, const std::string& bytes)> rebuild;
  // Set: a crash or a variation is not explained now but kept here, for util::explainLater (a run
  // whose failure a retry may still replace: its sanitizer build and run are saved then).
  struct Unexplained* explain_later = nullptr;
};

// The run a probe kept for later explanation (ProbeContext::explain_later): its request and folder.
struct Unexplained {
  std::optional<probe::ProbeMessage> request;
  std::filesystem::path dir;
};

// Test names of each group, in order (used for compile errors and crashes, where the group did
// not run): {stub, check, weight}.
struct PlannedTest {
  std::string stub, check;
  double weight;
};
std::vector<PlannedTest> plannedTests(int edition);

// The one table of probes: one row per probe group, each group one child process (or two, for a
// retry or a second size) run as one job. The rows are the protocol's group list's
// (bridge/probe_keys.h), in its order, each group's made by its probe's own file
// (probeRows<Name>() below). Adding a probe: docs/grading-reference.md, "Adding a probe".
struct ProbeGroup {
  std::string group;                // the protocol's group name (probe::group, bridge/probe_keys.h)
  std::string stub;                 // the course stub it grades; "" = information only
  std::vector<PlannedTest> checks;  // its tests, for a stub whose file could not be used
  std::function<std::vector<TestResult>(const ProbeContext&)> run;
  // The folders under the work dir its children run in, one each; the sanitizer reads their
  // stderr.
  std::vector<std::string> folders;
};
// Every row, whatever the edition, in run order.
std::vector<ProbeGroup> probeTable();

// Each group's rows, defined in its probe's file (probes/<name>.cpp): probeRowsForces() for
// X(kForces, "forces", Forces), and so on for every line of the protocol's group list.
#define CLOTHREF_PROBE_ROWS(identifier, text, name) std::vector<ProbeGroup> probeRows##name();
CLOTHREF_PROBE_GROUPS(CLOTHREF_PROBE_ROWS)
#undef CLOTHREF_PROBE_ROWS
// The rows an edition runs, in order: those whose stub the edition grades (points in
// stubTable()), and the information-only ones when `information` (the whole run).
std::vector<ProbeGroup> probeGroups(int edition, bool information);

// Runs the groups on `jobs` workers, each worker taking the next group when it is free: the
// scored groups in order, then the information-only ones once every scored group has ended (their
// crash is explained with the sanitizer builds the scored groups already made); groups whose stub
// is in `unavailable` are skipped (their results stay empty). Results by group, in the groups'
// order; an exception a group throws is rethrown once all have ended.
std::vector<std::vector<TestResult>> runProbeGroups(
    const std::vector<ProbeGroup>& groups, const ProbeContext& context,
    const std::map<std::string, std::string>& unavailable, int jobs);

// Issue 38's repairs (explain/repair_proof.h): for each stub with a failed check, each pattern of
// its source whose cause no replay proved (an `auto` expression, an integer division, a backup
// that is no copy, a discarded normalized(), a changed deltaTime) is repaired in a private copy,
// the file rebuilt with `context.rebuild` (one build per pattern) and the stub's groups probed
// again; what the repair changed proves or disproves the cause. Then every cause still named
// likely without a proof becomes a guess, but for what is read directly (the catalogue's
// properties: a crash, NaN, a changed deltaTime; a spring list's foreign pairs and sizes).
void proveByRepair(const ProbeContext& context, std::vector<TestResult>& tests);

// The folders the rows name, with the stub each grades ("" = information only), in run order
// (probeTable()).
std::vector<std::pair<std::string, std::string>> probeFolders();
// The folder of an integrator's probe (method: the row of clothref's method table, as the
// protocol's key::kMethod), and of its retry on the course's cloth.
std::string integratorFolder(int method, bool course_size);
inline constexpr const char* kSpringsSmallFolder = "springs-small";

}  // namespace clothref::grader
