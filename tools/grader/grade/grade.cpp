#include "grader/grade/grade.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "grader/grade/probes/probes.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

// Lines that hold an Eigen *expression* in an `auto` variable (e.g. `auto d = p.position(i) -
// p.position(j);`): it refers to temporaries that are gone when it is read. Not when the
// expression ends in a call that returns a plain value (`.normalized()`, `.eval()`, `.norm()`,
// `.dot(...)`, `.cross3(...)`): those hold a vector or a number and nothing dangles.
std::vector<SourceQuote> autoExpressionLines(const std::string& file, const std::string& source) {
  std::istringstream in(source);
  static const std::regex declaration(R"(\bauto\s*&{0,2}\s*\w+\s*=\s*([^;]*);)");
  static const std::regex over_state(
      R"((position|velocity|acceleration)\s*\([^;]*\)\s*[-+*/]|[-+*/]\s*[\w>.-]*(position|velocity|acceleration)\s*\()");
  static const std::regex plain_value(
      R"(\.\s*(normalized|eval|norm|squaredNorm|stableNorm|sum|dot|cross3|cross|value)\s*\([^()]*\)\s*$)");
  std::vector<SourceQuote> lines;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    std::smatch match;
    if (!std::regex_search(line, match, declaration)) continue;
    const std::string value = match[1].str();
    if (!std::regex_search(value, over_state) || std::regex_search(value, plain_value)) continue;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back({file, number, line.substr(line.find_first_not_of(" \t"))});
  }
  return lines;
}

