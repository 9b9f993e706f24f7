// clothref golden: check the golden data against the code (default), or regenerate it (--update).
// The directory is --dir, else the source tree's golden/ recorded when the build was configured, so
// running from another directory checks the real data. --update rewrites an existing golden set
// only; a new one needs --create, so a typo never yields a fresh set that checks against itself.
// The check prints the diff report of each mismatch, one line per matching entry with --verbose,
// and a final count line; it exits 0 when everything matches, 1 on a mismatch, 2 on bad input.
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "clothref/golden/golden.h"
#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/output_file.h"
#include "clothref/io/progress.h"
#include "clothref/io/terminal_text.h"
#include "commands.h"

#ifndef CLOTHREF_DATA_FROM_BIN
#define CLOTHREF_DATA_FROM_BIN ""
#endif

namespace clothref::cli {

namespace {

struct GoldenOptions {
  // an install's own copy (<prefix>/share/clothref/golden), else the source tree's
  std::string golden = installedDataDir(CLOTHREF_DATA_FROM_BIN).empty()
                           ? std::string(CLOTHREF_GOLDEN_DIR)
                           : (installedDataDir(CLOTHREF_DATA_FROM_BIN) / "golden").string();
  bool update = false;
  bool create = false;
  bool quiet = false;
  bool verbose = false;
  std::optional<std::int64_t> ulps;
  std::string tolerances;
  bool skip_hashes = false;
};

// A golden set is a directory with a manifest; anything else is refused before any work.
void requireGoldenSet(const GoldenOptions& options) {
  const std::filesystem::path manifest = std::filesystem::path(options.golden) / "manifest.json";
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(manifest, error);
  if (std::filesystem::is_regular_file(status)) return;
  // named as what it is (and never opened: a FIFO would block the read)
  if (std::filesystem::exists(status))
    throw InputError(fmt::format("{}: {}, not a regular file", manifest.string(),
                                 std::filesystem::is_directory(status) ? "a directory"
                                 : std::filesystem::is_fifo(status)    ? "a FIFO"
                                                                       : "a special file"));
  if (error && error != std::errc::no_such_file_or_directory)
    throw InputError(fmt::format("{}: cannot be read: {}", manifest.string(), error.message()));
  throw InputError(fmt::format(
      "{}: golden directory not found (no manifest.json); give it with --dir, or make a new "
      "golden set there with --update --create",
      options.golden));
}

int runUpdate(const GoldenOptions& options) {
  if (!options.create) requireGoldenSet(options);
  const GoldenUpdateSummary summary = updateGolden(options.golden);
  std::cerr << fmt::format(
      "clothref golden: wrote {} scenes, {} traces and a manifest with {} hash runs to {}\n",
      summary.scenes, summary.traces, summary.hash_runs, options.golden);
  for (const std::filesystem::path& removed : summary.removed)
    std::cerr << fmt::format("  removed stale {}\n", terminalSafe(removed.string()));
  return kExitOk;
}

// Indents every line of a multi-line report under its entry.
std::string indented(const std::string& text) {
  std::string out = "    ";
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '\n' && i + 1 < text.size()) out += "    ";
  }
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

int runCheck(const GoldenOptions& options) {
  GoldenCheckOptions check;
  if (!options.tolerances.empty()) check.diff = readToleranceFile(options.tolerances);
  if (options.ulps) {
    if (*options.ulps < 0)
      throw InputError(fmt::format("--ulps: must be >= 0 (got {})", *options.ulps));
    check.diff.global = Tolerance{};
    check.diff.global.ulps = *options.ulps;
  }
  check.check_hashes = !options.skip_hashes;
  requireGoldenSet(options);

  const GoldenSet& defined = goldenSet();
  // counts what is checked: the hash runs only when they are
  const std::size_t entries_checked = defined.scenes.size() + defined.traces.size() +
                                      (options.skip_hashes ? 0 : defined.hash_runs.size());
  Progress progress("clothref golden", static_cast<std::int64_t>(entries_checked), "entries",
                    progressStyleForStderr(options.quiet), std::cerr);
  std::int64_t entries = 0;
  const GoldenCheckSummary summary =
      checkGolden(options.golden, check, [&](const GoldenEntryResult& entry) {
        progress.update(++entries);
        if (entry.matched && !options.verbose) return;
        progress.finish();  // a report line must not land inside the terminal's progress line
        // names and summaries quote manifest paths and scene names: escaped for the terminal
        std::cout << fmt::format("{:<8} {:<6} {}: {}\n", entry.matched ? "ok" : "MISMATCH",
                                 entry.kind, terminalSafe(entry.name), terminalSafe(entry.summary));
        if (!entry.report.empty()) std::cout << indented(terminalSafe(entry.report, true));
        std::cout.flush();
      });
  progress.finish();
  std::cout << fmt::format("clothref golden: {} of {} entries match, {} mismatch ({}{})\n",
                           summary.checked - summary.mismatched, summary.checked,
                           summary.mismatched, options.golden,
                           options.skip_hashes ? ", hash runs skipped" : "");
  return summary.mismatched ? kExitDiffer : kExitOk;
}

}  // namespace

Command addGoldenCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "golden",
      "Check the golden data (scenes, traces, per-step hashes) against the code, or regenerate "
      "it with --update (docs/regression.md)");
  auto options = std::make_shared<GoldenOptions>();
  app->add_option(
         "--dir,--golden", options->golden,
         "Golden directory (default: an installed clothref's own copy, else the source tree's)")
      ->capture_default_str();
  CLI::Option* update =
      app->add_flag("--update", options->update,
                    "Regenerate every golden file of an existing golden set from the code and "
                    "delete stale ones");
  app->add_flag("--create", options->create,
                "With --update: make a new golden set in a directory that has none")
      ->needs(update);
  app->add_flag("-q,--quiet", options->quiet, "No progress on stderr");
  app->add_flag("-v,--verbose", options->verbose, "Also print one line per matching entry")
      ->excludes(update);
  app->add_option("--ulps", options->ulps,
                  "Let trace values differ by up to N units in the last place (default 0: exact)")
      ->excludes(update);
  app->add_option("--tolerances", options->tolerances,
                  "Tolerance file for the traces (docs/trace-format.md); --ulps overrides its "
                  "default")
      ->excludes(update);
  app->add_flag("--skip-hashes", options->skip_hashes,
                "Do not check the per-step hash runs (they are exact by nature: skip them on a "
                "toolchain other than the one that made the files)")
      ->excludes(update);
  return {app, [options] { return options->update ? runUpdate(*options) : runCheck(*options); }};
}

}  // namespace clothref::cli
