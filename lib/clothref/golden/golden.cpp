#include "clothref/golden/golden.h"
#include "clothref/scene/make_world.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "clothref/core/world.h"
#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/json_input.h"
#include "clothref/record/world_views.h"
#include "clothref/trace/build_info.h"

namespace clothref {

namespace {

// Horizon and stride of the stored float traces, per scene. The course scenes (626-629
// particles, ~39 kB per recorded line) are strided hard; the small ones keep ~100 lines.
struct TracePlan {
  const char* scene;
  std::int64_t steps;
  std::int64_t stride;
};
constexpr TracePlan kTracePlans[] = {
    {"course2022", 5000, 500},  // spheres reach the cloth at ~0.32 s (3200 steps), 0.5 s shown
    {"course2024", 3000, 500},  // the cloth drapes over the sphere from step 0
    {"spring", 2000, 20},       // ~3 periods (2 pi / 10 s each)
    {"spring-undamped", 2000, 20},
    {"free-fall", 2000, 20},          // apex at ~0.5 s, back through y = 10 m at ~1 s
    {"two-spheres", 500, 5},          // contact at ~0.25 s
    {"small-cloth", 4000, 200},       // the sphere reaches the cloth at ~0.2 s (2000 steps)
    {"two-spheres-oblique", 500, 5},  // off-axis contact at ~0.29 s
};

// Steps of the hash-only runs: every step hashed, so only the hash list is stored.
struct HashPlan {
  const char* scene;
  std::int64_t steps;
  bool double_too;  // also in double (the small scenes)
};
constexpr HashPlan kHashPlans[] = {
    {"course2022", 1000, false},         {"course2024", 1000, false}, {"spring", 1000, true},
    {"spring-undamped", 1000, true},     {"free-fall", 1000, true},   {"two-spheres", 1000, true},
    {"small-cloth", 3000, true},  // past first contact at ~2000 steps
    {"two-spheres-oblique", 1000, true},
};
// course2022 for 1 s simulated with every method: contact, rebound, and the spheres' first
// sphere-sphere contact (step 8142), where the restitution e = 0.8 decides last bits
constexpr std::int64_t kLongCourseSteps = 10000;

const Scene& builtin(const std::string& name) {
  const Scene* scene = findBuiltinScene(name);
  if (!scene) throw InputError("golden set: unknown built-in scene '" + name + "'");
  return *scene;
}

std::string traceFile(const std::string& scene, Method method) {
  return fmt::format("traces/{}.{}.jsonl", scene, methodName(method));
}

GoldenSet defineGoldenSet() {
  GoldenSet set;
  for (const Scene& scene : builtinScenes()) set.scenes.push_back(scene.name);
  for (const TracePlan& plan : kTracePlans) {
    for (Method method : kAllMethods) {
      TraceSettings settings;
      settings.method = method;
      settings.precision = Precision::Float;
      settings.dt = builtin(plan.scene).dt;
      settings.steps = plan.steps;
      settings.stride = plan.stride;
      set.traces.push_back(GoldenTrace{plan.scene, settings, traceFile(plan.scene, method)});
    }
  }
  auto add_run = [&set](const std::string& scene, Method method, Precision precision,
                        std::int64_t steps) {
    set.hash_runs.push_back(HashRun{scene, method, precision, builtin(scene).dt, steps, {}});
  };
  for (const HashPlan& plan : kHashPlans) {
    for (Method method : kAllMethods) add_run(plan.scene, method, Precision::Float, plan.steps);
    if (!plan.double_too) continue;
    for (Method method : kAllMethods) add_run(plan.scene, method, Precision::Double, plan.steps);
  }
  for (Method method : kAllMethods)
    add_run("course2022", method, Precision::Float, kLongCourseSteps);
  return set;
}

template <typename T>
std::vector<std::uint64_t> hashesOf(const Scene& scene, Method method, double dt,
                                    std::int64_t steps) {
  World<T> world = makeWorld<T>(scene, method, dt);
  std::vector<std::uint64_t> hashes;
  hashes.reserve(static_cast<std::size_t>(steps) + 1);
  hashes.push_back(stateHash(world));
  for (std::int64_t s = 0; s < steps; ++s) {
    step(world);
    hashes.push_back(stateHash(world));
  }
  return hashes;
}

// Field access with errors that name the manifest file and the JSON pointer.
class ManifestReader {
 public:
  explicit ManifestReader(std::string file_name) : file_name_(std::move(file_name)) {}

