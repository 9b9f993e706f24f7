// What grading produces: one result per test, grouped by the course stub it grades, and the
// report for a submission. Plain data; the writers (report.h) turn it into results.json, JUnit
// and Markdown.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace clothref::grader {

// What happened to a submission, or to one probe run: one word each (CSV, results.json, JUnit),
// in the order a submission's verdict is chosen (the first that happened wins;
// docs/grading-reference.md, "Verdicts"). Verdicts travel as this enum; the words are written only
// from the table below and read back only through it (a batch's row.json).
enum class Verdict {
  GraderError,    // our failure (a sandbox, fork, pipe or file of ours): never the student's
  NotGradable,    // batch only: the grader refused the folder (no student file, ...)
  CompileError,   // a student file does not compile (our reference linked in its place)
  LinkError,      // a student file compiles but the probe does not link with it
  MissingFile,    // one of the three files is not in the submission
  TimedOut,       // a probe hit the wall or CPU time limit
  MemoryLimit,    // a probe died of std::bad_alloc under the address-space limit
  OutputLimit,    // a probe was stopped by the file-size limit
  Crashed,        // a probe was killed by another signal
  ResultsVary,    // a probe answered differently in its two runs (undefined behaviour)
  ExitedNonZero,  // a probe exited with a non-zero code
  NoAnswer,       // a probe exited 0 without a valid answer
  NonFinite,      // a probe answered with NaN or infinity
  Graded          // every probe answered with finite numbers (a run: it finished cleanly)
};

struct VerdictInfo {
  Verdict verdict;
  const char* id;  // the one word
};

// The one table of verdicts, in the order above.
inline const std::vector<VerdictInfo>& verdictTable() {
  static const std::vector<VerdictInfo> table = {{Verdict::GraderError, "grader-error"},
                                                 {Verdict::NotGradable, "not-gradable"},
                                                 {Verdict::CompileError, "compile-error"},
                                                 {Verdict::LinkError, "link-error"},
                                                 {Verdict::MissingFile, "missing-file"},
                                                 {Verdict::TimedOut, "timed-out"},
                                                 {Verdict::MemoryLimit, "memory-limit"},
                                                 {Verdict::OutputLimit, "output-limit"},
                                                 {Verdict::Crashed, "crashed"},
                                                 {Verdict::ResultsVary, "results-vary"},
                                                 {Verdict::ExitedNonZero, "exited-non-zero"},
                                                 {Verdict::NoAnswer, "no-answer"},
                                                 {Verdict::NonFinite, "non-finite"},
                                                 {Verdict::Graded, "graded"}};
  return table;
}

inline const char* verdictId(Verdict verdict) {
  return verdictTable()[static_cast<std::size_t>(verdict)].id;
}

// The verdict a word names; false when it names none.
inline bool verdictFromId(const std::string& id, Verdict& verdict) {
  for (const VerdictInfo& info : verdictTable())
    if (id == info.id) {
      verdict = info.verdict;
      return true;
    }
  return false;
}

// The first of `happened` in the table's order; Graded when none.
inline Verdict worstVerdict(const std::vector<Verdict>& happened) {
  Verdict worst = Verdict::Graded;
  for (Verdict v : happened)
    if (static_cast<int>(v) < static_cast<int>(worst)) worst = v;
  return worst;
}

// The graded stubs, in the course's order.
enum class Stub {
  InitializeSpring,
  ComputeSpringForce,
  CollideCloth,
  CollideSpheres,
  ExplicitEuler,
  ImplicitEuler,
  MidpointEuler,
  RungeKuttaFourth
};

struct StubInfo {
  Stub stub;
  const char* name;    // the course's name
  const char* file;    // the student file that defines it
  double points_2022;  // the course's weights (points of 100); 0 = not in that edition
  double points_2024;
};

// The one table of the graded stubs: every list of stub names, files or weights derives from it.
inline const std::vector<StubInfo>& stubTable() {
  static const std::vector<StubInfo> table = {
      {Stub::InitializeSpring, "Cloth::initializeSpring", "cloth.cpp", 15, 10},
      {Stub::ComputeSpringForce, "Cloth::computeSpringForce", "cloth.cpp", 20, 25},
      {Stub::CollideCloth, "Spheres::collide(Cloth*)", "sphere.cpp", 10, 20},
      {Stub::CollideSpheres, "Spheres::collide()", "sphere.cpp", 10, 0},
      {Stub::ExplicitEuler, "ExplicitEuler::integrate", "integrator.cpp", 5, 5},
      {Stub::ImplicitEuler, "ImplicitEuler::integrate", "integrator.cpp", 2.5, 2.5},
      {Stub::MidpointEuler, "MidpointEuler::integrate", "integrator.cpp", 2.5, 2.5},
      {Stub::RungeKuttaFourth, "RungeKuttaFourth::integrate", "integrator.cpp", 15, 15}};
  return table;
}

