#include "clothref/record/record.h"
#include "clothref/scene/make_world.h"
#include "clothref/trace/format.h"

#include <string>
#include <vector>

#define XXH_STATIC_LINKING_ONLY
#include <xxhash.h>

#include <gtest/gtest.h>

#include "clothref/record/world_views.h"
#include "test_util.h"

namespace clothref {
namespace {

using json = nlohmann::json;

std::vector<json> traceLines(const Scene& scene, const TraceSettings& settings) {
  std::vector<json> lines;
  for (const std::string& line : test::traceLines(scene, settings))
    lines.push_back(json::parse(line));
  return lines;
}

TraceSettings settings(Method method, Precision precision, std::int64_t steps, std::int64_t stride,
                       double dt) {
  TraceSettings s;
  s.method = method;
  s.precision = precision;
  s.steps = steps;
  s.stride = stride;
  s.dt = dt;
  return s;
}

TEST(Trace, HeaderCarriesTheFullSceneAndRun) {
  const Scene& scene = *findBuiltinScene("course2022");
  const auto lines = traceLines(scene, settings(Method::Midpoint, Precision::Double, 3, 1, 2e-4));
  const json& header = lines.front();
  EXPECT_EQ(header["format"].get<std::string>(), "clothref-trace");
  EXPECT_EQ(header["version"].get<int>(), kTraceVersion);
  EXPECT_EQ(sceneFromJson(header["scene"]), scene);
  EXPECT_EQ(header["integrator"].get<std::string>(), "midpoint");
  EXPECT_EQ(header["precision"].get<std::string>(), "double");
  EXPECT_EQ(header["dt"].get<double>(), 2e-4);
  EXPECT_EQ(header["stride"].get<int>(), 1);
  EXPECT_EQ(header["bodies"][0]["name"].get<std::string>(), "cloth");
  EXPECT_EQ(header["bodies"][0]["particles"].get<int>(), 625);
  EXPECT_EQ(header["bodies"][1]["name"].get<std::string>(), "spheres");
  EXPECT_TRUE(header["build"].contains("compiler"));
}

TEST(Trace, RecordsStepZeroEveryStrideAndTheLast) {
  const auto lines = traceLines(*findBuiltinScene("spring"),
                                settings(Method::Rk4, Precision::Float, 25, 10, 1e-3));
  std::vector<int> steps;
  for (std::size_t i = 1; i < lines.size(); ++i) steps.push_back(lines[i]["step"].get<int>());
  EXPECT_EQ(steps, (std::vector<int>{0, 10, 20, 25}));
  EXPECT_EQ(lines.back()["t"].get<double>(), 25 * double(1e-3f));
}

// Every number parses back to the bits the world holds, and the hash on each line is the
// documented XXH3-64 of the x, y, z values it carries.
template <typename T>
void checkRoundTripAndHash(Precision precision) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  World<T> world = makeWorld<T>(scene, Method::Explicit);
  for (int i = 0; i < 700; ++i) step(world);  // the sphere is on the cloth by now
  std::string text;
  appendStepLine(text, world);
  const json line = json::parse(text);
  EXPECT_EQ(line["step"].get<int>(), 700);
  EXPECT_EQ(line["hash"].get<std::string>(), hashToHex(stateHash(world)));

  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  auto check = [&](const char* name, const Particles<T>& p) {
    for (const char* field : {"position", "velocity"}) {
      const Mat4X<T>& m = std::string(field) == "position" ? p.position : p.velocity;
      const json& values = line["bodies"][name][field];
      ASSERT_EQ(values.size(), std::size_t(p.size()));
      for (int i = 0; i < p.size(); ++i)
        for (int k = 0; k < 3; ++k) {
          const T parsed = static_cast<T>(values[i][k].template get<double>());
          ASSERT_EQ(test::bits(parsed), test::bits(m(k, i))) << name << field << i << k;
          XXH3_64bits_update(&state, &parsed, sizeof(T));
        }
    }
  };
  check("cloth", world.cloth->particles);
  check("spheres", world.spheres->particles);
  EXPECT_EQ(hashToHex(XXH3_64bits_digest(&state)), line["hash"].get<std::string>());
  (void)precision;
}

TEST(Trace, FloatValuesRoundTripAndHashIsRecomputable) {
  checkRoundTripAndHash<float>(Precision::Float);
}
TEST(Trace, DoubleValuesRoundTripAndHashIsRecomputable) {
  checkRoundTripAndHash<double>(Precision::Double);
}

TEST(Trace, FloatsAreWrittenShortestInFloat) {
  World<float> world = makeWorld<float>(*findBuiltinScene("course2022"), Method::Explicit);
  std::string text;
  appendStepLine(text, world);
  // particle 1 sits at x = -1.8333334f: its shortest float text, not the double expansion
  EXPECT_NE(text.find("[-1.8333334,0,-2]"), std::string::npos);
}

TEST(Trace, NonFiniteValuesAreQuotedStrings) {
  World<float> world = makeWorld<float>(*findBuiltinScene("free-fall"), Method::Explicit);
  world.cloth->particles.position(0, 0) = std::numeric_limits<float>::quiet_NaN();
  world.cloth->particles.velocity(1, 0) = -std::numeric_limits<float>::infinity();
  std::string text;
  appendStepLine(text, world);
  const json line = json::parse(text);
  EXPECT_EQ(line["bodies"]["cloth"]["position"][0][0].get<std::string>(), "NaN");
  EXPECT_EQ(line["bodies"]["cloth"]["velocity"][0][1].get<std::string>(), "-Infinity");
}

}  // namespace
}  // namespace clothref
