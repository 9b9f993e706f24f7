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
#include "grader/grade/report/html_report.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

constexpr const char* kRowFile = "row.json";
constexpr const char* kCacheDir = ".cache";  // no submission name starts with a dot
// The writers already give valid UTF-8 (text.h); should a byte slip through, it becomes U+FFFD
// rather than an exception that loses the submission's row.
constexpr auto kReplace = nlohmann::json::error_handler_t::replace;

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A path component as a folder name: letters, digits, '.', '_' and '-' kept, the rest '_'; never
// starting with a dot (so never "." or "..", nor BATCHDIR/.cache).
std::string safeComponent(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  if (out.empty() || out.front() == '.') out = "_" + out;
  return out;
}

// Rounded to 0.001, without trailing zeros: "12.5", "80", "3.333".
std::string number(double value) {
  std::ostringstream out;
  out << std::round(value * 1000) / 1000;
  return out.str();
}

std::string csvField(const std::string& given) {
  const std::string text = safeName(given);  // valid UTF-8, one line, no terminal escapes
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void writeText(const fs::path& path, const std::string& text) {
  OutputFile out(path.string());
  out.stream() << text;
  out.commit();
}

// The row a previous run left in `folder`, or nullopt (none, unreadable, or a grader error,
// which is ours to retry).
std::optional<BatchRow> finishedRow(const fs::path& folder) {
  std::error_code error;
  const fs::path path = folder / kRowFile;
  if (!fs::exists(path, error)) return std::nullopt;
  try {
    BatchRow row = rowFromJson(readJsonFile(path.string(), "batch row"), path.string());
    if (row.verdict == Verdict::GraderError) return std::nullopt;
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
};

Outputs notGradable(const BatchEntry& entry, Verdict verdict,
                    const std::string& problem) {
  Outputs out;
  out.row.name = entry.name;
  out.row.dir = safeName(entry.dir.string());
  out.row.verdict = verdict;
  out.row.problem = safeName(problem);
  const std::string text =
      verdict == Verdict::NotGradable
          ? "The submission could not be graded: " + out.row.problem
          : "The grader failed on this submission (" + out.row.problem + "); see the course staff.";
  nlohmann::ordered_json results;
  results["score"] = 0;
  results["output"] = text;
  results["output_format"] = "md";
  results["visibility"] = "visible";
  results["tests"] = nlohmann::ordered_json::array();
  out.results_json = results.dump(2, ' ', false, kReplace) + "\n";
  out.report_md = "# Grading report: " + out.row.dir + "\n\n**" + verdictId(verdict) + "**. " + text + "\n";
  return out;
}

Outputs gradeOne(const BatchEntry& entry, const GradeOptions& grade) {
  try {
    nlohmann::ordered_json whole_run_view;  // the pictures of report.html (html_report.h)
    GradeReport report = gradeWithWholeRun(entry.dir, grade, whole_run_view);
    Outputs out;
    out.row = rowOf(entry, report);
    out.results_json =
        withHtmlSummary(resultsJson(report), report).dump(2, ' ', false, kReplace) + "\n";
    out.report_md = markdownReport(report);
    out.report_html = studentReportHtml(report, whole_run_view);
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
    std::error_code error;
    fs::path full = fs::weakly_canonical(fs::absolute(dir), error);
    if (error) full = fs::absolute(dir).lexically_normal();
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

BatchRow rowOf(const BatchEntry& entry, const GradeReport& report) {
  BatchRow row;
  row.name = entry.name;
  row.dir = safeName(entry.dir.string());
  row.edition = report.edition;
  row.stub_score = report.stub_score;
  row.stub_max = report.stub_max;
  row.score = report.score;
  row.max_score = report.max_score;
  row.verdict = report.verdict;
  row.isolation = safeName(report.isolation);
  row.seconds = report.seconds.count("total") ? report.seconds.at("total") : 0;
  return row;
}

nlohmann::ordered_json rowJson(const BatchRow& row) {
  nlohmann::ordered_json json;
  json["submission"] = row.name;
  json["dir"] = row.dir;
  json["edition"] = row.edition;
  json["stub_scores"] = row.stub_score;
  json["stub_max"] = row.stub_max;
  json["total"] = row.score;
  json["max"] = row.max_score;
  json["verdict"] = verdictId(row.verdict);
  json["isolation"] = row.isolation;
  json["problem"] = row.problem;
  json["seconds"] = row.seconds;
  return json;
}

BatchRow rowFromJson(const nlohmann::json& json, const std::string& where) {
  try {
    BatchRow row;
    row.name = json.at("submission").get<std::string>();
    row.dir = json.at("dir").get<std::string>();
    row.edition = json.at("edition").get<int>();
    row.stub_score = json.at("stub_scores").get<std::map<std::string, double>>();
    row.stub_max = json.at("stub_max").get<std::map<std::string, double>>();
    row.score = json.at("total").get<double>();
    row.max_score = json.at("max").get<double>();
    if (!verdictFromId(json.at("verdict").get<std::string>(), row.verdict))
      throw InputError(where + ": not a batch row (unknown verdict)");
    row.isolation = json.at("isolation").get<std::string>();
    row.problem = json.at("problem").get<std::string>();
    row.seconds = json.at("seconds").get<double>();
    return row;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(where + ": not a batch row (" + error.what() + ")");
  }
}

std::string batchCsv(const std::vector<BatchRow>& rows, bool header) {
  std::string out;
  if (header) {
    out += "submission,edition";
    for (const std::string& stub : stubNames()) out += "," + csvField(stub);
    out += ",total,max,verdict,isolation,seconds\n";
  }
  for (const BatchRow& row : rows) {
    out += csvField(row.name) + "," + (row.edition ? std::to_string(row.edition) : "");
    for (const std::string& stub : stubNames()) {
      auto it = row.stub_score.find(stub);
      out += "," + (it == row.stub_score.end() ? std::string() : number(it->second));
    }
    std::ostringstream seconds;
    seconds.setf(std::ios::fixed);
    seconds.precision(1);
    seconds << row.seconds;
    out += "," + number(row.score) + "," + number(row.max_score) + "," + csvField(verdictId(row.verdict)) +
           "," + csvField(row.isolation) + "," + seconds.str() + "\n";
  }
  return out;
}

int perSubmissionJobs(int jobs, int cores) { return std::max(1, cores / std::max(1, jobs)); }

BatchSummary runBatch(const std::vector<fs::path>& dirs, const BatchOptions& options,
                      std::ostream& progress_out) {
  const std::vector<BatchEntry> selected = shardEntries(batchEntries(dirs), options.shard);
  std::error_code error;
  fs::create_directories(options.out_dir, error);
  if (error || !fs::is_directory(options.out_dir, error))
    throw InputError(safeName(options.out_dir.string()) +
                     ": cannot create the batch folder (--out)");
  BatchSummary summary;
  summary.csv = options.csv;
  if (summary.csv.empty())
    summary.csv =
        options.out_dir / (options.shard.count == 1
                               ? std::string("grades.csv")
                               : "grades-" + std::to_string(options.shard.index) + "-of-" +
                                     std::to_string(options.shard.count) + ".csv");

  std::vector<const BatchEntry*> pending;
  for (const BatchEntry& entry : selected) {
    if (!options.regrade && finishedRow(options.out_dir / entry.name)) {
      ++summary.skipped;
      continue;
    }
    // Not graded, half graded, or asked to regrade: without its marker the folder counts as
    // not graded until the new row is written, whatever happens in between.
    fs::remove(options.out_dir / entry.name / kRowFile, error);
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
      Outputs out = gradeOne(entry, grade);
      out.row.seconds = since(graded_start);
      std::lock_guard<std::mutex> lock(mutex);
      try {
        // OutputFile keeps one temporary for its signal handler: one writer at a time.
        const fs::path folder = options.out_dir / entry.name;
        fs::create_directories(folder);
        writeText(folder / "results.json", out.results_json);
        writeText(folder / "report.md", out.report_md);
        if (!out.report_html.empty()) writeText(folder / "report.html", out.report_html);
        writeText(folder / kRowFile,
                  rowJson(out.row).dump(2, ' ', false, kReplace) + "\n");  // the marker, last
      } catch (...) {
        failure = std::current_exception();
        return;
      }
      ++done;
      if (out.row.verdict != Verdict::Graded) ++failed;
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
    const fs::path path = options.out_dir / entry.name / kRowFile;
    BatchRow row = rowFromJson(readJsonFile(path.string(), "batch row"), path.string());
    if (row.verdict != Verdict::Graded) ++summary.failed;
    summary.rows.push_back(std::move(row));
  }
  writeText(summary.csv, batchCsv(summary.rows, options.csv_header));
  // the class overview, from the same markers (html_report.h), beside the CSV
  writeText(options.out_dir / (options.shard.count == 1
                                   ? std::string("index.html")
                                   : "index-" + std::to_string(options.shard.index) + "-of-" +
                                         std::to_string(options.shard.count) + ".html"),
            batchIndexHtml(options.out_dir, summary.rows));
  return summary;
}

}  // namespace clothref::grader