// The course's names of the graded stubs, in the course's order.
inline const std::vector<std::string>& stubNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const StubInfo& info : stubTable()) all.push_back(info.name);
    return all;
  }();
  return names;
}

inline const std::string& stubName(Stub stub) { return stubNames()[std::size_t(stub)]; }

// The integrator stub of the course's currentIntegrator (0 explicit, 1 implicit, 2 midpoint, 3
// RK4).
inline Stub integratorStub(int method) { return Stub(int(Stub::ExplicitEuler) + method); }

// The stubs `file` ("cloth.cpp", ...) defines, in the course's order.
inline std::vector<std::string> stubsOfFile(const std::string& file) {
  std::vector<std::string> stubs;
  for (const StubInfo& info : stubTable())
    if (info.file == file) stubs.push_back(info.name);
  return stubs;
}

// One body of the state a failed collision check set up, for the report's small picture.
struct SketchBody {
  std::string label;                  // "sphere 0", "particle 312"
  std::array<float, 3> x{};           // position before the call, m
  float radius = 0;                   // m; 0 for a cloth particle (drawn as a dot)
  std::array<float, 3> v{};           // velocity before the call, m/s
  std::array<float, 3> v_expected{};  // after the course's collide, m/s
  std::array<float, 3> v_actual{};    // after the student's, m/s
};

// The state a failed check tried, as data for the HTML report's small picture (html_report.h
// draws it); empty for a check that passed or has nothing to draw.
struct Sketch {
  // A collision check: the bodies it set up.
  std::vector<SketchBody> bodies;
  // A springs check: an n x n cloth (grid = n, 0 = none) and the springs, as (lower, higher)
  // particle indices (row-major), that the course has and the student lacks, that only the
  // student has, and that both have but differ in rest length or type label.
  int grid = 0;
  std::vector<std::array<int, 2>> missing, unexpected, differing;
  std::string differing_means = "differs";  // legend of `differing`: "wrong rest length", ...
};

// A line of the student's source shown as evidence for a cause: always inside the stub the test
// grades.
struct SourceQuote {
  std::string file;  // "integrator.cpp"
  int line = 0;      // 1-based
  std::string text;  // the line as written (the writers make it printable and quote it verbatim)
  bool operator==(const SourceQuote&) const = default;
};

// A cause named for a failed check: an id of the catalogue (tools/grader/diagnoses.json), whether
// the numbers confirm it (likely) or it is a guess, and what the probe measured beside it. Data,
// never text: every writer renders it the same way (report/outputs.cpp, causeMarkdown), from the
// catalogue's text for the id, so the tags, the badges, the overview and the text always agree.
struct Cause {
  std::string id;
  bool likely = true;  // false: shown as "Possible cause (a guess)"
  std::string detail;  // Markdown measured by the probe for this check, shown after the text
  std::vector<SourceQuote> quotes;
  // The catalogue's text for `id` (fillCauseTexts, catalogue.h; a guess-only entry also clears
  // `likely`). Empty: the writers name the id alone.
  std::string text;
  // The catalogue's why (a paragraph: why the mistake gives these numbers) and example (the
  // mistaken line and its fix, two lines of C++), shown under a likely cause only.
  std::string why, example;
  // One line under the cause: how it was proven on this submission's numbers (docs/grading-
  // reference.md, "Likely means proven"): a replay ("Proven: the course's collide without the
  // position correction gives your numbers on 8 of 8 checks.") or a repair ("With line 129 ...:
  // 6 of 8 checks pass; ..."); for a guess, where its model and the student's numbers part.
  // Empty: nothing was tried (a property read directly, a crash, a guess).
  std::string proof;
  // Named as likely with a proof: only such a cause earns per-mistake points (rubric.h).
  bool proven() const { return likely && !proof.empty(); }
  bool operator==(const Cause&) const = default;
};

