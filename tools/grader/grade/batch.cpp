#include "grader/grade/batch.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/json_input.h"
#include "clothref/io/output_file.h"
#include "clothref/io/progress.h"
#include "grader/grade/batch_files.h"
#include "grader/grade/report/html_report.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/submission/submission.h"
#include "grader/grade/text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <regex>
#include <utility>

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

constexpr const char* kRowFile = "row.json";
constexpr const char* kCacheDir = ".cache";    // no submission name starts with a dot
constexpr std::size_t kMaxRowBytes = 1 << 20;  // a marker is a few hundred bytes
// The writers already give valid UTF-8 (text.h); should a byte slip through, it becomes U+FFFD
// rather than an exception that loses the submission's row.
constexpr auto kReplace = nlohmann::json::error_handler_t::replace;

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A name the batch writes at BATCHDIR's top (grades.csv, index.html and their shard forms
// grades-k-of-n.csv, index-k-of-n.html), which no submission folder may take.
bool isBatchOutputName(const std::string& name) {
  static const std::regex output(R"((grades|index)(-[0-9]+-of-[0-9]+)?\.(csv|html))",
                                 std::regex::icase);
  return std::regex_match(name, output);
}

// A path component as a folder name: letters, digits, '.', '_' and '-' kept, the rest '_'; never
// starting with a dot (so never "." or "..", nor BATCHDIR/.cache) and never a name of the batch's
// own outputs (index.html becomes _index.html).
std::string safeComponent(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  if (out.empty() || out.front() == '.' || isBatchOutputName(out)) out = "_" + out;
  return out;
}