std::string readSource(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Verdict submissionVerdict(const GradeReport& report, const std::vector<Verdict>& run_verdicts) {
  std::vector<Verdict> happened = run_verdicts;
  for (const UsedFile& used : report.files)
    if (!used.compiled) happened.push_back(used.status);
  for (const TestResult& t : report.tests)
    if (t.names("non-finite")) happened.push_back(Verdict::NonFinite);
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

// How student processes are confined: they see none of our files (the course side, the
// reference, our build, scratch), and compiles run as the tool uid only where it can read what
// they read.
Isolation isolationFor(const CourseToolchain& toolchain, const fs::path& scratch) {
  Isolation isolation = detectIsolation();
  isolation.hidden = {toolchain.course_dir.parent_path(), toolchain.reference_dir,
                      toolchain.driver_lib_dir, scratch};
  // This grade's own uids in the fallback: a submission graded beside it in a batch runs as
  // others (bubblewrap keeps them apart by namespaces instead).
  if (isolation.kind == IsolationKind::Rlimits && isolation.uid >= 0) {
    const UidLease lease = leaseUids();
    isolation.uid = lease.uid;
    if (isolation.tool_uid >= 0) isolation.tool_uid = lease.tool_uid;
    isolation.uid_lease = lease.hold;
  }
  // The tool uid must read what compiles read (a checkout under mode-700 /root is unreadable to
  // it): else compiles keep the grader's uid, and the report says why.
  if (isolation.tool_uid >= 0) {
    std::vector<fs::path> folders = {toolchain.course_dir, toolchain.reference_dir,
                                     toolchain.driver_lib_dir};
    for (fs::path folder : {toolchain.prebuilt_dir, toolchain.cache_dir}) {
      std::error_code error;
      while (!folder.empty() && !fs::exists(folder, error) && folder != folder.parent_path())
        folder = folder.parent_path();  // a cache made later: its nearest existing folder
      if (!folder.empty()) folders.push_back(folder);
    }
    std::string unreadable;
    if (!readableAs(isolation.tool_uid, folders, &unreadable)) {
      isolation.why_not_tool_uid = "the compiles' uid cannot read " + safeName(unreadable);
      isolation.tool_uid = -1;
    }
  }
  return isolation;
}

// What every probe needs: the edition, rubric, catalogue, the linked probes, the limits and the
// student's compiled sources (patterns in them refine a measured finding).
ProbeContext probeContext(const GradeReport& report, const Rubric& rubric,
                          const Catalogue& catalogue, const ProbeBuild& build,
                          const Isolation& isolation, const fs::path& scratch,
                          const GradeOptions& options) {
  ProbeContext context;
  context.edition = report.edition;
  context.rubric = rubric;
  context.catalogue = &catalogue;
  context.probe = build.probe;
  context.probe_small = build.small_ok ? build.probe_small : fs::path();
  context.small_problem = build.small_problem;
  context.work_dir = scratch / "probes";
  context.limits = options.limits;
  context.limits.isolation = isolation;
  context.limits.log = std::make_shared<RunLog>();
  context.seed = options.seed;
  for (const UsedFile& used : build.files)
    if (used.compiled) context.sources[used.name] = readSource(used.path);
  return context;
}

// Stubs whose file is not the student's (missing, or it does not compile or link): stub -> the
// test every planned test of that stub gets instead of running (its output and cause).
std::map<std::string, TestResult> unavailableStubs(const std::vector<UsedFile>& files) {
  std::map<std::string, TestResult> unavailable;
  for (const UsedFile& used : files) {
    if (used.compiled) continue;
    TestResult t;
    if (used.status == Verdict::MissingFile) {
      t.output = used.name + " was not found in the submission; its stubs get no points.";
    } else {
      t.output = used.name + (used.status == Verdict::LinkError
                                  ? " compiles but does not link (a function it must define is "
                                    "missing or defined twice):\n\n"
                                  : " does not compile against the course's headers:\n\n") +
                 codeBlock(used.problem) +
                 (used.log.empty() ? std::string()
                                   : "\nThe whole log of " + used.name +
                                         " (its own messages):\n\n" + codeBlock(used.log));
      t.causes = {Cause{"compile-error", true, {}, {}, {}}};
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
    const std::string source = readSource(
        (scratch / ("src-" + used.name.substr(0, used.name.size() - 4)) / used.name).string());
    const std::vector<SourceQuote> lines = autoExpressionLines(used.name, source);
    if (lines.empty()) continue;
    const auto stubs = stubsOfFile(used.name);
    for (TestResult& t : tests) {
      if (t.passed() || std::find(stubs.begin(), stubs.end(), t.stub) == stubs.end()) continue;
      if (!t.names("crashed")) continue;
      const StubLines body = stubLines(source, t.stub);
      std::vector<SourceQuote> inside;
      for (const SourceQuote& line : lines)
        if (body.contains(line.line) && inside.size() < 3) inside.push_back(line);
      if (inside.empty()) continue;
      Cause& cause = t.addCause("dangling-auto-expression");
      cause.quotes = inside;
    }
  }
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

// --keep-work: a copy of the scratch folder for debugging; a failed copy is a note, not an error.
void keepWork(const fs::path& scratch, const fs::path& keep_work, GradeReport& report) {
  std::error_code error;
  fs::create_directories(keep_work, error);
  fs::copy(scratch, keep_work, fs::copy_options::recursive | fs::copy_options::overwrite_existing,
           error);
  if (error)
    report.notes.push_back("--keep-work: could not copy the scratch folder: " + error.message());
}

}  // namespace

std::vector<std::vector<TestResult>> runProbeGroups(
    const std::vector<ProbeGroup>& groups, const ProbeContext& context,
    const std::map<std::string, std::string>& unavailable, int jobs) {
  std::vector<std::vector<TestResult>> results(groups.size());
  std::vector<std::exception_ptr> errors(groups.size());
  // `jobs` workers take the groups in order, each the next one as soon as it is free: a group that
  // runs into its time limit holds one worker, never the start of the groups behind it.
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t g = next++; g < groups.size(); g = next++) {
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

  ScratchDir scratch("clothref-grade");
  const Isolation isolation = isolationFor(options.toolchain, scratch.path());
  report.isolation = isolation.describe();
  // The unprivileged uid must pass through the scratch folder (not list it) to reach its own.
  if (isolation.uid >= 0)
    fs::permissions(scratch.path(),
                    fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
  CourseToolchain toolchain = options.toolchain;
  toolchain.isolation = isolation;
  const ProbeBuild build = buildProbes(files, report.edition, toolchain, scratch.path());
  report.files = build.files;
  report.seconds["compile"] = build.compile_seconds;
  report.seconds["link"] = build.link_seconds;
  if (!build.ok) throw InputError(dir.string() + ": cannot grade: " + build.problem);

  const ProbeContext context =
      probeContext(report, rubric, catalogue, build, isolation, scratch.path(), options);
  const std::map<std::string, TestResult> unavailable = unavailableStubs(build.files);
  std::map<std::string, std::string> skipped;  // the groups of those stubs do not run
  for (const auto& [stub, test] : unavailable) skipped[stub] = test.output;
  const auto probe_start = std::chrono::steady_clock::now();
  auto results = runProbeGroups(probeGroups(report.edition, options.whole_run), context, skipped,
                                options.probe_jobs);
  report.seconds["probes"] = since(probe_start);

  report.tests = unavailableTests(report.edition, unavailable);
  for (auto& group : results)
    for (auto& t : group) report.tests.push_back(std::move(t));
  addDanglingAutoCauses(build.files, scratch.path(), report.tests);
  fillCauseTexts(catalogue, report.tests);
  sortInCourseOrder(report.tests);
  applyRubric(rubric, report);
  for (TestResult& t : report.tests) t.visibility = rubric.visibilityOf(t.name(), t.stub);
  report.verdict = submissionVerdict(report, context.limits.log->verdicts);
  if (!options.keep_work.empty()) keepWork(scratch.path(), options.keep_work, report);
  report.seconds["total"] = since(start);
  return report;
}

}  // namespace clothref::grader
