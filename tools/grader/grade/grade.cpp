#include "grader/grade/grade.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <fstream>
#include <iomanip>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/confinement.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/submission/source_patterns.h"
#include "grader/grade/submission/source_text.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string oneDecimal(double seconds) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << seconds;
  return out.str();
}

// Where a grade's time went (GradeReport::time_note): probes stopped at their time limit, the
// sanitizer's rebuild and rerun, then the compile and probe seconds.
std::string timeNote(const GradeReport& report, const ChildLimits& limits, double sanitizer) {
  std::vector<std::string> parts;
  std::size_t timed_out = 0;
  {
    std::lock_guard<std::mutex> lock(limits.log->mutex);
    timed_out = static_cast<std::size_t>(
        std::count(limits.log->verdicts.begin(), limits.log->verdicts.end(), Verdict::TimedOut));
  }
  if (timed_out)
    parts.push_back("endless loop: " + std::to_string(timed_out) +
                    (timed_out == 1 ? " probe" : " probes") + " stopped at the " +
                    (std::ostringstream() << limits.wall_seconds).str() + " s limit");
  if (sanitizer > 0) parts.push_back("sanitizer rebuild and rerun " + oneDecimal(sanitizer) + " s");
  const auto seconds = [&](const char* key) {
    const auto found = report.seconds.find(key);
    return found == report.seconds.end() ? 0.0 : found->second;
  };
  parts.push_back("compile " + oneDecimal(seconds("compile") + seconds("link")) + " s, probes " +
                  oneDecimal(seconds("probes")) + " s");
  std::string note;
  for (const std::string& part : parts) note += (note.empty() ? "" : "; ") + part;
  return note;
}

}  // namespace

Verdict submissionVerdict(const GradeReport& report, const std::vector<Verdict>& run_verdicts) {
  std::vector<Verdict> happened = run_verdicts;
  for (const UsedFile& used : report.files)
    if (!used.compiled) happened.push_back(used.status);
  for (const TestResult& t : report.tests)
    if (t.names(cause::kNonFinite)) happened.push_back(Verdict::NonFinite);
  return worstVerdict(happened);
}

