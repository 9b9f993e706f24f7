// golden.cpp: the golden set definition, the manifest reader, an update of a small golden set
// into a temporary directory (stale files swept, others kept), the check passing on what update
// wrote, a tampered copy failing with exactly the tampered entries named, and the CLI's exit codes.
// (The full set is checked by the ctest `golden`.)
#include "clothref/golden/golden.h"
#include "clothref/scene/make_world.h"

#include <unistd.h>

#include <algorithm>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "clothref/io/error.h"
#include "clothref/record/world_views.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

bool hasRun(const GoldenSet& set, const std::string& scene, Method method, Precision precision,
            std::int64_t steps) {
  return std::any_of(set.hash_runs.begin(), set.hash_runs.end(), [&](const HashRun& run) {
    return run.scene == scene && run.method == method && run.precision == precision &&
           run.steps == steps;
  });
}

TEST(GoldenSet, CoversEverySceneAndIntegrator) {
  const GoldenSet& set = goldenSet();
  ASSERT_EQ(set.scenes.size(), builtinScenes().size());
  for (const Scene& scene : builtinScenes()) {
    for (Method method : kAllMethods) {
      const std::string file = fmt::format("traces/{}.{}.jsonl", scene.name, methodName(method));
      const auto trace = std::find_if(set.traces.begin(), set.traces.end(),
                                      [&](const GoldenTrace& t) { return t.file == file; });
      ASSERT_NE(trace, set.traces.end()) << file;
      EXPECT_EQ(trace->scene, scene.name);
      EXPECT_EQ(trace->settings.method, method);
      EXPECT_EQ(trace->settings.precision, Precision::Float);
      EXPECT_EQ(trace->settings.dt, scene.dt);
      const bool small = scene.name.rfind("course", 0) != 0;
      if (small) {
        EXPECT_TRUE(hasRun(set, scene.name, method, Precision::Float, 1000) ||
                    hasRun(set, scene.name, method, Precision::Float, 3000))
            << scene.name;
        EXPECT_TRUE(hasRun(set, scene.name, method, Precision::Double, 1000) ||
                    hasRun(set, scene.name, method, Precision::Double, 3000))
            << scene.name;
      }
    }
  }
  for (Method method : kAllMethods)
    EXPECT_TRUE(hasRun(set, "course2022", method, Precision::Float, 1000)) << methodName(method);
  for (Method method : kAllMethods)
    EXPECT_TRUE(hasRun(set, "course2022", method, Precision::Float, 10000)) << methodName(method);
  // The spheres reach the course2022 cloth at ~0.32 s: the stored trace must go past it.
  for (const GoldenTrace& trace : set.traces) {
    if (trace.scene == "course2022") {
      EXPECT_GT(double(trace.settings.steps) * trace.settings.dt, 0.32);
    }
  }
}

TEST(GoldenSet, HashesStartAtTheInitialState) {
  const Scene& scene = *findBuiltinScene("two-spheres");
  const std::vector<std::uint64_t> hashes =
      computeHashes(scene, Method::Rk4, Precision::Double, scene.dt, 3);
  ASSERT_EQ(hashes.size(), 4u);
  World<double> world = makeWorld<double>(scene, Method::Rk4);
  EXPECT_EQ(hashes[0], stateHash(world));
  for (int s = 1; s <= 3; ++s) {
    step(world);
    EXPECT_EQ(hashes[s], stateHash(world)) << "step " << s;
  }
}

