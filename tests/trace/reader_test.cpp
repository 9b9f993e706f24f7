// trace_reader: a trace written by writeTrace parses back to the exact bits the world held, the
// non-finite strings come back as NaN / infinity, and every malformed case is rejected with its
// file and line number.
#include "clothref/trace/reader.h"
#include "clothref/scene/make_world.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "clothref/io/error.h"
#include "clothref/io/limits.h"
#include "clothref/io/output_file.h"
#include "clothref/record/record.h"
#include "clothref/record/world_views.h"
#include "clothref/trace/format.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed at the end.
class TraceReaderTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.file(name); }

  // Writes a trace of `scene` and returns its lines.
  std::vector<std::string> writeLines(const std::string& name, const Scene& scene,
                                      const TraceSettings& settings) {
    const std::vector<std::string> lines = test::traceLines(scene, settings);
    writeLines(name, lines);
    return lines;
  }

  void writeLines(const std::string& name, const std::vector<std::string>& lines,
                  bool final_newline = true) {
    test::writeLines(path(name), lines, final_newline);
  }

  // The InputError message of reading `name` to the end, or "" when it reads fine.
  std::string readError(const std::string& name) {
    try {
      readTrace(path(name));
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }

  test::TempDir dir_;
};

TraceSettings settingsFor(const Scene& scene, Precision precision, std::int64_t steps,
                          std::int64_t stride) {
  TraceSettings settings;
  settings.precision = precision;
  settings.dt = scene.dt;
  settings.steps = steps;
  settings.stride = stride;
  return settings;
}

// Every recorded value equals, bit for bit, the state of a world stepped alongside.
template <typename T>
void expectSameBits(const Trace& trace, const Scene& scene, std::int64_t steps,
                    std::int64_t stride) {
  World<T> world = makeWorld<T>(scene, Method::Explicit);
  std::size_t line = 0;
  for (std::int64_t s = 0; s <= steps; ++s) {
    if (isRecorded(s, steps, stride)) {
      ASSERT_LT(line, trace.steps.size());
      const TraceStep& recorded = trace.steps[line++];
      EXPECT_EQ(recorded.prefix.step, s);
      EXPECT_EQ(recorded.prefix.hash, stateHash(world));
      ASSERT_EQ(recorded.bodies.size(), 2u);
      const Particles<T>* parts[] = {&world.cloth->particles, &world.spheres->particles};
      for (std::size_t b = 0; b < 2; ++b)
        for (Eigen::Index i = 0; i < parts[b]->position.cols(); ++i)
          for (int k = 0; k < 3; ++k) {
            const T position = T(recorded.bodies[b].position[std::size_t(3 * i + k)]);
            const T velocity = T(recorded.bodies[b].velocity[std::size_t(3 * i + k)]);
            // widening to double and back is exact, so the bits must match
            ASSERT_EQ(test::bits(position), test::bits(parts[b]->position(k, i)));
            ASSERT_EQ(test::bits(velocity), test::bits(parts[b]->velocity(k, i)));
          }
    }
    if (s < steps) step(world);
  }
  EXPECT_EQ(line, trace.steps.size());
}

TEST_F(TraceReaderTest, FloatTraceParsesBackToTheExactBits) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 300, 25));
  const Trace trace = readTrace(path("a.jsonl"));
  EXPECT_EQ(trace.header.precision, Precision::Float);
  EXPECT_EQ(trace.header.steps, 300);
  EXPECT_EQ(trace.header.stride, 25);
  ASSERT_EQ(trace.header.bodies.size(), 2u);
  EXPECT_EQ(trace.header.bodies[0].name, "cloth");
  EXPECT_EQ(trace.header.bodies[0].particles, 81);
  EXPECT_EQ(trace.steps.size(), 13u);
  expectSameBits<float>(trace, scene, 300, 25);
}

TEST_F(TraceReaderTest, DoubleTraceParsesBackToTheExactBits) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  writeLines("a.jsonl", scene, settingsFor(scene, Precision::Double, 120, 50));
  const Trace trace = readTrace(path("a.jsonl"));
  EXPECT_EQ(trace.header.precision, Precision::Double);
  expectSameBits<double>(trace, scene, 120, 50);
}

