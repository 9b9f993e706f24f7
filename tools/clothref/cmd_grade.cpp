// clothref grade DIR...: compile a student's cloth.cpp, sphere.cpp and integrator.cpp against the
// course stand-in and grade each stub (docs/grading-reference.md). With --out BATCHDIR: a batch
// (many submissions in parallel, resume, shards, a CSV summary; grader/grade/batch.h).
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "commands.h"
#include "grader/grade/batch.h"
#include "grader/grade/grade.h"
#include "grader/grade/report/html_report.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/submission/submission.h"
#include "grader/grade/text.h"

namespace clothref::cli {
namespace {

constexpr double kMaxTimeoutSeconds = 24 * 3600;  // one day: past it a probe is simply stuck

// The user's text in a message: escaped, and cut (a 300-digit number says nothing more).
std::string shownText(const std::string& text) {
  const std::string safe = grader::safeName(text);
  return safe.size() > 32 ? safe.substr(0, 32) + "..." : safe;
}

// --timeout: seconds in (0, 1 day]. NaN, infinity and huge values would set no limit at all.
CLI::Validator timeoutSeconds() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value))
          return "expected a number of seconds, got '" + shownText(text) + "'";
        if (!(value > 0 && value <= kMaxTimeoutSeconds))
          return "must be > 0 and <= 86400 seconds (got " + shownText(text) + ")";
        return "";
      },
      "seconds, (0, 86400]");
}

// A named output (--results, --junit, --report, --html, --csv) is checked before anything is
// graded: a symbolic link is refused (never written through: give the file it names), and a folder
// that does not exist or cannot be written is named with the reason, so a typo costs no grading.
void checkOutputPath(const std::string& option, const std::string& path) {
  if (path.empty() || path == "-") return;
  const std::string shown = option + " " + grader::safeName(path);
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode))
      throw InputError(shown +
                       ": a symbolic link; outputs are never written through a link (give the "
                       "file it names, or remove the link)");
    if (S_ISDIR(st.st_mode)) throw InputError(shown + ": a directory, not a file");
  }
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (::stat(folder.c_str(), &st) != 0)
    throw InputError(shown + ": " + grader::safeName(folder.string()) + ": " +
                     std::strerror(errno));
  if (!S_ISDIR(st.st_mode))
    throw InputError(shown + ": " + grader::safeName(folder.string()) + ": " +
                     std::strerror(ENOTDIR));
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError(shown + ": " + grader::safeName(folder.string()) + ": " +
                     std::strerror(errno));
}

// The batch's last lines: the slowest submissions and why, what it did, the submissions whose
// verdict is not `graded` (at most 20 by name), and where the CSV and the class overview are.
void printBatchEnd(const grader::BatchSummary& summary) {
  // where the time went first: the lines after the summary stay the last ones
  if (!summary.slowest.empty()) {
    std::cerr << "clothref grade: the slowest:\n";
    for (const auto& slow : summary.slowest)
      std::cerr << "  " << grader::safeName(slow.name) << ": " << std::fixed << std::setprecision(1)
                << slow.seconds << " s (" << slow.why << ")\n";
    std::cerr.unsetf(std::ios::floatfield);
  }
  std::cerr << "clothref grade: " << summary.rows.size() << " submissions (" << summary.graded
            << " graded now, " << summary.skipped << " already graded), " << summary.failed
            << " with a verdict other than 'graded'" << (summary.not_graded.empty() ? "" : ":")
            << '\n';
  for (std::size_t k = 0; k < summary.not_graded.size() && k < 20; ++k)
    std::cerr << "  " << grader::safeName(summary.not_graded[k].first) << ": "
              << grader::verdictId(summary.not_graded[k].second) << '\n';
  if (summary.not_graded.size() > 20)
    std::cerr << "  ... and " << summary.not_graded.size() - 20 << " more (the CSV has them all)\n";
  for (const std::string& isolation : summary.isolation)
    std::cerr << "clothref grade: student code ran with: " << grader::safeName(isolation) << '\n';
  std::cerr << "clothref grade: CSV " << grader::safeName(summary.csv.string())
            << "; class overview " << grader::safeName(summary.index.string()) << '\n';
}

}  // namespace