// The row marker of a folder of the batch (read without following links), or nullopt.
std::optional<BatchRow> readRow(int batch_fd, const fs::path& batch_dir, const std::string& name) {
  Fd folder(::openat(batch_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (folder.fd < 0) return std::nullopt;
  const std::optional<std::string> text = readNoFollow(folder.fd, kRowFile, kMaxRowBytes);
  if (!text) return std::nullopt;
  const std::string where = (batch_dir / name / kRowFile).string();
  const nlohmann::json json = nlohmann::json::parse(*text, nullptr, false);
  if (json.is_discarded()) throw InputError(where + ": not a batch row (not JSON)");
  return rowFromJson(json, where);
}

// The row a previous run left for `name`, or nullopt (none, unreadable, or a grader error, which
// is ours to retry).
std::optional<BatchRow> finishedRow(int batch_fd, const fs::path& batch_dir,
                                    const std::string& name) {
  try {
    std::optional<BatchRow> row = readRow(batch_fd, batch_dir, name);
    if (row && row->verdict == Verdict::GraderError) return std::nullopt;
    return row;
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// What a submission that could not be graded gets instead of a report.
struct Outputs {
  BatchRow row;
  std::string results_json, report_md;
  std::string report_html;  // empty when not graded
  std::string time_note;    // GradeReport::time_note
};

Outputs notGradable(const BatchEntry& entry, Verdict verdict, const std::string& problem) {
  Outputs out;
  out.row.name = entry.name;
  out.row.dir = safeName(entry.dir.string());
  out.row.verdict = verdict;
  out.row.problem = safeName(problem);
  // Markdown: the problem names the folder, which the submission controls: in a code block
  const std::string text =
      (verdict == Verdict::NotGradable
           ? std::string("The submission could not be graded:\n\n")
           : std::string("The grader failed on this submission (see the course staff):\n\n")) +
      codeBlock(out.row.problem);
  nlohmann::ordered_json results;
  results["score"] = 0;
  results["output"] = text;
  results["output_format"] = "md";
  results["visibility"] = "visible";
  results["tests"] = nlohmann::ordered_json::array();
  out.results_json = results.dump(2, ' ', false, kReplace) + "\n";
  out.report_md =
      "# Grading report: " + codeSpan(out.row.dir) + "\n\n**" + verdictId(verdict) + "**. " + text;
  return out;
}

// Keeps the kSlowestShown slowest submissions, slowest first.
void noteIfSlow(std::vector<BatchSummary::Slow>& slowest, BatchSummary::Slow row) {
  slowest.push_back(std::move(row));
  std::stable_sort(slowest.begin(), slowest.end(),
                   [](const auto& a, const auto& b) { return a.seconds > b.seconds; });
  if (slowest.size() > kSlowestShown) slowest.pop_back();
}

Outputs gradeOne(const BatchEntry& entry, const BatchOptions& options, const GradeOptions& grade) {
  try {
    if (!options.one_submission) {
      const std::vector<std::string> several = submissionsBelow(entry.dir);
      if (!several.empty())
        return notGradable(entry, Verdict::NotGradable,
                           severalSubmissionsProblem(entry.dir, several));
    }
    GradeReport report = gradeSubmission(entry.dir, grade);
    // the pictures of report.html (html_report.h)
    const nlohmann::ordered_json whole_run_view = wholeRunView(report);
    Outputs out;
    out.row = rowOf(entry, report);
    out.results_json =
        withHtmlSummary(resultsJson(report), report).dump(2, ' ', false, kReplace) + "\n";
    out.report_md = markdownReport(report);
    out.report_html = studentReportHtml(report, whole_run_view);
    out.time_note = report.time_note;
    return out;
  } catch (const InputError& error) {
    return notGradable(entry, Verdict::NotGradable, error.what());
  } catch (const std::exception& error) {
    return notGradable(entry, Verdict::GraderError, error.what());
  }
}

}  // namespace

Shard parseShard(const std::string& text) {
  const auto fail = [&] {
    return InputError("--shard: expected k/n with integers 1 <= k <= n (got '" + safeName(text) +
                      "')");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw fail();
  Shard shard;
  const char* begin = text.data();
  const char* end = begin + text.size();
  auto [after_k, error_k] = std::from_chars(begin, begin + slash, shard.index);
  auto [after_n, error_n] = std::from_chars(begin + slash + 1, end, shard.count);
  if (error_k != std::errc() || after_k != begin + slash || error_n != std::errc() ||
      after_n != end || shard.index < 1 || shard.count < 1 || shard.index > shard.count)
    throw fail();
  return shard;
}

std::vector<BatchEntry> batchEntries(const std::vector<fs::path>& dirs) {
  struct Candidate {
    fs::path dir;
    std::vector<std::string> components;  // last first
    std::size_t depth = 1;
    std::string name;
  };
  std::vector<Candidate> candidates;
  std::set<fs::path> seen;
  for (const fs::path& dir : dirs) {
    // The folder's own name is kept (a submission given as a link is not followed, so it is not
    // the folder it points to); the folders above it are resolved.
    std::error_code error;
    fs::path given = fs::absolute(dir).lexically_normal();
    if (given.filename().empty()) given = given.parent_path();
    fs::path full = fs::weakly_canonical(given.parent_path(), error) / given.filename();
    if (error) full = given;
    if (!seen.insert(full).second) continue;  // the same directory twice
    Candidate c;
    c.dir = dir;
    for (const auto& part : full)
      if (part != "/" && !part.empty()) c.components.insert(c.components.begin(), part.string());
    if (c.components.empty()) c.components.push_back("root");
    candidates.push_back(c);
  }
  for (;;) {
    std::map<std::string, std::vector<std::size_t>> by_name;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      Candidate& c = candidates[i];
      c.name.clear();
      for (std::size_t k = std::min(c.depth, c.components.size()); k-- > 0;)
        c.name += safeComponent(c.components[k]) + (k ? "-" : "");
      by_name[c.name].push_back(i);
    }
    bool collided = false;
    for (const auto& [name, members] : by_name) {
      if (members.size() < 2) continue;
      collided = true;
      bool deeper = false;
      for (std::size_t i : members)
        if (candidates[i].depth < candidates[i].components.size()) {
          ++candidates[i].depth;
          deeper = true;
        }
      if (!deeper)
        throw InputError("two submissions get the same name '" + name +
                         "': " + safeName(candidates[members[0]].dir.string()) + " and " +
                         safeName(candidates[members[1]].dir.string()) + " (rename one folder)");
    }
    if (!collided) break;
  }
  std::vector<BatchEntry> entries;
  for (const Candidate& c : candidates) entries.push_back({c.name, c.dir});
  std::sort(entries.begin(), entries.end(),
            [](const BatchEntry& a, const BatchEntry& b) { return a.name < b.name; });
  return entries;
}

std::vector<BatchEntry> shardEntries(const std::vector<BatchEntry>& entries, const Shard& shard) {
  const std::size_t n = entries.size(), k = static_cast<std::size_t>(shard.index),
                    count = static_cast<std::size_t>(shard.count);
  const std::size_t begin = (k - 1) * n / count, end = k * n / count;
  return {entries.begin() + static_cast<std::ptrdiff_t>(begin),
          entries.begin() + static_cast<std::ptrdiff_t>(end)};
}

int perSubmissionJobs(int jobs, int cores) { return std::max(1, cores / std::max(1, jobs)); }

BatchSummary runBatch(const std::vector<fs::path>& dirs, const BatchOptions& options,
                      std::ostream& progress_out) {
  // A path that does not exist is a typo of the command, not a submission: nothing is graded.
  for (const fs::path& dir : dirs) {
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0 && (errno == ENOENT || errno == ENOTDIR))
      throw InputError(errnoText(dir) + " (nothing was graded)");
  }
  const std::vector<BatchEntry> selected = shardEntries(batchEntries(dirs), options.shard);
  std::error_code error;
  fs::create_directories(options.out_dir, error);
  if (error || !fs::is_directory(options.out_dir, error))
    throw InputError(safeName(options.out_dir.string()) +
                     ": cannot create the batch folder (--out)" +
                     (error ? ": " + error.message() : std::string()));
  // BATCHDIR itself the user named (a link to it is theirs); inside it nothing is followed.
  const Fd batch(::open(options.out_dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (batch.fd < 0) throw InputError(errnoText(options.out_dir) + " (--out)");
  BatchSummary summary;
  const std::string shard_suffix = options.shard.count == 1
                                       ? std::string()
                                       : "-" + std::to_string(options.shard.index) + "-of-" +
                                             std::to_string(options.shard.count);
  summary.csv = options.csv;
  if (summary.csv.empty()) summary.csv = options.out_dir / ("grades" + shard_suffix + ".csv");
  summary.index = options.out_dir / ("index" + shard_suffix + ".html");

  // A folder of the batch that is a link or a file (planted, or the user's) stops the batch before
  // anything is graded: its results would be written wherever it points.
  for (const BatchEntry& entry : selected) {
    struct stat st {};
    if (::fstatat(batch.fd, entry.name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        !S_ISDIR(st.st_mode))
      throw InputError(safeName((options.out_dir / entry.name).string()) +
                       ": not a folder of the batch (" +
                       (S_ISLNK(st.st_mode) ? "a symbolic link" : "not a directory") +
                       "; results are never written through it: remove it) (nothing was graded)");
  }

  std::vector<const BatchEntry*> pending;
  for (const BatchEntry& entry : selected) {
    if (!options.regrade && finishedRow(batch.fd, options.out_dir, entry.name)) {
      ++summary.skipped;
      continue;
    }
    // Not graded, half graded, or asked to regrade: without its marker the folder counts as
    // not graded until the new row is written, whatever happens in between.
    const Fd folder(
        ::openat(batch.fd, entry.name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (folder.fd >= 0) ::unlinkat(folder.fd, kRowFile, 0);
    pending.push_back(&entry);
  }

  const int cores = options.cores > 0
                        ? options.cores
                        : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  GradeOptions grade = options.grade;
  grade.probe_jobs = grade.toolchain.jobs = perSubmissionJobs(options.jobs, cores);
  // Without --cache-dir a batch still shares compiled objects and the precompiled header
  // between its submissions (and with its own reruns): in BATCHDIR/.cache.
  if (grade.toolchain.cache_dir.empty()) grade.toolchain.cache_dir = options.out_dir / kCacheDir;
  // No student's code may read the batch folder (the others' results) or another's submission.
  grade.private_paths.push_back(options.out_dir);
  for (const BatchEntry& entry : selected) grade.private_paths.push_back(entry.dir);

  Progress progress("clothref grade", static_cast<std::int64_t>(pending.size()), "submissions",
                    progressStyleForStderr(options.quiet), progress_out);
  std::mutex mutex;  // guards the counters, the progress and the output files
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  int done = 0, failed = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto worker = [&] {
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (failure) return;
      }
      const std::size_t k = next++;
      if (k >= pending.size()) return;
      const BatchEntry& entry = *pending[k];
      const auto graded_start = std::chrono::steady_clock::now();
      Outputs out = gradeOne(entry, options, grade);
      out.row.seconds = since(graded_start);
      std::lock_guard<std::mutex> lock(mutex);
      try {
        const fs::path path = options.out_dir / entry.name;
        const Fd folder = openFolder(batch.fd, options.out_dir, entry.name);
        writeNoFollow(folder.fd, path, "results.json", out.results_json);
        writeNoFollow(folder.fd, path, "report.md", out.report_md);
        if (!out.report_html.empty())
          writeNoFollow(folder.fd, path, "report.html", out.report_html);
        writeNoFollow(folder.fd, path, kRowFile,
                      rowJson(out.row).dump(2, ' ', false, kReplace) + "\n");  // the marker, last
      } catch (...) {
        failure = std::current_exception();
        return;
      }
      ++done;
      if (out.row.verdict != Verdict::Graded) ++failed;
      if (!out.time_note.empty())  // graded: a refused folder costs nothing to speak of
        noteIfSlow(summary.slowest, {entry.name, out.row.seconds, out.time_note});
      const double eta = since(start) / done * static_cast<double>(pending.size() - done);
      progress.update(done, std::to_string(failed) + " failed, ETA " + formatDuration(eta));
    }
  };
  std::vector<std::thread> threads;
  const int workers = std::max(1, std::min<int>(options.jobs, static_cast<int>(pending.size())));
  for (int w = 0; w < workers; ++w) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  progress.finish();
  if (failure) std::rethrow_exception(failure);
  summary.graded = done;

  // The CSV comes from the markers alone, so a resumed batch gets the same file as one that ran
  // through.
  for (const BatchEntry& entry : selected) {
    std::optional<BatchRow> row = readRow(batch.fd, options.out_dir, entry.name);
    if (!row)
      throw InputError(safeName((options.out_dir / entry.name / kRowFile).string()) +
                       ": missing after grading");
    if (row->verdict != Verdict::Graded) {
      ++summary.failed;
      summary.not_graded.push_back({row->name, row->verdict});
    }
    if (!row->isolation.empty() && std::find(summary.isolation.begin(), summary.isolation.end(),
                                             row->isolation) == summary.isolation.end())
      summary.isolation.push_back(row->isolation);
    summary.rows.push_back(std::move(*row));
  }
  // The CSV where --csv says (the user named it: written as any named output), else beside the
  // class overview in BATCHDIR, never through a link there.
  const std::string csv = batchCsv(summary.rows, options.csv_header);
  if (options.csv.empty()) {
    writeNoFollow(batch.fd, options.out_dir, summary.csv.filename().string(), csv);
  } else {
    OutputFile out(summary.csv.string());
    out.stream() << csv;
    out.commit();
  }
  // the class overview, from the same markers (html_report.h)
  writeNoFollow(batch.fd, options.out_dir, summary.index.filename().string(),
                batchIndexHtml(classRows(options.out_dir, summary.rows)));
  return summary;
}

}  // namespace clothref::grader