TEST_F(TraceReaderTest, NonFiniteStringsReadAsNanAndInfinity) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 10));
  // step 10: particle 1 position and velocity become non-finite
  const std::string last = lines[2];
  const auto position = last.find("\"position\":[[0,0,0],[") + 21;
  lines[2] = last.substr(0, position) + "\"NaN\",\"Infinity\",\"-Infinity\"" +
             last.substr(last.find(']', position));
  writeLines("b.jsonl", lines);
  const Trace trace = readTrace(path("b.jsonl"));
  const std::vector<double>& p = trace.steps[1].bodies[0].position;
  EXPECT_TRUE(std::isnan(p[3]));
  EXPECT_EQ(p[4], std::numeric_limits<double>::infinity());
  EXPECT_EQ(p[5], -std::numeric_limits<double>::infinity());
}

TEST_F(TraceReaderTest, MalformedInputNamesFileAndLine) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  const std::vector<std::string> lines =
      writeLines("good.jsonl", scene, settingsFor(scene, Precision::Float, 40, 10));
  ASSERT_EQ(readError("good.jsonl"), "");
  ASSERT_EQ(lines.size(), 6u);  // header + steps 0, 10, 20, 30, 40

  struct Case {
    std::string name;
    int line;                                      // 1-based line to edit
    std::function<std::string(std::string)> edit;  // new text of that line
    std::string expected;                          // part of the message after FILE:LINE:
  };
  auto replaceFirst = [](std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::vector<Case> cases = {
      {"truncated", 4, [](std::string s) { return s.substr(0, s.size() / 2); }, "truncated line"},
      {"not-json", 3, [](std::string) { return std::string("not json"); }, "expected '{'"},
      {"lowercase-nan", 4,
       [&](std::string s) { return replaceFirst(s, "\"velocity\":[[0", "\"velocity\":[[nan"); },
       "expected a number, got 'n'"},
      {"cut-infinity", 4,
       [&](std::string s) { return replaceFirst(s, "\"velocity\":[[0", "\"velocity\":[[-Inf"); },
       "expected a number, got 'I'"},
      {"missing-key", 5, [&](std::string s) { return replaceFirst(s, "\"t\":", "\"time\":"); },
       "/time: unknown key"},
      {"missing-hash", 5,
       [&](std::string s) {
         const auto at = s.find(",\"hash\"");
         return s.erase(at, s.find(",\"bodies\"") - at);
       },
       "missing key \"hash\""},
      {"two-components", 3,
       [&](std::string s) {
         return replaceFirst(s, "\"velocity\":[[0,0,0]", "\"velocity\":[[0,0]");
       },
       "/bodies/cloth/velocity/0"},
      {"four-components", 3,
       [&](std::string s) {
         return replaceFirst(s, "\"velocity\":[[0,0,0]", "\"velocity\":[[0,0,0,0]");
       },
       "expected 3 components"},
      {"missing-particle", 6,
       [&](std::string s) { return replaceFirst(s, "\"velocity\":[[0,0,0],", "\"velocity\":["); },
       "80 particles, the header declares 81"},
      {"missing-body", 2,
       [&](std::string s) {
         const auto at = s.find(",\"spheres\"");
         return s.erase(at, s.size() - 2 - at);
       },
       "missing body \"spheres\""},
      {"wrong-format", 1,
       [&](std::string s) { return replaceFirst(s, "clothref-trace", "other-trace"); },
       "not a clothref trace"},
      {"unsupported-version", 1,
       [&](std::string s) { return replaceFirst(s, "\"version\":1", "\"version\":7"); },
       "unsupported version 7"},
      {"header-not-json", 1, [](std::string s) { return s.substr(0, 50); }, "not valid JSON"},
      {"header-missing-dt", 1,
       [&](std::string s) { return replaceFirst(s, "\"dt\":0.0001,\"steps\"", "\"steps\""); },
       "missing key \"dt\""},
      {"bad-number", 4,
       [&](std::string s) { return replaceFirst(s, "\"velocity\":[[0", "\"velocity\":[[0.0.1"); },
       "malformed"},
      {"bad-hash", 3,
       [&](std::string s) { return replaceFirst(s, "\"hash\":\"", "\"hash\":\"zz"); },
       "16 hex digits"},
      {"missing-line", 4, [](std::string) { return std::string(); }, "empty line"},
      {"wrong-step", 4,
       [&](std::string s) { return replaceFirst(s, "\"step\":20", "\"step\":25"); },
       "expected step 20"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> edited = lines;
    edited[std::size_t(c.line - 1)] = c.edit(edited[std::size_t(c.line - 1)]);
    writeLines(c.name + ".jsonl", edited);
    const std::string message = readError(c.name + ".jsonl");
    const std::string where = path(c.name + ".jsonl") + ":" + std::to_string(c.line) + ": ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
  }
}

TEST_F(TraceReaderTest, CutFilesAndMissingFilesAreErrors) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("good.jsonl", scene, settingsFor(scene, Precision::Float, 30, 10));
  // a last line without its newline was cut short
  writeLines("no-newline.jsonl", lines, false);
  EXPECT_NE(readError("no-newline.jsonl").find("no-newline.jsonl:5: truncated"), std::string::npos)
      << readError("no-newline.jsonl");
  // a file cut at a line boundary ends before the header's last step
  lines.pop_back();
  writeLines("short.jsonl", lines);
  EXPECT_NE(readError("short.jsonl").find("trace ends after step 20, the header says 30 steps"),
            std::string::npos)
      << readError("short.jsonl");
  writeLines("empty.jsonl", {}, false);
  EXPECT_NE(readError("empty.jsonl").find("empty.jsonl:1: empty file"), std::string::npos);
  EXPECT_NE(readError("absent.jsonl").find("absent.jsonl: cannot open"), std::string::npos);
}