TEST(Manifest, TextRoundTrips) {
  GoldenSet set = goldenSet();
  for (HashRun& run : set.hash_runs)
    run.hashes.assign(static_cast<std::size_t>(run.steps) + 1, "0123456789abcdef");
  set.hash_runs.front().hashes.back() = "fedcba9876543210";
  const GoldenSet back = manifestFromJson(nlohmann::json::parse(manifestText(set)), "m.json");
  EXPECT_EQ(back.scenes, set.scenes);
  ASSERT_EQ(back.traces.size(), set.traces.size());
  for (std::size_t i = 0; i < set.traces.size(); ++i) {
    EXPECT_EQ(back.traces[i].file, set.traces[i].file);
    EXPECT_EQ(back.traces[i].settings.dt, set.traces[i].settings.dt);
    EXPECT_EQ(back.traces[i].settings.stride, set.traces[i].settings.stride);
  }
  ASSERT_EQ(back.hash_runs.size(), set.hash_runs.size());
  for (std::size_t i = 0; i < set.hash_runs.size(); ++i) {
    EXPECT_TRUE(back.hash_runs[i].sameRun(set.hash_runs[i]));
    EXPECT_EQ(back.hash_runs[i].hashes, set.hash_runs[i].hashes);
  }
}

// The InputError message for a manifest with one field changed.
std::string manifestError(const std::string& pointer, const nlohmann::json& value) {
  GoldenSet set;
  set.scenes = {"spring"};
  set.traces = {goldenSet().traces.front()};
  set.hash_runs = {HashRun{
      "spring", Method::Rk4, Precision::Float, 1e-3, 1, {"0123456789abcdef", "0123456789abcdef"}}};
  nlohmann::json document = nlohmann::json::parse(manifestText(set));
  document[nlohmann::json::json_pointer(pointer)] = value;
  try {
    manifestFromJson(document, "golden/manifest.json");
  } catch (const InputError& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(Manifest, BadFieldsAreNamed) {
  EXPECT_EQ(manifestError("/traces/0/steps", "10"),
            "golden/manifest.json: /traces/0/steps: expected an integer");
  EXPECT_EQ(manifestError("/traces/0/integrator", "euler"),
            "golden/manifest.json: /traces/0/integrator: unknown method 'euler'");
  EXPECT_EQ(manifestError("/traces/0/file", "../../etc/passwd"),
            "golden/manifest.json: /traces/0/file: must be a file under traces/ (got "
            "'../../etc/passwd')");
  EXPECT_EQ(manifestError("/hash_runs/0/hashes/1", "xyz"),
            "golden/manifest.json: /hash_runs/0/hashes/1: expected 16 lowercase hex digits");
  EXPECT_EQ(manifestError("/hash_runs/0/steps", 5),
            "golden/manifest.json: /hash_runs/0/hashes: expected 6 hashes (steps + 1), got 2");
  EXPECT_EQ(manifestError("/version", 7),
            "golden/manifest.json: /version: unsupported version 7 (this build reads 1)");
  EXPECT_EQ(manifestError("/hash_runs/0/precision", "half"),
            "golden/manifest.json: /hash_runs/0/precision: must be float or double, got 'half'");
}

// Replaces the first velocity value of the trace line for `step` with `value`.
void tamperTrace(const fs::path& file, int step, const std::string& value) {
  std::istringstream in(test::readText(file));
  std::vector<std::string> lines;
  const std::string prefix = fmt::format("{{\"step\":{},", step);
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    if (line.rfind(prefix, 0) != 0) continue;
    const std::size_t start = line.find("\"velocity\":[[") + 13;
    lines.back().replace(start, line.find(',', start) - start, value);
    lines.back() =
        test::rehashed(lines, lines.size() - 1);  // a changed value, not a corrupt record
  }
  test::writeLines(file.string(), lines);
}

// The line (1-based) of the first occurrence of `text` in `file_text`.
int lineOf(const std::string& file_text, const std::string& text) {
  const std::size_t at = file_text.find(text);
  return 1 + int(std::count(file_text.begin(), file_text.begin() + std::ptrdiff_t(at), '\n'));
}

// A small golden set, cheap even in an unoptimised build: every scene file, the traces of the
// spring and two-spheres scenes, and their hash runs.
GoldenSet smallSet() {
  GoldenSet set;
  set.scenes = goldenSet().scenes;
  for (const GoldenTrace& trace : goldenSet().traces)
    if (trace.scene == "spring" || trace.scene == "two-spheres") set.traces.push_back(trace);
  for (const HashRun& run : goldenSet().hash_runs)
    if (run.scene == "spring" || run.scene == "two-spheres") set.hash_runs.push_back(run);
  return set;
}

// Every mismatched entry, as "kind name: summary" (and the diff report when there is one).
struct CheckRun {
  GoldenCheckSummary summary;
  std::vector<std::string> mismatches;
  std::string reports;
};
CheckRun check(const fs::path& dir, const GoldenSet& set) {
  CheckRun run;
  run.summary = checkGolden(
      dir, GoldenCheckOptions{},
      [&run](const GoldenEntryResult& entry) {
        if (entry.matched) return;
        run.mismatches.push_back(entry.kind + " " + entry.name + ": " + entry.summary);
        run.reports += entry.report;
      },
      set);
  return run;
}

// One test, because each part needs the update of the one before: update into a temporary
// directory, check it passes, then tamper with a copy and check each entry is named.
TEST(GoldenDirectory, UpdateThenCheckThenTamper) {
  const test::TempDir root;
  const fs::path dir = root.path() / "golden";
  fs::create_directories(dir / "traces");
  // A stale trace (to be swept) and a file outside the generated subdirectories (to be kept).
  test::writeText(dir / "traces" / "retired.rk4.jsonl", "{}\n");
  test::writeText(dir / "NOTES.txt", "kept\n");
  const GoldenSet set = smallSet();
  const GoldenUpdateSummary update = updateGolden(dir, set);

  const int entries = int(set.scenes.size() + set.traces.size() + set.hash_runs.size());
  {
    SCOPED_TRACE("update writes every file and sweeps stale ones");
    EXPECT_EQ(update.traces, int(set.traces.size()));
    EXPECT_EQ(update.hash_runs, int(set.hash_runs.size()));
    for (const std::string& scene : set.scenes)
      EXPECT_EQ(test::readText(dir / "scenes" / (scene + ".json")),
                sceneFileText(*findBuiltinScene(scene)));
    for (const GoldenTrace& trace : set.traces) EXPECT_TRUE(fs::is_regular_file(dir / trace.file));
    EXPECT_FALSE(fs::exists(dir / "traces" / "retired.rk4.jsonl"));
    EXPECT_EQ(update.removed, std::vector<fs::path>{dir / "traces" / "retired.rk4.jsonl"});
    EXPECT_EQ(test::readText(dir / "NOTES.txt"), "kept\n");
    const GoldenSet manifest = readManifest(dir / "manifest.json");
    EXPECT_EQ(manifest.traces.size(), set.traces.size());
    ASSERT_EQ(manifest.hash_runs.size(), set.hash_runs.size());
    for (const HashRun& run : manifest.hash_runs)
      EXPECT_EQ(run.hashes.size(), static_cast<std::size_t>(run.steps) + 1);
  }
  {
    SCOPED_TRACE("the check passes on what update wrote");
    const CheckRun clean = check(dir, set);
    EXPECT_EQ(clean.mismatches, std::vector<std::string>{});
    EXPECT_EQ(clean.summary.checked, entries);
    EXPECT_EQ(clean.summary.mismatched, 0);
  }

  SCOPED_TRACE("a tampered copy fails, naming each tampered entry");
  const fs::path copy = root.path() / "tampered";
  fs::copy(dir, copy, fs::copy_options::recursive);
  // 1. one hash of one run
  GoldenSet manifest = readManifest(copy / "manifest.json");
  for (HashRun& run : manifest.hash_runs)
    if (run.scene == "two-spheres" && run.method == Method::Midpoint &&
        run.precision == Precision::Double)
      run.hashes[300] = "0000000000000000";
  test::writeText(copy / "manifest.json", manifestText(manifest));
  // 2. one velocity value of one trace, 3. a scene parameter, 4. a stray file, 5. a missing trace
  tamperTrace(copy / "traces" / "spring.rk4.jsonl", 1000, "-12.5");
  const std::string scene = test::readText(copy / "scenes" / "free-fall.json");
  const std::string drag = "\"viscous_coef\": 0.5";
  test::writeText(
      copy / "scenes" / "free-fall.json",
      std::string(scene).replace(scene.find(drag), drag.size(), "\"viscous_coef\": 0.25"));
  test::writeText(copy / "scenes" / "extra.json", "{}\n");
  fs::remove(copy / "traces" / "two-spheres.symplectic.jsonl");
  // 6. a truncated trace: that entry's mismatch, not an abort of the whole check
  const std::string explicit_trace = test::readText(copy / "traces" / "spring.explicit.jsonl");
  test::writeText(copy / "traces" / "spring.explicit.jsonl",
                  explicit_trace.substr(0, explicit_trace.size() / 2));
  // 7. a number too large for a double in a trace's header: that entry's mismatch too (it used
  // to abort the whole check)
  std::string midpoint_trace = test::readText(copy / "traces" / "spring.midpoint.jsonl");
  midpoint_trace.replace(midpoint_trace.find("\"dt\":0.001"), 11, "\"dt\":1e400");
  test::writeText(copy / "traces" / "spring.midpoint.jsonl", midpoint_trace);

  CheckRun tampered = check(copy, set);
  const std::string truncated =
      "trace traces/spring.explicit.jsonl: spring explicit float dt=0.001 2000 steps stride 20: "
      "cannot compare: " +
      (copy / "traces" / "spring.explicit.jsonl").string() + ":";
  EXPECT_EQ(std::erase_if(tampered.mismatches,
                          [&](const std::string& line) { return line.rfind(truncated, 0) == 0; }),
            1u);
  const std::string huge_dt =
      "trace traces/spring.midpoint.jsonl: spring midpoint float dt=0.001 2000 steps stride 20: "
      "cannot compare: " +
      (copy / "traces" / "spring.midpoint.jsonl").string() + ":1: header: ";
  EXPECT_EQ(std::erase_if(tampered.mismatches,
                          [&](const std::string& line) {
                            return line.rfind(huge_dt, 0) == 0 &&
                                   line.find("not valid JSON") != std::string::npos;
                          }),
            1u);
  const std::vector<std::string> expected = {
      fmt::format("scene scenes/free-fall.json: differs from the built-in scene at line {}: "
                  "golden '  \"viscous_coef\": 0.25,', now '  \"viscous_coef\": 0.5,'",
                  lineOf(scene, drag)),
      "trace traces/spring.rk4.jsonl: spring rk4 float dt=0.001 2000 steps stride 20",
      "trace traces/two-spheres.symplectic.jsonl: golden trace file missing (two-spheres "
      "symplectic float dt=0.001 500 steps stride 5)",
      "hashes two-spheres midpoint double dt=0.001 1000 steps: first differs at step 300 of 1000: "
      "golden 0000000000000000, now " +
          hashToHex(computeHashes(*findBuiltinScene("two-spheres"), Method::Midpoint,
                                  Precision::Double, 1e-3, 300)[300]),
      "file scenes/extra.json: stray file: not produced by the golden set (run --update)"};
  EXPECT_EQ(tampered.mismatches, expected);
  EXPECT_EQ(tampered.summary.checked, entries + 1);
  EXPECT_EQ(tampered.summary.mismatched, 7);
  // The diff report of the tampered trace names the step and shows the value.
  EXPECT_NE(tampered.reports.find("step 1000"), std::string::npos) << tampered.reports;
  EXPECT_NE(tampered.reports.find("-12.5"), std::string::npos) << tampered.reports;
}

// A golden trace stored as concatenated gzip members (as `zcat` reads them) checks like the plain
// one; trailing zero bytes after it are that entry's mismatch. Both used to spin forever.
TEST(GoldenDirectory, MultiMemberGzipGoldenTraceChecks) {
  const test::TempDir root;
  const fs::path dir = root.path() / "golden";
  GoldenSet set;
  for (const GoldenTrace& trace : goldenSet().traces)
    if (trace.scene == "spring" && trace.settings.method == Method::Explicit)
      set.traces.push_back(trace);
  ASSERT_EQ(set.traces.size(), 1u);
  updateGolden(dir, set);
  const fs::path file = dir / set.traces[0].file;
  const std::string text = test::readText(file);
  const std::size_t half = text.find('\n', text.size() / 2) + 1;
  const std::string multi = test::gzipMember(text.substr(0, half)) + test::gzipMember("") +
                            test::gzipMember(text.substr(half));
  test::writeText(file, multi);
  EXPECT_EQ(check(dir, set).mismatches, std::vector<std::string>{});

  test::writeText(file, multi + std::string(4, '\0'));
  const CheckRun padded = check(dir, set);
  ASSERT_EQ(padded.mismatches.size(), 1u);
  EXPECT_NE(
      padded.mismatches[0].find("trailing bytes after the gzip data (not another gzip member)"),
      std::string::npos)
      << padded.mismatches[0];
}

// --update never follows a link when it writes or deletes: a linked scenes/ is refused (and the
// files where it points are kept: they used to be deleted as stale); a linked trace file is
// replaced by the new trace, its target untouched (it used to receive the trace); a stale link
// is deleted, not its target. A 0444 file stays 0444.
TEST(GoldenDirectory, UpdateNeverFollowsALinkAndKeepsModes) {
  const test::TempDir root;
  const fs::path dir = root.path() / "golden";
  const fs::path outside = root.path() / "outside";
  fs::create_directories(dir);
  fs::create_directories(outside);
  test::writeText(outside / "victim.jsonl", "victim\n");
  test::writeText(outside / "keep.json", "keep\n");
  GoldenSet set;
  set.scenes = {"spring"};
  for (const GoldenTrace& trace : goldenSet().traces)
    if (trace.scene == "spring" && trace.settings.method == Method::Explicit)
      set.traces.push_back(trace);
  ASSERT_EQ(set.traces.size(), 1u);

  fs::create_directory_symlink("../outside", dir / "scenes");
  try {
    updateGolden(dir, set);
    ADD_FAILURE() << "a linked scenes/ was written through";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              (dir / "scenes").string() +
                  ": a symbolic link, not a directory (golden never writes through one)");
  }
  EXPECT_EQ(test::readText(outside / "keep.json"), "keep\n");
  EXPECT_EQ(test::readText(outside / "victim.jsonl"), "victim\n");
  fs::remove(dir / "scenes");

  fs::create_directories(dir / "traces");
  fs::create_symlink("../../outside/victim.jsonl", dir / set.traces[0].file);
  fs::create_symlink("../../outside/keep.json", dir / "traces" / "stale.jsonl");
  const GoldenUpdateSummary summary = updateGolden(dir, set);
  EXPECT_EQ(test::readText(outside / "victim.jsonl"), "victim\n");
  EXPECT_EQ(test::readText(outside / "keep.json"), "keep\n");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / set.traces[0].file)));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "traces" / "stale.jsonl")));
  EXPECT_EQ(summary.removed, std::vector<fs::path>{dir / "traces" / "stale.jsonl"});
  EXPECT_EQ(check(dir, set).mismatches, std::vector<std::string>{});

  const fs::path scene = dir / "scenes" / "spring.json";
  fs::permissions(scene, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  updateGolden(dir, set);
  EXPECT_EQ(fs::status(scene).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
}

// A traces/ that is a link loop or a link at all is one line, from the check and the update
// (a loop used to reach "unexpected error: filesystem error").
TEST(GoldenDirectory, LinkedOrLoopingTracesDirectoryIsOneLine) {
  const test::TempDir root;
  const fs::path dir = root.path() / "golden";
  GoldenSet set;
  set.scenes = {"spring"};
  updateGolden(dir, set);
  fs::remove(dir / "traces");
  fs::create_directory_symlink("traces", dir / "traces");  // traces -> traces: a loop
  for (int update = 0; update < 2; ++update) {
    std::string message;
    try {
      if (update)
        updateGolden(dir, set);
      else
        check(dir, set);
    } catch (const InputError& error) {
      message = error.what();
    }
    EXPECT_EQ(message, (dir / "traces").string() +
                           ": a symbolic link, not a directory (golden never writes through one)");
  }
}

}  // namespace
}  // namespace clothref
