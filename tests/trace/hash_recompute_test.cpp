// The hash on every trace line, recomputed from nothing but the trace's text, as a tool outside
// clothref would do it (docs/trace-format.md): parse each step line with a JSON parser whose
// floating-point type is the run's precision (so float text becomes the float it was written
// from), then XXH3-64 (seed 0) over the little-endian bytes of x, y, z of every position, then of
// every velocity, body by body in the header's order. It must equal the recorded hash on every
// line, in float and double. Independent of clothref's hash, reader and writer code.
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#define XXH_INLINE_ALL
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <xxhash.h>

#include <nlohmann/json.hpp>

#include "clothref/record/record.h"

namespace clothref {
namespace {

// nlohmann::json with T as its floating-point type (its lexer then parses with strtof for float).
template <typename T>
using JsonIn =
    nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t, std::uint64_t, T>;

struct Recomputed {
  int lines = 0;
  int mismatches = 0;
  std::string first_mismatch;
  std::int64_t last_step = -1;
  bool velocities_differ_from_positions = false;
};

template <typename T>
Recomputed recompute(const std::string& trace_text) {
  Recomputed out;
  std::istringstream in(trace_text);
  std::string line;
  std::getline(in, line);
  const auto header = JsonIn<T>::parse(line);
  std::vector<std::string> body_names;
  for (const auto& body : header["bodies"])
    body_names.push_back(body["name"].template get<std::string>());
  while (std::getline(in, line)) {
    const auto step = JsonIn<T>::parse(line);
    XXH3_state_t state;
    XXH3_64bits_reset(&state);
    for (const std::string& name : body_names) {
      const auto& body = step["bodies"][name];
      for (const char* field : {"position", "velocity"}) {
        for (const auto& particle : body[field]) {
          EXPECT_EQ(particle.size(), 3u) << "x, y, z per particle";
          for (const auto& value : particle) {
            const T number = value.template get<T>();
            XXH3_64bits_update(&state, &number, sizeof(T));  // little-endian on x86-64
          }
        }
      }
      out.velocities_differ_from_positions |= body["position"] != body["velocity"];
    }
    const std::string hash = fmt::format("{:016x}", XXH3_64bits_digest(&state));
    if (hash != step["hash"].template get<std::string>() && out.mismatches++ == 0)
      out.first_mismatch = fmt::format("step {}: recorded {}, recomputed {}",
                                       step["step"].template get<std::int64_t>(),
                                       step["hash"].template get<std::string>(), hash);
    out.last_step = step["step"].template get<std::int64_t>();
    ++out.lines;
  }
  return out;
}

struct Case {
  const char* scene;
  Method method;
  std::int64_t steps;
  std::int64_t stride;  // steps is not a multiple of it: the last step must still be recorded
};

// A cloth with a sphere on it, and two spheres in an off-axis impact.
constexpr Case kCases[] = {{"small-cloth", Method::Rk4, 2150, 200},
                           {"two-spheres-oblique", Method::Midpoint, 333, 20}};

template <typename T>
void checkEveryLine(Precision precision) {
  for (const Case& c : kCases) {
    TraceSettings settings;
    settings.method = c.method;
    settings.precision = precision;
    settings.dt = findBuiltinScene(c.scene)->dt;
    settings.steps = c.steps;
    settings.stride = c.stride;
    std::ostringstream text;
    writeTrace(*findBuiltinScene(c.scene), settings, text);
    const Recomputed result = recompute<T>(text.str());
    SCOPED_TRACE(c.scene);
    EXPECT_EQ(result.lines, int(c.steps / c.stride) + 2) << "steps 0, every stride, and the last";
    EXPECT_EQ(result.last_step, c.steps);
    EXPECT_EQ(result.mismatches, 0) << result.first_mismatch;
    EXPECT_TRUE(result.velocities_differ_from_positions);
  }
}

TEST(HashRecompute, FloatTraceHashesFollowFromTheirValues) {
  checkEveryLine<float>(Precision::Float);
}
TEST(HashRecompute, DoubleTraceHashesFollowFromTheirValues) {
  checkEveryLine<double>(Precision::Double);
}

}  // namespace
}  // namespace clothref