TEST_F(TraceReaderTest, KeysAreMatchedByNameNotPosition) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 10));
  // move "bodies" before "step" and swap position and velocity in line 3
  std::string& line = lines[2];
  const auto bodies = line.find(",\"bodies\"");
  const std::string prefix = line.substr(1, bodies - 1);  // "step":..,"hash":".."
  const std::string rest = line.substr(bodies + 1, line.size() - bodies - 2);  // "bodies":{..}
  const auto position = rest.find("\"position\"");
  const auto velocity = rest.find(",\"velocity\"");
  const std::string body =
      fmt::format("{{{},{}}}}}", rest.substr(velocity + 1, rest.size() - 2 - velocity - 1),
                  rest.substr(position, velocity - position));
  line = fmt::format("{{{}{},{}}}", rest.substr(0, position - 1), body, prefix);
  writeLines("b.jsonl", lines);
  const Trace a = readTrace(path("a.jsonl"));
  const Trace b = readTrace(path("b.jsonl"));
  ASSERT_EQ(b.steps.size(), 2u);
  EXPECT_EQ(b.steps[1].prefix.step, 10);
  EXPECT_EQ(b.steps[1].prefix.hash, a.steps[1].prefix.hash);
  EXPECT_EQ(b.steps[1].bodies[0].position, a.steps[1].bodies[0].position);
  EXPECT_EQ(b.steps[1].bodies[0].velocity, a.steps[1].bodies[0].velocity);
}

// Python's json.dumps writes bare NaN, Infinity and -Infinity: they read like the strings.
TEST_F(TraceReaderTest, BareNonFiniteTokensReadLikeTheStrings) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Double, 10, 10));
  const std::string last = lines[2];
  const auto position = last.find("\"position\":[[0,0,0],[") + 21;
  lines[2] =
      last.substr(0, position) + "NaN, Infinity, -Infinity" + last.substr(last.find(']', position));
  writeLines("b.jsonl", lines);
  const Trace trace = readTrace(path("b.jsonl"));
  const std::vector<double>& p = trace.steps[1].bodies[0].position;
  EXPECT_TRUE(std::isnan(p[3]));
  EXPECT_EQ(p[4], std::numeric_limits<double>::infinity());
  EXPECT_EQ(p[5], -std::numeric_limits<double>::infinity());
}