  [[noreturn]] void fail(const std::string& pointer, const std::string& problem) const {
    throw InputError(
        fmt::format("{}: {}: {}", file_name_, pointer.empty() ? "/" : pointer, problem));
  }

  const nlohmann::json& field(const nlohmann::json& object, const std::string& pointer,
                              const char* key) const {
    if (!object.is_object()) fail(pointer, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) fail(pointer + "/" + key, "missing");
    return *it;
  }

  const nlohmann::json& array(const nlohmann::json& object, const std::string& pointer,
                              const char* key) const {
    const nlohmann::json& value = field(object, pointer, key);
    if (!value.is_array()) fail(pointer + "/" + key, "expected an array");
    return value;
  }

  std::string string(const nlohmann::json& object, const std::string& pointer,
                     const char* key) const {
    const nlohmann::json& value = field(object, pointer, key);
    if (!value.is_string()) fail(pointer + "/" + key, "expected a string");
    return value.get<std::string>();
  }

  std::int64_t integer(const nlohmann::json& object, const std::string& pointer, const char* key,
                       std::int64_t minimum) const {
    const nlohmann::json& value = field(object, pointer, key);
    if (!value.is_number_integer()) fail(pointer + "/" + key, "expected an integer");
    const std::int64_t n = value.get<std::int64_t>();
    if (n < minimum) fail(pointer + "/" + key, fmt::format("must be >= {} (got {})", minimum, n));
    return n;
  }

  double positive(const nlohmann::json& object, const std::string& pointer, const char* key) const {
    const nlohmann::json& value = field(object, pointer, key);
    if (!value.is_number()) fail(pointer + "/" + key, "expected a number");
    const double x = value.get<double>();
    if (!(x > 0)) fail(pointer + "/" + key, fmt::format("must be > 0 (got {})", x));
    return x;
  }

  Method method(const nlohmann::json& object, const std::string& pointer) const {
    const std::string name = string(object, pointer, "integrator");
    const auto method = parseMethod(name);
    if (!method) fail(pointer + "/integrator", "unknown method '" + name + "'");
    return *method;
  }

  Precision precision(const nlohmann::json& object, const std::string& pointer) const {
    const std::string name = string(object, pointer, "precision");
    const auto precision = parseEnum(kPrecisionNames, name);
    if (!precision) fail(pointer + "/precision", "must be float or double, got '" + name + "'");
    return *precision;
  }

