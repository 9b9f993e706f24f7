// The four integrators, each driven by OUR course-form simulateOneStep inside the child (the
// student's forces and contacts are never used): one step on a random state against clothref's
// method (or an accepted variant), every body integrated, deltaTime unchanged, backups are
// copies, the observed convergence order on a single damped spring, and no blow-up at half the
// method's stability limit. Known mistakes are recognised by simulating them and comparing.
//   systems.cpp    the test systems, the request's encoding (the system itself: mistakes/system.h)
//   run.cpp        one run of the probe: request, answer, the course's result
//   mistakes/integrate_mistakes.cpp   the mistake simulators and the accepted variants
//   diagnosis.cpp  likely causes of a wrong first step
//   stages.cpp     the stage explanation of the run, its Markdown and causes
//   text.cpp       the Markdown
#include <algorithm>
#include <cmath>
#include <mutex>

#include "clothref/verify/verify.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/mistakes/integrate_mistakes.h"
#include "grader/grade/probes/integrate/diagnosis.h"
#include "grader/grade/probes/integrate/replay.h"
#include "grader/grade/probes/integrate/stages.h"
#include "grader/grade/probes/integrate/text.h"
#include "grader/grade/submission/source_patterns.h"

namespace clothref::grader {
namespace {

using namespace integrators;

// The checks of an integrator probe, in report order (the names are the tests' names).
enum class Check { OneStep, EveryBody, DeltaTime, Backups, Order, Stability };
struct CheckInfo {
  Check check;
  const char* name;
  double weight;
  bool needs_backup;  // only for methods that back up the state (not explicit)
};
constexpr CheckInfo kChecks[] = {
    {Check::OneStep, "one step on a random state", 2, false},
    {Check::EveryBody, "every body integrated", 1, false},
    {Check::DeltaTime, "deltaTime unchanged", 1, false},
    {Check::Backups, "backups are copies", 1, true},
    {Check::Order, "convergence order", 1, false},
    {Check::Stability, "stable below the stability limit", 1, false},
};

// The causes of a wrong first step: what the stage fit shows is likely, with what the numbers of
// the random state show when the fit agrees or has nothing; a finding of the numbers that the fit
// does not show becomes a possibility (the two never give contradicting likely causes). With no
// likely cause: the possibilities, then `unknown`.
void addOneStepCauses(TestResult& one, const std::vector<std::string>& numeric,
                      const std::vector<std::string>& guesses, const RunStages& stages) {
  const std::vector<std::string> fitted = stages.causes(true);
  std::vector<std::string> likely = fitted.empty() ? numeric : fitted, possible;
  for (const std::string& id : numeric)
    if (std::find(likely.begin(), likely.end(), id) == likely.end())
      // deltaTime's value after integrate() is read, not fitted
      (id == cause::kDeltatimeMutated ? likely : possible).push_back(id);
  for (const std::string& id : stages.causes(false)) possible.push_back(id);
  for (const std::string& id : guesses) possible.push_back(id);
  for (const std::string& id : likely) {
    Cause& cause = one.addCause(id);
    if (const auto* c = stages.cause(id); c && c->likely)
      cause.detail = "Measured: " + c->why + ".";
  }
  for (const std::string& id : possible)
    if (std::find(likely.begin(), likely.end(), id) == likely.end()) one.addCause(id, false);
  if (likely.empty()) one.addCause(cause::kUnknown, false);
}

TestResult checkOneStep(const ProbeContext& context, const IntegratorRun& run,
                        const RunStages& stages) {
  TestResult one = makeTest(run.stub, kChecks[0].name, kChecks[0].weight);
  // On both states: the random one and the course's cloth.
  const auto matches = [&](const Step& step) {
    return distance(run.actual, stepped(run.random, step)) <= run.rel &&
           (!run.course_cloth ||
            distance(run.course_cloth->actual, stepped(run.course_cloth->state, step)) <= run.rel);
  };
  std::string matched_variant;
  for (const auto& [what, step] : acceptedVariants(context.rubric, run.method))
    if (matches(step)) matched_variant = what;
  const bool random_right = run.distance <= run.rel;
  if ((random_right && (!run.course_cloth || run.course_cloth->distance <= run.rel)) ||
      !matched_variant.empty()) {
    one.fraction = 1;
    one.output = matched_variant.empty()
                     ? "Matches the course method after one step (every body, x and v)."
                     : "Matches an accepted variant: " + matched_variant + ".";
    return one;
  }
  one.output = oneStepText(run);
  std::vector<std::string> guesses;
  // The numbers of the random state say nothing when only the course's cloth parts (replay.h
  // then tries every model, pinned particles among them).
  const std::vector<std::string> ids = random_right
                                           ? std::vector<std::string>{}
                                           : diagnoseOneStep(context, run, one.output, guesses);
  addOneStepCauses(one, ids, guesses, stages);
  return one;
}

// What the one-step check named as likely first, the mistake the other checks of the stub follow
// from; "unknown" when it named none.
std::string firstLikelyCause(const TestResult& one) {
  for (const Cause& cause : one.causes)
    if (cause.likely) return cause.id;
  return cause::kUnknown;
}

// Each body the course method moves must move.
TestResult checkEveryBody(const IntegratorRun& run, const TestResult& one) {
  TestResult all = makeTest(run.stub, kChecks[1].name, kChecks[1].weight);
  // Moved: by a finite distance (distance() says 1e300 for NaN: a body made NaN was lost, not
  // integrated).
  const auto moved = [&](int body) {
    const double d = distance(run.actual, run.start, body);
    return d > run.rel && d < 1e299;
  };
  std::string stuck;
  if (distance(run.expected, run.start, 0) > run.rel && !moved(0))
    stuck += "the cloth (particles[0])";
  if (distance(run.expected, run.start, 1) > run.rel && !moved(1))
    stuck += std::string(stuck.empty() ? "" : " and ") + "the spheres (particles[1])";
  all.fraction = stuck.empty() ? 1 : 0;
  if (stuck.empty()) {
    all.output = "Every Particles* in the vector was integrated.";
    return all;
  }
  const bool lost = !(distance(run.actual, run.start, 0) < 1e299) ||
                    !(distance(run.actual, run.start, 1) < 1e299);
  all.output =
      "After one step " + stuck +
      (lost ? " was not integrated (its numbers are not finite)" : " did not move at all") +
      ", although the course method moves it (state: " + systemText(run.random) + ").\n\n";
  const bool only_spheres = stuck.find("cloth") == std::string::npos;
  // Nothing moved: the one-step diagnosis says why (integer division, ...), when it has one.
  const std::string first = firstLikelyCause(one);
  const std::string id = only_spheres ? cause::kOnlyFirstBody : first;
  all.addCause(id, id != cause::kUnknown);
  return all;
}

TestResult checkDeltaTime(const IntegratorRun& run) {
  TestResult t = makeTest(run.stub, kChecks[2].name, kChecks[2].weight);
  const auto& after = run.answer.f(key::perCase(key::kDtAfter, 0));
  const float dt_after = after.empty() ? std::nanf("") : after[0];
  t.fraction = dt_after == run.random.dt ? 1 : 0;
  t.output = t.fraction == 1 ? "The global deltaTime is unchanged after integrate()."
                             : "deltaTime was " + util::num(run.random.dt) +
                                   " before integrate() and " + util::num(dt_after) + " after.\n";
  if (t.fraction == 0) t.addCause(cause::kDeltatimeMutated);
  return t;
}

TestResult checkBackups(const IntegratorRun& run, const SourceHints& hints) {
  TestResult t = makeTest(run.stub, kChecks[3].name, kChecks[3].weight);
  // The same numbers from a real copy that is not read back are the corrector's mistake, not
  // the backup's (corrector-from-prediction, on the one-step check).
  const bool alias =
      distance(run.actual, stepped(run.random, readingStep(cause::kBackupAlias, run.method))) <=
          10 * run.rel &&
      run.distance > run.rel && !copiesButNoView(hints);
  t.fraction = alias ? 0 : 1;
  t.output = alias ? "The result is exactly what a step gives when the backup follows the live "
                     "state (same state as the one-step test).\n"
                   : "The backed-up start state is not changed by the later stages.";
  if (alias) t.addCause(cause::kBackupAlias);
  return t;
}

// The cause a later check follows from when the one-step check passed: the stage fit's first
// likely cause (at h = kStageStep, where the stub is stable), or `otherwise`.
std::string causeAfterPassedStep(const RunStages& stages, const std::string& otherwise) {
  const std::vector<std::string> fitted = stages.causes(true);
  return fitted.empty() ? otherwise : fitted.front();
}

TestResult checkOrder(const ProbeContext& context, const IntegratorRun& run, const TestResult& one,
                      const RunStages& stages) {
  TestResult order = makeTest(run.stub, kChecks[4].name, kChecks[4].weight);
  std::vector<double> student_errors, reference_errors;
  for (std::size_t k = 0; k < run.dts.size(); ++k) {
    const std::int64_t steps = std::llround(run.end_time / run.dts[k]);
    student_errors.push_back(
        trajectoryError(run.answer.f(key::perCase(key::kTrajectory, int(k) + 1)), run.dts[k],
                        run.strides[k], run.spring_particles));
    reference_errors.push_back(referenceError(run.method, run.dts[k], steps, run.strides[k]));
  }
  bool usable = true;
  for (double e : student_errors) usable = usable && std::isfinite(e) && e > 0 && e < 1e299;
  const double expected_order = fitOrder(run.dts, reference_errors);
  const double observed = usable ? fitOrder(run.dts, student_errors) : std::nan("");
  order.fraction =
      usable && std::abs(observed - expected_order) <= context.rubric.tolerances.order ? 1 : 0;
  order.output = orderText(run, student_errors, reference_errors, usable, observed, expected_order);
  if (order.fraction == 0) {
    const std::string id = one.fraction == 1 ? causeAfterPassedStep(stages, cause::kWrongOrder)
                                             : firstLikelyCause(one);
    order.addCause(id, id != cause::kUnknown);
  }
  return order;
}

TestResult checkStability(const IntegratorRun& run, const TestResult& one,
                          const RunStages& stages) {
  TestResult stable = makeTest(run.stub, kChecks[5].name, kChecks[5].weight);
  const auto& trajectory = run.answer.f(key::perCase(key::kTrajectory, run.stable_case));
  const std::size_t per_record = 4 * std::size_t(run.spring_particles);
  double amplitude = 0;
  for (std::size_t r = 0; r + per_record <= trajectory.size(); r += per_record) {
    const double u = std::abs(double(trajectory[r + 4]) - 1.0);
    amplitude = std::isfinite(u) ? std::max(amplitude, u) : 1e300;
  }
  stable.fraction = amplitude <= 0.3 ? 1 : 0;
  stable.output = stabilityText(run, amplitude);
  if (stable.fraction == 0) {
    // The blow-up is a consequence: the one-step finding names the mistake when there is one.
    const std::string first = firstLikelyCause(one);
    const std::string id = one.fraction == 1 ? causeAfterPassedStep(stages, cause::kUnstable)
                           : first == cause::kUnknown ? cause::kUnstable
                                                      : first;
    stable.addCause(id);
  }
  return stable;
}

// "Backups are copies" compares the result with the right method's step from an aliased backup,
// which a second mistake hides; a replay that proves `backup-alias` on every check (with that
// other mistake) shows the backup is no copy, and the check fails with that proof.
void failBackupsOnProvenAlias(std::vector<TestResult>& tests) {
  const Cause* proof = nullptr;
  for (const TestResult& t : tests)
    for (const Cause& c : t.causes)
      if (!t.passed() && c.id == cause::kBackupAlias && c.proven()) proof = &c;
  if (!proof) return;
  const Cause alias = *proof;  // tests grows no further, but a copy keeps it simple
  for (TestResult& t : tests) {
    if (t.check != kChecks[3].name || !t.passed()) continue;
    t.fraction = 0;
    t.output =
        "Your result is the step of a method whose backup follows the live state, with another "
        "mistake beside it (the replay below proves both on every check), so the backed-up start "
        "state is not a copy.\n";
    Cause& named = t.addCause(cause::kBackupAlias);
    named.proof = alias.proof;
  }
}

// The stage explanation once per stub: on its first failed check; later failed checks refer to it.
void addStages(std::vector<TestResult>& tests, const RunStages& stages) {
  const std::string text = stages.markdown();
  if (text.empty()) return;
  const TestResult* first = nullptr;
  for (TestResult& t : tests) {
    if (t.fraction >= 1) continue;
    t.output += (t.output.empty() || t.output.back() == '\n' ? "" : "\n") +
                (first ? stagesShownUnder(first->check) : text);
    if (!first) first = &t;
  }
}

}  // namespace

std::vector<PlannedTest> integratorChecks(int method) {
  std::vector<PlannedTest> checks;
  for (const CheckInfo& info : kChecks)
    if (!info.needs_backup || integratorMethod(method) != Method::Explicit)
      checks.push_back({stubName(integratorStub(method)), info.name, info.weight});
  return checks;
}

std::vector<TestResult> probeIntegrator(const ProbeContext& context, int index) {
  const Method method = integratorMethod(index);
  IntegratorRun run;
  util::ProbeFailure failure;
  ChildRun child;
  std::string note;  // why the course-size cloth was used
  // A crash on the probe cloth is explained only when the course's cloth crashes too: its text
  // is then the same, and a retry that answers saves the sanitizer's build and run.
  Unexplained kept;
  ProbeContext first = context;
  first.explain_later = &kept;
  bool ok = runIntegrator(first, index, false, run, failure, child, false);
  if (!ok && failure.verdict != Verdict::Crashed) util::explainLater(context, kept, failure);
  if (!ok && failure.verdict == Verdict::Crashed) {
    // Code written for the course's cloth (e.g. indexing particlesPerEdge into it) crashes on the
    // small probe cloth: grade it on the course's cloth instead, and say so.
    note = "On the 4 x 4 probe cloth the probe process " + child.describe() +
           " (code written for the course's 25 x 25 cloth?), so this stub was graded on the "
           "course's cloth and spheres.\n\n";
    util::ProbeFailure again;
    IntegratorRun course;
    ok = runIntegrator(context, index, true, course, again, child, true);
    if (ok) {
      run = std::move(course);
    } else {
      util::explainLater(context, kept, failure);
      failure = {again.verdict, "On the 4 x 4 probe cloth: " + failure.text +
                                    "\n\nOn the course's cloth: " + again.text};
    }
  } else if (!ok && context.limits.log) {
    std::lock_guard<std::mutex> lock(context.limits.log->mutex);
    context.limits.log->verdicts.push_back(child.verdict());
    context.limits.log->folders.push_back(integratorFolder(index, false));  // as runChild logs
  }
  if (ok && context.limits.answers && onlyDivergedRuns(run.answer)) {
    std::lock_guard<std::mutex> lock(context.limits.answers->mutex);
    context.limits.answers->diverged.insert(integratorFolder(index, !note.empty()));
  }
  std::vector<TestResult> tests;
  if (!ok) {
    for (const PlannedTest& check : integratorChecks(index))
      tests.push_back(util::failedTest(check, failure.text, {util::likely(failure.causeId())}));
    return tests;
  }
  const RunStages stages = explainRun(context, run, !note.empty());
  const TestResult one = checkOneStep(context, run, stages);
  tests.push_back(one);
  tests.push_back(checkEveryBody(run, one));
  tests.push_back(checkDeltaTime(run));
  if (method != Method::Explicit)
    tests.push_back(checkBackups(run, sourceHints(stubSource(context, run.stub))));
  tests.push_back(checkOrder(context, run, one, stages));
  tests.push_back(checkStability(run, one, stages));
  // Likely means proven: every cause named is replayed on every probe state (replay.h).
  proveIntegratorCauses(context, run, stages, tests);
  failBackupsOnProvenAlias(tests);
  for (TestResult& t : tests)
    if (!t.passed() &&
        std::none_of(t.causes.begin(), t.causes.end(), [](const Cause& c) { return c.likely; }) &&
        !t.names(cause::kUnknown))
      t.causes.insert(t.causes.begin(), util::guess(cause::kUnknown));
  addStages(tests, stages);
  if (!note.empty())
    for (TestResult& t : tests) t.output = note + t.output;
  return tests;
}

}  // namespace clothref::grader
