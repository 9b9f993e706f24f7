// golden.cpp: the golden set definition, the manifest reader, `clothref golden --update` into a
// temporary directory (stale files swept, others kept), the check passing on what update wrote,
// and a tampered copy failing with exactly the tampered entries named.
#include "clothref/golden.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "clothref/error.h"
#include "clothref/hash.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

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
  EXPECT_TRUE(hasRun(set, "course2022", Method::Explicit, Precision::Float, 10000));
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
  std::istringstream in(readText(file));
  std::string out, line;
  const std::string prefix = fmt::format("{{\"step\":{},", step);
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) {
      const std::size_t start = line.find("\"velocity\":[[") + 13;
      line.replace(start, line.find(',', start) - start, value);
    }
    out += line + '\n';
  }
  writeText(file, out);
}

// The line (1-based) of the first occurrence of `text` in `file_text`.
int lineOf(const std::string& file_text, const std::string& text) {
  const std::size_t at = file_text.find(text);
  return 1 + int(std::count(file_text.begin(), file_text.begin() + std::ptrdiff_t(at), '\n'));
}

// One test, because each part needs the ~4 s `--update` of the one before: update into a
// temporary directory, check it passes, then tamper with a copy and check each entry is named.
TEST(GoldenDirectory, UpdateThenCheckThenTamper) {
  const fs::path root =
      fs::temp_directory_path() / fmt::format("clothref-golden-test-{}", ::getpid());
  const fs::path dir = root / "golden";
  fs::remove_all(root);
  fs::create_directories(dir / "traces");
  // A stale trace (to be swept) and a file outside the generated subdirectories (to be kept).
  writeText(dir / "traces" / "retired.rk4.jsonl", "{}\n");
  writeText(dir / "NOTES.txt", "kept\n");
  const test::CommandResult update = test::runCli("golden --update --golden " + dir.string());
  ASSERT_EQ(update.exit_code, 0) << update.output;

  const GoldenSet& set = goldenSet();
  const int entries = int(set.scenes.size() + set.traces.size() + set.hash_runs.size());
  {
    SCOPED_TRACE("update writes every file and sweeps stale ones");
    for (const std::string& scene : set.scenes)
      EXPECT_EQ(readText(dir / "scenes" / (scene + ".json")),
                sceneFileText(*findBuiltinScene(scene)));
    for (const GoldenTrace& trace : set.traces) EXPECT_TRUE(fs::is_regular_file(dir / trace.file));
    EXPECT_FALSE(fs::exists(dir / "traces" / "retired.rk4.jsonl"));
    EXPECT_NE(update.output.find("removed stale"), std::string::npos) << update.output;
    EXPECT_EQ(readText(dir / "NOTES.txt"), "kept\n");
    // No temporary files left behind by the atomic writes.
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    const GoldenSet manifest = readManifest(dir / "manifest.json");
    EXPECT_EQ(manifest.traces.size(), set.traces.size());
    EXPECT_EQ(manifest.hash_runs.size(), set.hash_runs.size());
  }
  {
    SCOPED_TRACE("the check passes on what update wrote");
    std::vector<std::string> mismatches;
    const GoldenCheckSummary summary =
        checkGolden(dir, GoldenCheckOptions{}, [&](const GoldenEntryResult& entry) {
          if (!entry.matched) mismatches.push_back(entry.name + ": " + entry.summary);
        });
    EXPECT_EQ(mismatches, std::vector<std::string>{});
    EXPECT_EQ(summary.checked, entries);
    EXPECT_EQ(summary.mismatched, 0);
  }

  SCOPED_TRACE("a tampered copy fails, naming each tampered entry");
  const fs::path copy = root / "tampered";
  fs::copy(dir, copy, fs::copy_options::recursive);
  // 1. one hash of one run
  GoldenSet manifest = readManifest(copy / "manifest.json");
  for (HashRun& run : manifest.hash_runs)
    if (run.scene == "two-spheres" && run.method == Method::Midpoint &&
        run.precision == Precision::Double)
      run.hashes[300] = "0000000000000000";
  writeText(copy / "manifest.json", manifestText(manifest));
  // 2. one velocity value of one trace, 3. a scene parameter, 4. a stray file, 5. a missing trace
  tamperTrace(copy / "traces" / "spring.rk4.jsonl", 1000, "-12.5");
  const std::string scene = readText(copy / "scenes" / "free-fall.json");
  const std::string drag = "\"viscous_coef\": 0.5";
  writeText(copy / "scenes" / "free-fall.json",
            std::string(scene).replace(scene.find(drag), drag.size(), "\"viscous_coef\": 0.25"));
  writeText(copy / "scenes" / "extra.json", "{}\n");
  fs::remove(copy / "traces" / "small-cloth.symplectic.jsonl");

  const test::CommandResult check = test::runCli("golden --golden " + copy.string());
  EXPECT_EQ(check.exit_code, 1) << check.output;
  const std::string& out = check.output;
  auto has = [&out](const std::string& text) { return out.find(text) != std::string::npos; };
  EXPECT_TRUE(
      has("MISMATCH hashes two-spheres midpoint double dt=0.001 1000 steps: first differs "
          "at step 300 of 1000: golden 0000000000000000"))
      << out;
  EXPECT_TRUE(has("MISMATCH trace  traces/spring.rk4.jsonl:")) << out;
  EXPECT_TRUE(has("step 1000")) << "the diff report names the tampered step\n" << out;
  EXPECT_TRUE(has("-12.5")) << "the diff report shows the tampered value\n" << out;
  EXPECT_TRUE(
      has(fmt::format("MISMATCH scene  scenes/free-fall.json: differs from the built-in "
                      "scene at line {}: golden '  \"viscous_coef\": 0.25,', now '  "
                      "\"viscous_coef\": 0.5,'",
                      lineOf(scene, drag))))
      << out;
  EXPECT_TRUE(has("MISMATCH file   scenes/extra.json: stray file")) << out;
  EXPECT_TRUE(has("MISMATCH trace  traces/small-cloth.symplectic.jsonl: golden trace file missing"))
      << out;
  // Every entry plus the stray file; only the mismatches are printed without --verbose.
  EXPECT_TRUE(has(
      fmt::format("clothref golden: {} of {} entries match, 5 mismatch", entries - 4, entries + 1)))
      << out;
  EXPECT_FALSE(has("ok ")) << out;
  fs::remove_all(root);
}

TEST(GoldenCli, BadInputExitsTwo) {
  const fs::path root =
      fs::temp_directory_path() / fmt::format("clothref-golden-bad-{}", ::getpid());
  fs::remove_all(root);
  const test::CommandResult missing = test::runCli("golden --golden " + (root / "none").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("golden directory not found"), std::string::npos) << missing.output;

  fs::create_directories(root);
  writeText(root / "manifest.json", "{\"format\": \"clothref-golden\", \"version\": 1,");
  const test::CommandResult malformed = test::runCli("golden --golden " + root.string());
  EXPECT_EQ(malformed.exit_code, 2);
  EXPECT_NE(malformed.output.find("manifest.json: not valid JSON"), std::string::npos)
      << malformed.output;
  fs::remove_all(root);
}

}  // namespace
}  // namespace clothref