// t follows the rule of every other number: a run whose time overflows reads back.
TEST_F(TraceReaderTest, NonFiniteTimeReadsBack) {
  const Scene& scene = *findBuiltinScene("spring");
  TraceSettings settings = settingsFor(scene, Precision::Double, 2, 1);
  settings.dt = 1e308;  // t = 2e308 overflows at step 2
  const std::vector<std::string> lines = writeLines("a.jsonl", scene, settings);
  ASSERT_NE(lines[3].find("\"t\":\"Infinity\""), std::string::npos) << lines[3];
  const Trace trace = readTrace(path("a.jsonl"));
  ASSERT_EQ(trace.steps.size(), 3u);
  EXPECT_EQ(trace.steps[2].prefix.t, std::numeric_limits<double>::infinity());
}

// Header values that used to abort, exhaust memory, overflow or recurse without bound are one
// InputError each.
TEST_F(TraceReaderTest, HostileHeadersAreInputErrors) {
  const Scene& scene = *findBuiltinScene("spring");
  const std::vector<std::string> lines =
      writeLines("good.jsonl", scene, settingsFor(scene, Precision::Float, 10, 5));
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::string header = lines[0];
  // the first body's "particles":N (the scene object has a "particles" key of its own)
  const std::size_t first = header.find("\"particles\":", header.find("\"bodies\""));
  const std::string particles = header.substr(first, header.find('}', first) - first);
  struct Case {
    std::string name, header, expected;
  };
  const std::vector<Case> cases = {
      {"huge-dt", replaced(header, "\"dt\":", "\"dt\":1e400,\"x\":"), "not valid JSON"},
      {"particles-1e12", replaced(header, particles, "\"particles\":1000000000000"),
       "above the limit 10000000 (raise it with --max-particles)"},
      {"particles-4e18", replaced(header, particles, "\"particles\":4000000000000000000"),
       "above the limit"},
      {"particles-2e19", replaced(header, particles, "\"particles\":18000000000000000000"),
       "too large"},
      {"deep",
       replaced(header, "\"build\":", "\"deep\":" + std::string(100000, '[') + "],\"build\":"),
       "nested deeper than 64 levels"},
      {"steps-huge", replaced(header, "\"steps\":10", "\"steps\":9223372036854775807"),
       "above the limit"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> edited = lines;
    edited[0] = c.header;
    writeLines(c.name + ".jsonl", edited);
    const std::string message = readError(c.name + ".jsonl");
    EXPECT_EQ(message.rfind(path(c.name + ".jsonl") + ":1", 0), 0u) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_LT(message.size(), 400u) << c.name;
  }
}

// steps 2^63-1 with stride 2^62+1: the next expected step is computed without overflow (UBSan
// flagged the old form), and the limit raised to allow it.
TEST_F(TraceReaderTest, StepArithmeticNearTheTopOfInt64DoesNotOverflow) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 5));
  std::string& header = lines[0];
  header.replace(header.find("\"steps\":10"), 10, "\"steps\":9223372036854775807");
  header.replace(header.find("\"stride\":5"), 10, "\"stride\":4611686018427387905");
  lines[2].replace(lines[2].find("\"step\":5"), 8, "\"step\":4611686018427387905");
  writeLines("b.jsonl", lines);
  const std::int64_t saved = inputLimits().steps;
  inputLimits().steps = std::numeric_limits<std::int64_t>::max();
  TraceReader reader(path("b.jsonl"));
  EXPECT_TRUE(reader.next());
  EXPECT_TRUE(reader.next());
  EXPECT_EQ(reader.prefix().step, 4611686018427387905);
  try {
    reader.next();  // step 10 where 2^63-1 is expected
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("expected step 9223372036854775807"),
              std::string::npos)
        << error.what();
  }
  inputLimits().steps = saved;
}

// A line longer than the limit is refused while reading it; its message quotes no content.
TEST_F(TraceReaderTest, LinesLongerThanTheLimitAreRefused) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 5));
  lines[2] = std::string(5000, '"');
  writeLines("b.jsonl", lines);
  const std::size_t saved = inputLimits().line_bytes;
  inputLimits().line_bytes = 4096;
  const std::string message = readError("b.jsonl");
  inputLimits().line_bytes = saved;
  EXPECT_NE(message.find(":3: line longer than 4096 bytes (raise the limit with --max-line-bytes)"),
            std::string::npos)
      << message;
  EXPECT_EQ(readError("a.jsonl"), "");
}