 private:
  std::string file_name_;
};

bool isHexHash(const std::string& text) {
  return text.size() == 16 && std::all_of(text.begin(), text.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

bool sameTrace(const GoldenTrace& a, const GoldenTrace& b) {
  return a.scene == b.scene && a.file == b.file && a.settings == b.settings;
}

bool containsTrace(const std::vector<GoldenTrace>& traces, const GoldenTrace& trace) {
  return std::any_of(traces.begin(), traces.end(),
                     [&trace](const GoldenTrace& other) { return sameTrace(trace, other); });
}

std::string settingsText(const GoldenTrace& trace) {
  return fmt::format("{} {} {} dt={} {} steps stride {}", trace.scene,
                     methodName(trace.settings.method), precisionName(trace.settings.precision),
                     trace.settings.dt, trace.settings.steps, trace.settings.stride);
}

// Re-runs a golden trace and compares it with the stored one through the diff library.
GoldenEntryResult checkTrace(const std::filesystem::path& dir, const GoldenTrace& trace,
                             const DiffOptions& options) {
  GoldenEntryResult result{"trace", trace.file, false, "", ""};
  const std::filesystem::path golden_file = dir / trace.file;
  if (!std::filesystem::is_regular_file(golden_file)) {
    result.summary = "golden trace file missing (" + settingsText(trace) + ")";
    return result;
  }
  // the fresh trace is compared in memory: nothing is written
  std::stringstream fresh;
  writeTrace(builtin(trace.scene), trace.settings, fresh);
  result.summary = settingsText(trace);
  // A golden trace the reader rejects (truncated, edited) is this entry's mismatch, not bad
  // input to the whole check: the other entries are still worth checking.
  try {
    std::ifstream golden(golden_file, std::ios::binary);
    if (!golden) throw InputError(golden_file.string() + ": cannot open the trace file");
    const DiffReport report =
        diffTraces(golden, golden_file.string(), fresh, "(this build)", options);
    result.matched = report.verdict != Verdict::Differ;
    if (!result.matched) result.report = formatReport(report);
  } catch (const InputError& error) {
    result.summary += std::string(": cannot compare: ") + error.what();
  }
  return result;
}

GoldenEntryResult checkHashRun(const HashRun& run) {
  GoldenEntryResult result{"hashes", run.name(), false, "", ""};
  const std::vector<std::uint64_t> fresh =
      computeHashes(builtin(run.scene), run.method, run.precision, run.dt, run.steps);
  for (std::size_t s = 0; s < fresh.size(); ++s) {
    const std::string hash = hashToHex(fresh[s]);
    if (hash == run.hashes[s]) continue;
    result.summary = fmt::format("first differs at step {} of {}: golden {}, now {}", s, run.steps,
                                 run.hashes[s], hash);
    return result;
  }
  result.matched = true;
  result.summary = fmt::format("{} step hashes equal", fresh.size());
  return result;
}

GoldenEntryResult checkSceneFile(const std::filesystem::path& dir, const std::string& name) {
  const std::string file = "scenes/" + name + ".json";
  GoldenEntryResult result{"scene", file, false, "", ""};
  if (!std::filesystem::is_regular_file(dir / file)) {
    result.summary = "golden scene file missing";
    return result;
  }
  const std::string stored = readFile(dir / file, "golden scene file");
  const std::string expected = sceneFileText(builtin(name));
  if (stored == expected) {
    result.matched = true;
    result.summary = "equal to the built-in scene, byte for byte";
    return result;
  }
  // The first differing line tells the reviewer which parameter changed.
  std::istringstream a(stored), b(expected);
  std::string line_a, line_b;
  int line = 1;
  for (;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, line_a));
    const bool more_b = static_cast<bool>(std::getline(b, line_b));
    if (!more_a || !more_b || line_a != line_b) {
      result.summary =
          fmt::format("differs from the built-in scene at line {}: golden '{}', now '{}'", line,
                      more_a ? line_a : "<end>", more_b ? line_b : "<end>");
      break;
    }
  }
  return result;
}

// The regular files and links directly in DIR/sub, as '/'-separated names relative to DIR,
// sorted; none when DIR/sub does not exist. A DIR/sub that is a link (or a loop), or that cannot be
// read, is refused with one line (OpenDirectory::sub).
std::vector<std::string> filesIn(const OpenDirectory& dir, const std::string& sub) {
  std::vector<std::string> files;
  if (!dir.has(sub)) return files;
  for (const std::string& name : dir.sub(sub, false).files()) files.push_back(sub + "/" + name);
  return files;
}

// Every file path the golden set produces, relative to the golden directory.
std::set<std::string> expectedFiles(const GoldenSet& set) {
  std::set<std::string> files;
  for (const std::string& scene : set.scenes) files.insert("scenes/" + scene + ".json");
  for (const GoldenTrace& trace : set.traces) files.insert(trace.file);
  return files;
}

}  // namespace

std::string HashRun::name() const {
  return fmt::format("{} {} {} dt={} {} steps", scene, methodName(method), precisionName(precision),
                     dt, steps);
}

bool HashRun::sameRun(const HashRun& other) const {
  return scene == other.scene && method == other.method && precision == other.precision &&
         dt == other.dt && steps == other.steps;
}

const GoldenSet& goldenSet() {
  static const GoldenSet set = defineGoldenSet();
  return set;
}

std::vector<std::uint64_t> computeHashes(const Scene& scene, Method method, Precision precision,
                                         double dt, std::int64_t steps) {
  return withPrecision(precision,
                       [&]<typename T>() { return hashesOf<T>(scene, method, dt, steps); });
}

std::string sceneFileText(const Scene& scene) { return sceneToJson(scene).dump(2) + "\n"; }

std::string manifestText(const GoldenSet& manifest) {
  nlohmann::ordered_json json;
  json["format"] = "clothref-golden";
  json["version"] = kGoldenVersion;
  json["note"] = "generated by `clothref golden --update`; do not edit (docs/regression.md)";
  // Which toolchain made the files: the check is bit-exact on this one (docs/determinism.md).
  json["generated_by"] = {{"clothref", build_info::kVersion},
                          {"compiler", build_info::kCompiler},
                          {"build_type", build_info::kBuildType},
                          {"system", build_info::kSystem}};
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  for (const std::string& scene : manifest.scenes)
    scenes.push_back({{"name", scene}, {"file", "scenes/" + scene + ".json"}});
  json["scenes"] = scenes;
  nlohmann::ordered_json traces = nlohmann::ordered_json::array();
  for (const GoldenTrace& trace : manifest.traces) {
    traces.push_back({{"file", trace.file},
                      {"scene", trace.scene},
                      {"integrator", methodName(trace.settings.method)},
                      {"precision", precisionName(trace.settings.precision)},
                      {"dt", trace.settings.dt},
                      {"steps", trace.settings.steps},
                      {"stride", trace.settings.stride}});
  }
  json["traces"] = traces;
  json["hash_runs"] = nlohmann::ordered_json::array();
  std::string text = json.dump(2);

  // The hash lists by hand, four per line: two fifths of the size of one per line, and a changed
  // step still shows as one changed line in a git diff.
  constexpr std::size_t kHashesPerLine = 4;
  text.erase(text.rfind("[]"));
  text += "[";
  for (std::size_t r = 0; r < manifest.hash_runs.size(); ++r) {
    const HashRun& run = manifest.hash_runs[r];
    text += r ? ",\n" : "\n";
    text += fmt::format(
        "    {{\n      \"scene\": {},\n      \"integrator\": \"{}\",\n      \"precision\": "
        "\"{}\",\n      \"dt\": {},\n      \"steps\": {},\n      \"hashes\": [",
        nlohmann::json(run.scene).dump(), methodName(run.method), precisionName(run.precision),
        nlohmann::json(run.dt).dump(), run.steps);
    for (std::size_t s = 0; s < run.hashes.size(); ++s) {
      text += s == 0 ? "\n        " : s % kHashesPerLine == 0 ? ",\n        " : ", ";
      text += "\"" + run.hashes[s] + "\"";
    }
    text += "\n      ]\n    }";
  }
  text += "\n  ]\n}\n";
  return text;
}

GoldenSet manifestFromJson(const nlohmann::json& document, const std::string& file_name) {
  const ManifestReader reader(file_name);
  if (!document.is_object()) reader.fail("", "expected an object");
  if (reader.string(document, "", "format") != "clothref-golden")
    reader.fail("/format", "expected \"clothref-golden\"");
  const std::int64_t version = reader.integer(document, "", "version", 1);
  if (version != kGoldenVersion)
    reader.fail("/version", fmt::format("unsupported version {} (this build reads {})", version,
                                        kGoldenVersion));
  GoldenSet manifest;
  const nlohmann::json& scenes = reader.array(document, "", "scenes");
  for (std::size_t i = 0; i < scenes.size(); ++i)
    manifest.scenes.push_back(reader.string(scenes[i], fmt::format("/scenes/{}", i), "name"));

  const nlohmann::json& traces = reader.array(document, "", "traces");
  for (std::size_t i = 0; i < traces.size(); ++i) {
    const std::string pointer = fmt::format("/traces/{}", i);
    GoldenTrace trace;
    trace.file = reader.string(traces[i], pointer, "file");
    // Keep every golden file inside the golden directory.
    if (trace.file.rfind("traces/", 0) != 0 || trace.file.find("..") != std::string::npos)
      reader.fail(pointer + "/file", "must be a file under traces/ (got '" + trace.file + "')");
    trace.scene = reader.string(traces[i], pointer, "scene");
    trace.settings.method = reader.method(traces[i], pointer);
    trace.settings.precision = reader.precision(traces[i], pointer);
    trace.settings.dt = reader.positive(traces[i], pointer, "dt");
    trace.settings.steps = reader.integer(traces[i], pointer, "steps", 0);
    trace.settings.stride = reader.integer(traces[i], pointer, "stride", 1);
    manifest.traces.push_back(trace);
  }

  const nlohmann::json& runs = reader.array(document, "", "hash_runs");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string pointer = fmt::format("/hash_runs/{}", i);
    HashRun run;
    run.scene = reader.string(runs[i], pointer, "scene");
    run.method = reader.method(runs[i], pointer);
    run.precision = reader.precision(runs[i], pointer);
    run.dt = reader.positive(runs[i], pointer, "dt");
    run.steps = reader.integer(runs[i], pointer, "steps", 0);
    const nlohmann::json& hashes = reader.array(runs[i], pointer, "hashes");
    if (hashes.size() != static_cast<std::size_t>(run.steps) + 1)
      reader.fail(pointer + "/hashes", fmt::format("expected {} hashes (steps + 1), got {}",
                                                   run.steps + 1, hashes.size()));
    for (std::size_t s = 0; s < hashes.size(); ++s) {
      if (!hashes[s].is_string() || !isHexHash(hashes[s].get<std::string>()))
        reader.fail(fmt::format("{}/hashes/{}", pointer, s), "expected 16 lowercase hex digits");
      run.hashes.push_back(hashes[s].get<std::string>());
    }
    manifest.hash_runs.push_back(std::move(run));
  }
  return manifest;
}