Command addGradeCommand(CLI::App& root) {
  auto* app = root.add_subcommand(
      "grade", "Grade student submissions stub by stub (compile, probe, score, feedback)");
  struct Options {
    std::vector<std::string> dirs;
    int edition = 0;
    std::string results, junit, report, rubric, keep_work, cache_dir, html;
    bool no_whole_run = false;
    double timeout = 20;
    std::string optimisation = "-O2";
    std::size_t max_file_bytes = grader::kDefaultMaxSourceBytes;
    // batch
    std::string out, csv, shard;
    int jobs = 1;
    bool regrade = false, csv_no_header = false, quiet = false, sanitize = false;
    bool one_submission = false;
  };
  auto options = std::make_shared<Options>();
  app->add_option("DIR", options->dirs, "submission directories (the three files anywhere below)")
      ->required();  // checked by the grading: in a batch, a bad DIR is a row, not an abort
  app->add_option("--edition", options->edition,
                  "course edition (default: detected from the files)")
      ->check(CLI::IsMember({2022, 2024}));
  app->add_option("--results", options->results, "write Gradescope results.json here");
  app->add_option("--junit", options->junit, "write JUnit XML here");
  app->add_option("--report", options->report, "write the Markdown report here (default: stdout)");
  app->add_option("--html", options->html,
                  "write the HTML report here (checks, the whole run beside the reference)");
  app->add_option("--rubric", options->rubric,
                  "JSON rubric: weights, tolerances, accepted variants, per-mistake or per-check "
                  "scoring")
      ->check(CLI::ExistingFile);
  app->add_option("--timeout", options->timeout,
                  "wall-clock limit per probe process, seconds (at most 86400)")
      ->check(timeoutSeconds());
  app->add_option("--max-file-bytes", options->max_file_bytes,
                  "largest student file read, bytes (default 16777216); a larger one is refused "
                  "and graded as missing")
      ->check(atLeast(1));
  app->add_option("--opt", options->optimisation, "optimisation flag for student code")
      ->check(CLI::IsMember({"-O0", "-O1", "-O2", "-O3"}));
  app->add_option("--cache-dir", options->cache_dir,
                  "reuse compiled objects of identical files across runs (keyed by bytes + flags)");
  app->add_option("--keep-work", options->keep_work,
                  "copy the scratch folder (objects, probe I/O, child output) to this directory");
  app->add_flag("--no-whole-run", options->no_whole_run, "skip the information-only whole run");
  app->add_flag(
      "--sanitize", options->sanitize,
      "accepted for old scripts; nothing to ask for: a probe that crashes or whose two runs differ "
      "is rebuilt with ASan/UBSan (-g -Og) by itself and its first report quoted");
  app->add_flag("--one-submission", options->one_submission,
                "grade a DIR that holds several whole submissions as one (without it, such a "
                "folder is refused, naming them)");
  app->add_option("--out", options->out,
                  "batch: grade every DIR into this folder (BATCHDIR/<name>/results.json, "
                  "report.md, report.html; BATCHDIR/grades.csv and the class overview "
                  "BATCHDIR/index.html)");
  app->add_option("--jobs", options->jobs, "batch: submissions graded at once (default 1)")
      ->check(atLeast(1));
  auto* shard =
      app->add_option("--shard", options->shard,
                      "batch: grade only part k of n of the sorted submissions (k/n, 1 <= k <= n)");
  app->add_flag("--regrade", options->regrade,
                "batch: grade again submissions a previous run already graded");
  app->add_option("--csv", options->csv,
                  "batch: write the CSV summary here (default BATCHDIR/grades.csv, or "
                  "BATCHDIR/grades-k-of-n.csv with --shard)");
  app->add_flag("--csv-no-header", options->csv_no_header,
                "batch: no header line in the CSV (for shards 2..n before concatenating)");
  app->add_flag("--quiet", options->quiet, "batch: no progress or summary on stderr");
  return {app, [options, shard] {
            const bool batch = !options->out.empty();
            const bool single = options->dirs.size() == 1 && !batch;
            if (!single && (!options->results.empty() || !options->junit.empty() ||
                            !options->report.empty() || !options->html.empty()))
              throw InputError(
                  batch ? "--results, --junit, --report and --html are per submission; a batch "
                          "(--out) writes them into BATCHDIR/<name>/"
                        : "--results, --junit, --report and --html take one submission DIR; got " +
                              std::to_string(options->dirs.size()));
            const bool sharded = shard->count() > 0;  // --shard "" is a shard, and a bad one
            if (!batch && (options->jobs != 1 || sharded || options->regrade ||
                           !options->csv.empty() || options->csv_no_header))
              throw InputError(
                  "--jobs, --shard, --regrade, --csv and --csv-no-header need --out "
                  "BATCHDIR (batch grading)");
            for (const auto& [option, path] :
                 {std::pair<const char*, std::string>{"--results", options->results},
                  {"--junit", options->junit},
                  {"--report", options->report},
                  {"--html", options->html},
                  {"--csv", options->csv}})
              checkOutputPath(option, path);
            grader::GradeOptions grade;
            grade.edition = options->edition;
            if (!options->rubric.empty()) grade.rubric_path = options->rubric;
            grade.keep_work = options->keep_work;
            grade.whole_run = !options->no_whole_run;
            grade.limits = grader::limitsForTimeout(options->timeout);
            grade.max_file_bytes = options->max_file_bytes;
            grade.toolchain.optimisation = options->optimisation;
            grade.toolchain.cache_dir = options->cache_dir;
            if (batch) {
              grader::BatchOptions batch_options;
              batch_options.out_dir = options->out;
              batch_options.csv = options->csv;
              batch_options.csv_header = !options->csv_no_header;
              batch_options.jobs = options->jobs;
              if (sharded) batch_options.shard = grader::parseShard(options->shard);
              batch_options.regrade = options->regrade;
              batch_options.quiet = options->quiet;
              batch_options.one_submission = options->one_submission;
              batch_options.grade = grade;
              std::vector<std::filesystem::path> dirs(options->dirs.begin(), options->dirs.end());
              const grader::BatchSummary summary = grader::runBatch(dirs, batch_options, std::cerr);
              if (!options->quiet) printBatchEnd(summary);
              return kExitOk;  // every submission has a row, whatever its verdict
            }
            int exit_code = kExitOk;
            for (const std::string& dir : options->dirs) {
              grader::GradeReport report;
              nlohmann::ordered_json whole_run_view;  // --html's pictures
              try {
                if (!options->one_submission) {
                  const std::vector<std::string> several = grader::submissionsBelow(dir);
                  if (!several.empty())
                    throw InputError(grader::severalSubmissionsProblem(dir, several));
                }
                report = grader::gradeSubmission(dir, grade);
                if (!options->html.empty()) whole_run_view = grader::wholeRunView(report);
              } catch (const InputError& error) {
                std::cerr << "clothref grade: " << grader::safeName(error.what()) << '\n';
                exit_code = kExitBadInput;
                continue;
              }
              // Every output is rendered first, then written; when one cannot be written (a full
              // disk) those already written by this run are removed again and no "graded" line
              // claims success: all of the outputs or none of them.
              std::vector<std::pair<std::string, std::string>> outputs;  // path, bytes
              if (!options->results.empty())
                outputs.emplace_back(
                    options->results,
                    grader::withHtmlSummary(grader::resultsJson(report), report)
                            .dump(2, ' ', false, nlohmann::json::error_handler_t::replace) +
                        "\n");
              if (!options->html.empty())
                outputs.emplace_back(options->html,
                                     grader::studentReportHtml(report, whole_run_view));
              if (!options->junit.empty())
                outputs.emplace_back(options->junit, grader::junitXml(report));
              if (!options->report.empty())
                outputs.emplace_back(options->report, grader::markdownReport(report));
              std::vector<std::string> written;
              try {
                for (const auto& [path, bytes] : outputs) {
                  OutputFile out(path);
                  out.stream() << bytes;
                  out.commit();
                  written.push_back(path);
                }
              } catch (const InputError&) {
                for (const std::string& path : written) {
                  std::error_code ignored;
                  if (std::filesystem::is_regular_file(path, ignored))
                    std::filesystem::remove(path, ignored);
                }
                throw;
              }
              if (single && outputs.empty()) std::cout << grader::markdownReport(report);
              if (!options->quiet) {
                for (const std::string& line : grader::choiceLines(report))
                  std::cerr << "clothref grade: " << line << '\n';
                std::cerr << grader::summaryLine(report) << '\n';
              }
            }
            return exit_code;
          }};
}

}  // namespace clothref::cli
