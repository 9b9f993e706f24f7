// Determinism (docs/determinism.md): the per-step state hashes recomputed here, in this test
// binary, equal the ones `clothref golden --update` stored in golden/manifest.json; and worlds
// stepped interleaved in one process hash exactly as each does alone (they share no state).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "clothref/core/world.h"
#include "clothref/golden/golden.h"
#include "clothref/record/world_views.h"
#include "clothref/scene/make_world.h"

namespace clothref {
namespace {

const GoldenSet& manifest() {
  static const GoldenSet stored = readManifest(CLOTHREF_SOURCE_DIR "/golden/manifest.json");
  return stored;
}

// The stored run with these settings, or nullptr.
const HashRun* storedRun(const std::string& scene, Method method, Precision precision,
                         std::int64_t steps) {
  for (const HashRun& run : manifest().hash_runs)
    if (run.scene == scene && run.method == method && run.precision == precision &&
        run.steps == steps && run.dt == findBuiltinScene(scene)->dt)
      return &run;
  return nullptr;
}

// Steps a world of its own, hashing after every step (step 0 first), independently of golden.cpp.
template <typename T>
std::vector<std::string> hashesAlone(const HashRun& run) {
  World<T> world = makeWorld<T>(*findBuiltinScene(run.scene), run.method, run.dt);
  std::vector<std::string> hashes{hashToHex(stateHash(world))};
  for (std::int64_t s = 0; s < run.steps; ++s) {
    step(world);
    hashes.push_back(hashToHex(stateHash(world)));
  }
  return hashes;
}

// An empty string when `hashes` equals the stored list, else the first differing step.
std::string firstDifference(const HashRun& run, const std::vector<std::string>& hashes) {
  if (hashes.size() != run.hashes.size())
    return fmt::format("{}: {} hashes, manifest has {}", run.name(), hashes.size(),
                       run.hashes.size());
  for (std::size_t s = 0; s < hashes.size(); ++s)
    if (hashes[s] != run.hashes[s])
      return fmt::format("{}: first differs at step {}: manifest {}, now {}", run.name(), s,
                         run.hashes[s], hashes[s]);
  return "";
}

void expectStoredRunReproduced(const std::string& scene, Method method, Precision precision,
                               std::int64_t steps) {
  const HashRun* run = storedRun(scene, method, precision, steps);
  ASSERT_NE(run, nullptr) << scene << ' ' << methodName(method) << ' ' << precisionName(precision)
                          << ' ' << steps << " steps: missing from golden/manifest.json";
  const std::vector<std::string> hashes =
      precision == Precision::Float ? hashesAlone<float>(*run) : hashesAlone<double>(*run);
  EXPECT_EQ(firstDifference(*run, hashes), "");
}

TEST(Determinism, Course2022EveryIntegratorMatchesManifest) {
  for (Method method : kAllMethods)
    expectStoredRunReproduced("course2022", method, Precision::Float, 1000);
}

TEST(Determinism, SmallScenesEveryIntegratorBothPrecisionsMatchManifest) {
  int runs = 0;
  for (const HashRun& run : manifest().hash_runs) {
    // The course scenes (625 particles) are the test above; every other stored run is small.
    if (run.scene.rfind("course", 0) == 0) continue;
    expectStoredRunReproduced(run.scene, run.method, run.precision, run.steps);
    ++runs;
  }
  // Five small scenes, five integrators, float and double.
  EXPECT_GE(runs, 5 * 5 * 2);
}

// Three worlds advanced round-robin, one step each: two copies of the same run and a different
// scene in double. Each must hash, step by step, as its stored lone run.
TEST(Determinism, InterleavedWorldsHashAsAlone) {
  const HashRun* rk4 = storedRun("course2022", Method::Rk4, Precision::Float, 1000);
  const HashRun* spheres = storedRun("two-spheres", Method::Midpoint, Precision::Double, 1000);
  ASSERT_NE(rk4, nullptr);
  ASSERT_NE(spheres, nullptr);
  World<float> a = makeWorld<float>(*findBuiltinScene("course2022"), Method::Rk4);
  World<float> b = makeWorld<float>(*findBuiltinScene("course2022"), Method::Rk4);
  World<double> c = makeWorld<double>(*findBuiltinScene("two-spheres"), Method::Midpoint);
  std::vector<std::string> hashes_a, hashes_b, hashes_c;
  for (std::int64_t s = 0;; ++s) {
    hashes_a.push_back(hashToHex(stateHash(a)));
    hashes_c.push_back(hashToHex(stateHash(c)));
    hashes_b.push_back(hashToHex(stateHash(b)));
    if (s == 1000) break;
    step(a);
    step(c);
    step(b);
  }
  EXPECT_EQ(firstDifference(*rk4, hashes_a), "");
  EXPECT_EQ(firstDifference(*rk4, hashes_b), "");
  EXPECT_EQ(firstDifference(*spheres, hashes_c), "");
}

// Hashes see every bit: one ULP in one coordinate changes the hash (so equal hashes mean equal
// states, and the tests above can fail).
TEST(Determinism, OneUlpChangesTheHash) {
  World<float> world = makeWorld<float>(*findBuiltinScene("small-cloth"), Method::Explicit);
  const std::uint64_t before = stateHash(world);
  float& x = world.cloth->particles.position(0, 40);
  x = std::nextafter(x, 1.0f);
  EXPECT_NE(stateHash(world), before);
}

}  // namespace
}  // namespace clothref