namespace {

// The edition the probes assume: forced, else detected from the files, else 2022; the report
// says which and why (a forced edition that disagrees with the files is worth a line).
void chooseEdition(const SubmissionFiles& files, int forced, GradeReport& report) {
  std::string why;
  const int detected = detectEdition(files, why);
  if (forced) {
    report.edition = forced;
    report.edition_source =
        "forced with --edition" +
        (detected && detected != forced
             ? " (the files look like " + std::to_string(detected) + ": " + why + ")"
             : std::string());
  } else {
    report.edition = detected ? detected : 2022;
    report.edition_source =
        detected ? "detected: " + why : "not detected (" + why + "); assumed 2022";
  }
}

// What every probe needs: the edition, rubric, catalogue, the linked probes, the limits and the
// student's compiled sources (patterns in them refine a measured finding).
ProbeContext probeContext(const GradeReport& report, const Rubric& rubric,
                          const Catalogue& catalogue, const ProbeBuild& build,
                          const SubmissionFiles& files, const Isolation& isolation,
                          const GradeScratch& scratch, const GradeOptions& options) {
  ProbeContext context;
  context.edition = report.edition;
  context.course = courseEdition(report.edition);
  context.rubric = rubric;
  context.catalogue = &catalogue;
  context.probe = scratch.publish(build.probe);
  context.probe_small = build.small_ok ? scratch.publish(build.probe_small) : fs::path();
  context.small_problem = build.small_problem;
  context.work_dir = scratch.probes();
  context.limits = options.limits;
  context.limits.isolation = isolation;
  context.limits.keep_files = !options.keep_work.empty();
  context.limits.log = std::make_shared<RunLog>();
  context.limits.answers = context.limits.log;
  context.seed = options.seed;
  // the bytes the finder read: the student's path is never opened again
  for (const UsedFile& used : build.files)
    if (used.compiled) context.sources[used.name] = files.bytes.at(used.name);
  return context;
}

// Stubs whose file is not the student's (missing, or it does not compile or link): stub -> the
// test every planned test of that stub gets instead of running (its output and cause: the
// catalogue's missing-file, compile-error or link-error).
std::map<std::string, TestResult> unavailableStubs(const std::vector<UsedFile>& files) {
  std::map<std::string, TestResult> unavailable;
  for (const UsedFile& used : files) {
    if (used.compiled) continue;
    TestResult t;
    if (used.status == Verdict::MissingFile) {
      t.output = used.name + " was not found in the submission; its stubs get no points.";
      t.addCause(cause::kMissingFile);
    } else {
      t.output = used.name +
                 (used.status == Verdict::LinkError
                      ? " compiles but does not link (a function it must define is "
                        "missing or defined twice):\n\n"
                      : " does not compile against the course's headers:\n\n") +
                 codeBlock(used.problem) +
                 (used.log.empty() ? std::string()
                                   : "\nThe whole log of " + used.name +
                                         " (its own messages):\n\n" + codeBlock(used.log));
      t.addCause(used.status == Verdict::LinkError ? cause::kLinkError : cause::kCompileError);
    }
    for (const auto& stub : stubsOfFile(used.name)) unavailable[stub] = t;
  }
  return unavailable;
}

// The planned tests of unavailable stubs: zero points, the compile verdict as their output.
std::vector<TestResult> unavailableTests(int edition,
                                         const std::map<std::string, TestResult>& unavailable) {
  std::vector<TestResult> tests;
  for (const PlannedTest& planned : plannedTests(edition)) {
    auto it = unavailable.find(planned.stub);
    if (it == unavailable.end()) continue;
    TestResult t = makeTest(planned.stub, planned.check, planned.weight);
    t.output = it->second.output;
    t.causes = it->second.causes;
    tests.push_back(t);
  }
  return tests;
}

// A crash next to an `auto` Eigen expression over temporaries: the likely cause (a pattern
// alone, without the crash, names nothing). Only lines inside the stub the test grades are
// quoted: a crash in one stub says nothing of a line in another.
void addDanglingAutoCauses(const std::vector<UsedFile>& files, const fs::path& scratch,
                           std::vector<TestResult>& tests) {
  for (const UsedFile& used : files) {
    if (!used.compiled) continue;
    // The copy in the scratch folder: the student's path is never opened again.
    std::ifstream in(scratch / ("src-" + used.name.substr(0, used.name.size() - 4)) / used.name,
                     std::ios::binary);
    const std::string source((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
    const std::vector<SourceQuote> lines = autoExpressionLines(used.name, source);
    if (lines.empty()) continue;
    const auto stubs = stubsOfFile(used.name);
    for (TestResult& t : tests) {
      if (t.passed() || std::find(stubs.begin(), stubs.end(), t.stub) == stubs.end()) continue;
      if (!t.names(cause::kCrashed) && !t.names(cause::kUndefinedBehaviour)) continue;
      const StubLines body = stubLines(source, t.stub);
      std::vector<SourceQuote> inside;
      for (const SourceQuote& line : lines)
        if (body.contains(line.line) && inside.size() < 3) inside.push_back(line);
      if (inside.empty()) continue;
      t.addCause(cause::kDanglingAutoExpression).quotes = inside;
    }
  }
}

// The stubs whose probe answered with NaN or infinity (a scored run's verdict, by its folder).
std::set<std::string> nonFiniteStubs(RunLog& log) {
  std::map<std::string, std::string> stub_of;
  for (const auto& [folder, stub] : probeFolders()) stub_of[folder] = stub;
  std::set<std::string> stubs;
  std::lock_guard<std::mutex> lock(log.mutex);
  for (const std::string& folder : log.non_finite)
    if (stub_of.count(folder) && !stub_of[folder].empty() && !log.diverged.count(folder))
      stubs.insert(stub_of[folder]);
  return stubs;
}

// Every run's verdict, a diverged run's (RunLog::diverged) as graded: its checks judge it.
std::vector<Verdict> runVerdicts(RunLog& log) {
  std::lock_guard<std::mutex> lock(log.mutex);
  std::vector<Verdict> verdicts = log.verdicts;
  for (std::size_t k = 0; k < verdicts.size() && k < log.folders.size(); ++k)
    if (verdicts[k] == Verdict::NonFinite && log.diverged.count(log.folders[k]))
      verdicts[k] = Verdict::Graded;
  return verdicts;
}

// The causes whose model can make non-finite numbers (the catalogue's "non_finite").
std::set<std::string> nonFiniteCauses(const Catalogue& catalogue) {
  std::set<std::string> ids;
  for (const auto& [id, entry] : catalogue.entries)
    if (entry.non_finite) ids.insert(id);
  return ids;
}

// Course order of stubs, then the order the probes produced.
void sortInCourseOrder(std::vector<TestResult>& tests) {
  std::stable_sort(tests.begin(), tests.end(), [](const TestResult& a, const TestResult& b) {
    const auto rank = [](const std::string& stub) {
      const auto& names = stubNames();
      return std::find(names.begin(), names.end(), stub) - names.begin();
    };
    return rank(a.stub) < rank(b.stub);
  });
}

// --keep-work: a copy of the scratch folder for debugging, made without following any link a
// student process made (a link is listed, never copied through) and bounded in size. What was
// left out goes to KEEP/skipped.txt, for the staff: never into the student's report, where it
// would tell whether a host path exists.
void keepWork(const fs::path& scratch, const fs::path& keep_work) {
  std::vector<std::string> skipped;
  copyTree(scratch, keep_work, kKeepWorkBytes, &skipped);
  if (skipped.empty()) return;
  std::ofstream list(keep_work / "skipped.txt");
  for (const std::string& entry : skipped) list << safeName(entry) << "\n";
}

}  // namespace

std::vector<std::vector<TestResult>> runProbeGroups(
    const std::vector<ProbeGroup>& groups, const ProbeContext& context,
    const std::map<std::string, std::string>& unavailable, int jobs) {
  std::vector<std::vector<TestResult>> results(groups.size());
  std::vector<std::exception_ptr> errors(groups.size());
  // The scored groups first, then the information-only ones (the whole run): a crash of the whole
  // run is explained with the sanitizer's objects the scored groups' crashes built, when they
  // suffice (SanitizedProbes::explain), so those must all be built, whatever the workers' timing.
  for (const bool information : {false, true}) {
    // `jobs` workers take the groups in order, each the next one as soon as it is free: a group
    // that runs into its time limit holds one worker, never the start of the groups behind it.
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
      for (std::size_t g = next++; g < groups.size(); g = next++) {
        if (groups[g].stub.empty() != information) continue;
        if (!groups[g].stub.empty() && unavailable.count(groups[g].stub)) continue;
        try {
          results[g] = groups[g].run(context);
        } catch (...) {
          errors[g] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> workers;
    for (int k = 0; k < std::max(1, jobs); ++k) workers.emplace_back(worker);
    for (std::thread& w : workers) w.join();
  }
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
  return results;
}

GradeReport gradeSubmission(const fs::path& dir, const GradeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  GradeReport report;
  report.submission = dir.string();
  const SubmissionFiles files = findSubmissionFiles(dir, options.max_file_bytes);
  if (files.found.empty())
    throw InputError(dir.string() + ": none of cloth.cpp, sphere.cpp, integrator.cpp found");
  report.notes.assign(files.notes.begin(), files.notes.end());
  report.choices = files.choices;
  chooseEdition(files, options.edition, report);
  Rubric rubric = defaultRubric(report.edition);
  if (options.rubric_path) rubric = loadRubric(*options.rubric_path, rubric);
  const Catalogue catalogue =
      loadCatalogue(options.toolchain.course_dir.parent_path() / "diagnoses.json");

  const Isolation isolation = isolationFor(options.toolchain, options.private_paths, dir);
  report.isolation = isolation.describe();
  // What the grade's uids left in the shared temporary folders goes with the grade.
  // What the grade's uids left running (a compile's child) goes too, before the lease is freed.
  struct Sweep {
    const Isolation& isolation;
    ~Sweep() {
      if (isolation.uid >= 0) killProcessesOf({isolation.uid, isolation.tool_uid});
      for (const int uid : {isolation.uid, isolation.tool_uid})
        if (uid >= 0) removeOwnedBy(uid, sharedTemporaryFolders());
    }
  } sweep{isolation};
  GradeScratch scratch(isolation.uid, isolation.tool_uid);
  CourseToolchain toolchain = options.toolchain;
  toolchain.isolation = isolation;
  // Compiles of student code read the kit, never our folders.
  const CourseKit* kit = nullptr;
  if (isolation.kind != IsolationKind::None) {
    kit = &courseKit(toolchain.course_dir, toolchain.driver_lib_dir);
    toolchain.course_dir = kit->course_dir;
    toolchain.driver_lib_dir = kit->lib_dir;
    toolchain.kit = kit;
  }
  checkConfinement(isolation, scratch, kit);
  const ProbeBuild build = buildProbes(files, report.edition, toolchain, scratch.build());
  report.files = build.files;
  report.seconds["compile"] = build.compile_seconds;
  report.seconds["link"] = build.link_seconds;
  if (!build.ok) throw InputError(dir.string() + ": cannot grade: " + build.problem);

  ProbeContext context =
      probeContext(report, rubric, catalogue, build, files, isolation, scratch, options);
  SanitizedProbes sanitizer(files, report.edition, toolchain, scratch, context.limits, build);
  if (!options.toolchain.sanitize) context.sanitizer = &sanitizer;
  // Repairs rebuild one student file beside the grade's objects (probes.h, proveByRepair).
  int repair_builds = 0;
  if (!options.toolchain.sanitize)
    context.rebuild = [&](const std::string& file, const std::string& bytes) {
      const std::string name = "repair-" + std::to_string(++repair_builds);
      ProbeBuild repaired =
          rebuildWithFile(build, file, bytes, report.edition, toolchain, scratch.extraBuild(name));
      if (repaired.ok) repaired.probe = scratch.publish(repaired.probe, "probe-" + name);
      return repaired;
    };
  const std::map<std::string, TestResult> unavailable = unavailableStubs(build.files);
  std::map<std::string, std::string> skipped;  // the groups of those stubs do not run
  for (const auto& [stub, test] : unavailable) skipped[stub] = test.output;
  const auto probe_start = std::chrono::steady_clock::now();
  auto results = runProbeGroups(probeGroups(report.edition, options.whole_run), context, skipped,
                                options.probe_jobs);
  report.seconds["probes"] = since(probe_start);
  report.time_note = timeNote(report, context.limits, sanitizer.seconds());

  report.tests = unavailableTests(report.edition, unavailable);
  for (auto& group : results)
    for (auto& t : group) report.tests.push_back(std::move(t));
  addDanglingAutoCauses(build.files, scratch.build(), report.tests);
  const auto repair_start = std::chrono::steady_clock::now();
  proveByRepair(context, report.tests);
  report.seconds["repairs"] = since(repair_start);
  markNonFinite(nonFiniteStubs(*context.limits.log), nonFiniteCauses(catalogue), report.tests);
  fillCauseTexts(catalogue, report.tests);
  sortInCourseOrder(report.tests);
  applyRubric(rubric, report);
  for (TestResult& t : report.tests) t.visibility = rubric.visibilityOf(t.name(), t.stub);
  report.verdict = submissionVerdict(report, runVerdicts(*context.limits.log));
  if (!options.keep_work.empty()) keepWork(scratch.root(), options.keep_work);
  report.seconds["total"] = since(start);
  return report;
}

}  // namespace clothref::grader