// An unterminated 1 MB string: the error line quotes a short excerpt, not the string.
TEST_F(TraceReaderTest, ErrorsQuoteShortExcerpts) {
  const Scene& scene = *findBuiltinScene("spring");
  std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 5));
  for (const std::string& text :
       {"{\"format\":\"" + std::string(1 << 20, 'x'),
        "{\"step\":0,\"t\":0,\"hash\":\"" + std::string(1 << 20, 'x') + "\"}"}) {
    std::vector<std::string> edited = lines;
    edited[text[2] == 's' ? 1 : 0] = text;
    writeLines("b.jsonl", edited);
    const std::string message = readError("b.jsonl");
    EXPECT_FALSE(message.empty());
    EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
  }
}

// Gzip-compressed traces (written by OutputFile for a .gz path) read exactly like plain ones.
TEST_F(TraceReaderTest, GzipTracesReadLikePlainOnes) {
  const Scene& scene = *findBuiltinScene("small-cloth");
  const TraceSettings settings = settingsFor(scene, Precision::Float, 60, 20);
  writeLines("a.jsonl", scene, settings);
  {
    OutputFile out(path("a.jsonl.gz"));
    writeTrace(scene, settings, out.stream());
    out.commit();
  }
  std::ifstream compressed(path("a.jsonl.gz"), std::ios::binary);
  ASSERT_EQ(compressed.get(), 0x1f);  // really gzip
  const Trace plain = readTrace(path("a.jsonl"));
  const Trace unzipped = readTrace(path("a.jsonl.gz"));
  ASSERT_EQ(unzipped.steps.size(), plain.steps.size());
  for (std::size_t s = 0; s < plain.steps.size(); ++s) {
    EXPECT_EQ(unzipped.steps[s].prefix.hash, plain.steps[s].prefix.hash);
    EXPECT_EQ(unzipped.steps[s].bodies[0].position, plain.steps[s].bodies[0].position);
  }
  // cut short: an error naming the file, not a crash or a silent short trace
  std::ifstream in(path("a.jsonl.gz"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(path("cut.jsonl.gz"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string message = readError("cut.jsonl.gz");
  EXPECT_EQ(message.rfind(path("cut.jsonl.gz") + ":", 0), 0u) << message;
}

// The state hash recomputed from a step's values equals the one the writer put on the line.
TEST_F(TraceReaderTest, RecomputedHashMatchesTheWrittenOne) {
  for (Precision precision : {Precision::Float, Precision::Double}) {
    const Scene& scene = *findBuiltinScene("small-cloth");
    writeLines("a.jsonl", scene, settingsFor(scene, precision, 20, 10));
    const Trace trace = readTrace(path("a.jsonl"));
    for (const TraceStep& step : trace.steps)
      EXPECT_EQ(stateHashOf(trace.header, step), step.prefix.hash);
  }
}

// A value edited under its old hash is a corrupt record; a NaN, written "NaN" whatever its bits,
// keeps whatever hash the writer computed from them.
TEST_F(TraceReaderTest, StaleHashIsACorruptRecord) {
  const Scene& scene = *findBuiltinScene("spring");
  const std::vector<std::string> lines =
      writeLines("a.jsonl", scene, settingsFor(scene, Precision::Float, 10, 5));
  ASSERT_EQ(lines.size(), 4u);
  std::vector<std::string> edited = lines;
  const std::size_t at = edited[2].find("\"velocity\":[[") + 13;
  edited[2].replace(at, edited[2].find(',', at) - at, "7");
  writeLines("stale.jsonl", edited);
  EXPECT_EQ(readError("stale.jsonl"),
            path("stale.jsonl") +
                ":3: /hash: does not match the step's own values (a corrupt or edited record)");
  edited[2] = test::rehashed(edited, 2);
  writeLines("rehashed.jsonl", edited);
  EXPECT_EQ(readError("rehashed.jsonl"), "");
  // a NaN's sign and payload are not in the text: the written hash stands
  edited = lines;
  edited[2].replace(at, edited[2].find(',', at) - at, "\"NaN\"");
  writeLines("nan.jsonl", edited);
  EXPECT_EQ(readError("nan.jsonl"), "");
}

}  // namespace
}  // namespace clothref