struct TestResult {
  std::string stub;            // course name of the stub, e.g. "RungeKuttaFourth::integrate"
  std::string check;           // what is checked, e.g. "convergence order"
  double weight = 1;           // share of the stub's points, relative to its other tests
  double fraction = 0;         // earned share of this test's points, 0..1
  double max_score = 0;        // points, filled in by the rubric
  double score = 0;            // points, filled in by the rubric
  bool informational = false;  // never scored (e.g. the whole-run comparison)
  // Gradescope's visibility of the test (the rubric's "visibility"; rubric.h visibilityNames())
  std::string visibility = "visible";
  // Markdown: state tried, expected vs actual, what was measured. Never the causes' text: the
  // writers add it from `causes`. Text a submission controls enters it only through codeBlock()
  // or codeSpan() (text.h).
  std::string output;
  // Markdown the rubric shows before `output` (per-mistake scoring: "One mistake (`id`) explains
  // every failed check of this stub: ..."); set by applyRubric on a stub's first failed check.
  std::string rubric_note;
  std::vector<Cause> causes;  // in the order the probe found them; the likely ones come first
  Sketch sketch;              // the state tried, when a collision or springs check failed
  // The whole run's two traces (JSON Lines, docs/trace-format.md), kept in memory for the HTML
  // report's pictures; null for every other test, or when the student's run did not finish.
  struct Traces {
    std::string reference, student;
  };
  std::shared_ptr<const Traces> traces;
  std::string name() const { return stub + ": " + check; }
  bool passed() const { return fraction >= 1.0; }
  // The ids of `causes`, in order (results.json's tags after the stub, the overview's chips).
  std::vector<std::string> causeIds() const {
    std::vector<std::string> ids;
    for (const Cause& cause : causes) ids.push_back(cause.id);
    return ids;
  }
  bool names(const std::string& id) const {
    for (const Cause& cause : causes)
      if (cause.id == id) return true;
    return false;
  }
  // Adds the cause `id` unless it is named already (a guess named again as likely becomes likely).
  Cause& addCause(const std::string& id, bool likely = true) {
    for (Cause& cause : causes)
      if (cause.id == id) {
        cause.likely = cause.likely || likely;
        return cause;
      }
    causes.push_back(Cause{id, likely, {}, {}, {}, {}, {}, {}});
    return causes.back();
  }
};

inline TestResult makeTest(std::string stub, std::string check, double weight) {
  TestResult test;
  test.stub = std::move(stub);
  test.check = std::move(check);
  test.weight = weight;
  return test;
}

struct UsedFile {
  std::string name;       // cloth.cpp, sphere.cpp, integrator.cpp
  std::string path;       // as found below the submission directory, or empty when missing
  bool compiled = false;  // false: our reference version was linked in its place
  // Why it was not used (compiled = false): MissingFile, CompileError or LinkError.
  Verdict status = Verdict::Graded;
  std::string problem;  // the compile or link error (first error quoted), or "missing"
  double compile_seconds = 0;
  // The whole compile (or link) log of a file that did not build: every message located in the
  // student's own file, scratch paths removed (compilerLog, run/compiler_messages.h); shown folded
  // under `problem`. Empty when it says no more than `problem`.
  std::string log;
};

// A name found more than once below a submission: the copy used and the others (paths relative to
// the submission, as found: the writers clean them).
struct FileChoice {
  std::string name;                 // "cloth.cpp"
  std::string used;                 // "src/cloth.cpp"
  std::vector<std::string> others;  // "old/cloth.cpp", ...
  bool operator==(const FileChoice&) const = default;
};

// A line of a report's notes (files chosen or refused, encodings, a sanitizer's finding): `text` is
// Markdown on one line, in which every name a submission controls is a code span (text.h), and
// `block`, when not empty, is shown verbatim under it (a sanitizer report, several lines).
struct Note {
  std::string text;
  std::string block;
  Note() = default;
  Note(std::string text_, std::string block_ = {})  // NOLINT: a plain line converts
      : text(std::move(text_)), block(std::move(block_)) {}
  Note(const char* text_) : text(text_) {}  // NOLINT
  bool operator==(const Note&) const = default;
};

struct GradeReport {
  std::string submission;  // the directory graded
  int edition = 2022;
  std::string edition_source;  // "detected: ..." or "forced with --edition"
  std::vector<UsedFile> files;
  std::vector<Note> notes;          // BOM, CRLF, non-UTF-8 bytes, several candidates, ...
  std::vector<FileChoice> choices;  // names found more than once (the terminal says which was used)
  std::vector<TestResult> tests;
  double score = 0, max_score = 0;
  std::map<std::string, double> stub_score, stub_max;  // per course stub
  std::map<std::string, double> seconds;               // "compile", "link", "probes", "total"
  // Where the time went, for the batch's closing lines: what made it slow ("sanitizer rebuild and
  // rerun 6.1 s", "endless loop: 2 probes stopped at the 20 s limit"), then the compile and probe
  // seconds. Never written to the student's outputs.
  std::string time_note;
  // The outcome for batch summaries (CSV): Graded when every probe group answered, else the
  // worst thing that happened (the first of verdictTable() that happened).
  Verdict verdict = Verdict::Graded;
  // Which isolation the student processes had, e.g. "bubblewrap (net, pid, mount namespaces),
  // uid 65534, rlimits" or "rlimits only" (docs/grading-reference.md, "Sandbox").
  std::string isolation;
};

}  // namespace clothref::grader