GoldenSet readManifest(const std::filesystem::path& file) {
  return manifestFromJson(readJsonFile(file.string(), "golden manifest"), file.string());
}

namespace {

// Writes the set through descriptors of DIR, DIR/scenes and DIR/traces, never following a link
// (io/files.h OpenDirectory): a linked scenes/ or traces/ is refused, a linked file is replaced,
// not written through, and a stale link is deleted, not its target.
GoldenUpdateSummary writeGoldenSet(const std::filesystem::path& path, const GoldenSet& set) {
  GoldenUpdateSummary summary;
  const OpenDirectory dir(path, true);
  const bool new_set = !dir.has("manifest.json");
  const OpenDirectory scenes = dir.sub("scenes", true);
  const OpenDirectory traces = dir.sub("traces", true);
  std::vector<std::pair<const OpenDirectory*, std::string>> written;
  auto write = [&written](const OpenDirectory& where, const std::string& name,
                          const std::string& text) {
    where.replaceFile(name, text);
    written.emplace_back(&where, name);
  };
  try {
    for (const std::string& name : set.scenes) {
      write(scenes, name + ".json", sceneFileText(builtin(name)));
      ++summary.scenes;
    }
    for (const GoldenTrace& trace : set.traces) {
      if (trace.file.rfind("traces/", 0) != 0)
        throw InputError("golden set: trace file '" + trace.file + "' is not under traces/");
      std::ostringstream text;
      writeTrace(builtin(trace.scene), trace.settings, text);
      write(traces, trace.file.substr(7), text.str());
      ++summary.traces;
    }
    GoldenSet manifest = set;
    for (HashRun& run : manifest.hash_runs) {
      for (std::uint64_t hash :
           computeHashes(builtin(run.scene), run.method, run.precision, run.dt, run.steps))
        run.hashes.push_back(hashToHex(hash));
      ++summary.hash_runs;
    }
    // The manifest last: an interrupted update of a set leaves the old manifest, which the check
    // then flags.
    dir.replaceFile("manifest.json", manifestText(manifest));
  } catch (...) {
    // a new set (--create) that could not be finished (a full disk) leaves no files without a
    // manifest
    if (new_set)
      for (const auto& [where, name] : written) where->remove(name);
    throw;
  }

  // Only the two generated subdirectories are swept, so nothing else in DIR is ever deleted.
  const std::set<std::string> expected = expectedFiles(set);
  for (const OpenDirectory* sub : {&scenes, &traces}) {
    for (const std::string& name : sub->files()) {
      const std::string file = sub->path().filename().string() + "/" + name;
      if (expected.count(file)) continue;
      sub->remove(name);
      summary.removed.push_back(path / file);
    }
  }
  return summary;
}

}  // namespace

