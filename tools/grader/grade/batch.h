// Grading many submissions in one run (`clothref grade DIR... --out BATCHDIR`,
// docs/grading-reference.md, "Batch"): submissions in parallel, progress on stderr, one folder of
// results per submission and a CSV summary rebuilt from those folders, resume after an
// interruption, and shards so a large batch splits across machines.
//
// BATCHDIR/<name>/ holds results.json, report.md and, written last and atomically, row.json: the
// submission's CSV row. row.json is the "graded" marker a rerun skips on. BATCHDIR/.cache holds
// the compiled objects the submissions share when no --cache-dir is given.
#pragma once
#include <filesystem>
#include <iosfwd>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "grader/grade/grade.h"
#include "grader/grade/report/class_page.h"

namespace clothref::grader {

// Shard k of n (1 <= k <= n): the k-th of n contiguous slices of the sorted submission names.
struct Shard {
  int index = 1;
  int count = 1;
};
// "k/n" with integers 1 <= k <= n; throws InputError ("--shard: ...") otherwise.
Shard parseShard(const std::string& text);

// A submission of the batch: its directory and its name in BATCHDIR (and in the CSV).
struct BatchEntry {
  std::string name;
  std::filesystem::path dir;
};

// Names for `dirs`, sorted by name: the last path component, made safe for a folder name
// (characters other than letters, digits, '.', '_', '-' become '_'; a leading '.' gets a '_'
// before it, and so does a name of the batch's own outputs: index.html, grades.csv and their
// shard forms index-k-of-n.html, grades-k-of-n.csv); when two submissions would get the same name,
// both take their parent folder's name too ("2022-reference"), and so on. The same directory given
// twice counts once. Throws InputError when names cannot be made unique.
std::vector<BatchEntry> batchEntries(const std::vector<std::filesystem::path>& dirs);

// The entries of `shard`: of N sorted entries, indices [(k-1)N/n, kN/n). Shards are disjoint,
// cover every entry, and concatenated in order k = 1..n give the whole batch in sorted order.
std::vector<BatchEntry> shardEntries(const std::vector<BatchEntry>& entries, const Shard& shard);

// One CSV row: a submission's points per stub and its outcome.
struct BatchRow {
  std::string name;
  std::string dir;                                     // the directory graded (as given)
  int edition = 0;                                     // 0 when not gradable
  std::map<std::string, double> stub_score, stub_max;  // per course stub (stubNames())
  double score = 0, max_score = 0;
  // GradeReport::verdict, or NotGradable (the grader refused the directory: no student file,
  // our reference not building) or GraderError (an unexpected error of ours).
  Verdict verdict = Verdict::Graded;
  std::string isolation;
  std::string problem;  // why it is not gradable, else empty
  double seconds = 0;   // wall time of grading this submission
  // the causes its failed checks name, each once, in order: id, likely on some check
  std::vector<std::pair<std::string, bool>> causes;
};
BatchRow rowOf(const BatchEntry& entry, const GradeReport& report);
nlohmann::ordered_json rowJson(const BatchRow& row);
// Throws InputError naming `where` when a field is missing or has the wrong type.
BatchRow rowFromJson(const nlohmann::json& json, const std::string& where);

// The overview's rows for `rows` (the batch's, sorted by name) of the batch in `batch_dir`: each
// folder's results.json read for its checks and causes (extra_data's causes with whether each is
// likely; else a test's tags after its stub). A folder whose results.json is missing or unreadable
// still gets its row, without checks.
std::vector<ClassRow> classRows(const std::filesystem::path& batch_dir,
                                const std::vector<BatchRow>& rows);

// The CSV (RFC 4180; fields with a comma or quote are quoted; every field is valid UTF-8 on one
// line, control characters and line breaks escaped as in text.h): a header line
//   submission,edition,<the eight stubs of stubNames()>,total,max,verdict,causes,guesses,seconds
// when `header`, then one line per row in the order given: one fact per column. A stub the
// edition does not have (Spheres::collide() in 2024) is an empty cell; numbers are rounded to
// 0.001; `causes` and `guesses` are cause ids separated by spaces; seconds to 0.1. How student
// code was isolated is said once, in the batch's summary (BatchSummary::isolation).
std::string batchCsv(const std::vector<BatchRow>& rows, bool header);

struct BatchOptions {
  std::filesystem::path out_dir;  // BATCHDIR
  std::filesystem::path csv;      // default BATCHDIR/grades.csv (BATCHDIR/grades-k-of-n.csv)
  bool csv_header = true;
  int jobs = 1;          // submissions graded at once
  int cores = 0;         // cores to share between them; 0 = std::thread::hardware_concurrency()
  Shard shard;           // which part of the sorted submissions this run grades
  bool regrade = false;  // grade again even when row.json exists
  bool quiet = false;    // no progress on stderr
  // Grade a folder that holds several whole submissions as one (else it is not gradable: the
  // folder names them; submission/submission.h, submissionsBelow).
  bool one_submission = false;
  GradeOptions grade;  // per submission (probe_jobs and toolchain.jobs are set from cores/jobs)
};

inline constexpr std::size_t kSlowestShown = 3;

struct BatchSummary {
  std::vector<BatchRow> rows;  // the shard's submissions, sorted by name
  int graded = 0;              // graded by this run
  int skipped = 0;             // already graded (row.json found)
  int failed = 0;              // rows whose verdict is not Graded
  std::vector<std::pair<std::string, Verdict>> not_graded;  // those rows: name, verdict
  // The slowest submissions graded by this run (at most kSlowestShown, slowest first): where the
  // batch's time went, with why (GradeReport::time_note).
  struct Slow {
    std::string name;
    double seconds = 0;  // wall time of grading it
    std::string why;
  };
  std::vector<Slow> slowest;
  std::filesystem::path csv;
  std::filesystem::path index;  // the class overview
  // how the student processes were isolated, each description once (one on a machine)
  std::vector<std::string> isolation;
};

// Each submission's share of the cores: max(1, cores / jobs), used for its compiles and its probe
// groups, so jobs x share <= cores whenever jobs <= cores.
int perSubmissionJobs(int jobs, int cores);

// Grades the shard's submissions (skipping those with a row.json unless `regrade`), writes their
// folders and then the CSV. Progress goes to `progress_out` (n of N done, failures, ETA). Throws
// InputError, before grading anything, for a DIR that does not exist, a bad BATCHDIR or colliding
// names; a submission's own problems are rows. Inside BATCHDIR nothing is written or read through
// a link: every file is created new (O_NOFOLLOW | O_EXCL) and renamed into place, and a folder of
// the batch that is a link stops the batch with its name.
BatchSummary runBatch(const std::vector<std::filesystem::path>& dirs, const BatchOptions& options,
                      std::ostream& progress_out);

}  // namespace clothref::grader