GoldenUpdateSummary updateGolden(const std::filesystem::path& dir, const GoldenSet& set) {
  try {
    return writeGoldenSet(dir, set);
  } catch (const std::filesystem::filesystem_error& error) {
    // a read-only directory, or a path under a regular file: bad input, one line
    throw InputError(fmt::format("{}: cannot update the golden set: {}",
                                 error.path1().empty() ? dir.string() : error.path1().string(),
                                 error.code().message()));
  }
}

GoldenCheckSummary checkGolden(const std::filesystem::path& dir, const GoldenCheckOptions& options,
                               FunctionRef<void(const GoldenEntryResult&)> on_entry,
                               const GoldenSet& defined) {
  if (!std::filesystem::is_directory(dir))
    throw InputError(dir.string() +
                     ": golden directory not found (generate it with clothref "
                     "golden --update)");
  const GoldenSet manifest = readManifest(dir / "manifest.json");
  // listed first: a linked, looping or unreadable scenes/ or traces/ is refused before any work
  const OpenDirectory root(dir, false);
  std::vector<std::string> present = filesIn(root, "scenes");
  for (std::string& file : filesIn(root, "traces")) present.push_back(std::move(file));
  GoldenCheckSummary summary;
  auto report = [&summary, &on_entry](const GoldenEntryResult& result) {
    ++summary.checked;
    if (!result.matched) ++summary.mismatched;
    on_entry(result);
  };
  auto not_defined = [&report](const char* kind, const std::string& name) {
    report({kind, name, false,
            "in the manifest but not in the golden set this code defines (run --update)", ""});
  };
  auto not_stored = [&report](const char* kind, const std::string& name) {
    report({kind, name, false,
            "in the golden set this code defines but not in the manifest (run --update)", ""});
  };

  for (const std::string& name : defined.scenes) report(checkSceneFile(dir, name));
  for (const std::string& name : manifest.scenes)
    if (std::find(defined.scenes.begin(), defined.scenes.end(), name) == defined.scenes.end())
      not_defined("scene", "scenes/" + name + ".json");

  for (const GoldenTrace& trace : manifest.traces) {
    if (!containsTrace(defined.traces, trace))
      not_defined("trace", trace.file + " (" + settingsText(trace) + ")");
    else
      report(checkTrace(dir, trace, options.diff));
  }
  for (const GoldenTrace& trace : defined.traces)
    if (!containsTrace(manifest.traces, trace))
      not_stored("trace", trace.file + " (" + settingsText(trace) + ")");

  if (options.check_hashes) {
    for (const HashRun& run : manifest.hash_runs) {
      const bool is_defined =
          std::any_of(defined.hash_runs.begin(), defined.hash_runs.end(),
                      [&run](const HashRun& other) { return run.sameRun(other); });
      if (is_defined)
        report(checkHashRun(run));
      else
        not_defined("hashes", run.name());
    }
    for (const HashRun& run : defined.hash_runs) {
      const bool is_stored =
          std::any_of(manifest.hash_runs.begin(), manifest.hash_runs.end(),
                      [&run](const HashRun& other) { return run.sameRun(other); });
      if (!is_stored) not_stored("hashes", run.name());
    }
  }

  // Files the golden set does not produce (left by hand or by an older set) are mismatches too.
  const std::set<std::string> expected = expectedFiles(defined);
  for (const std::string& file : present)
    if (!expected.count(file))
      report(
          {"file", file, false, "stray file: not produced by the golden set (run --update)", ""});
  return summary;
}

}  // namespace clothref
