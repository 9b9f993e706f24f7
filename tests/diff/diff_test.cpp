// diff: traces written by the library, perturbed as text, compared through diffTraces and the
// CLI. Covers: self-diff, one perturbed value located exactly, 1 ULP, the floor near zero, each
// tolerance mode, non-finite values, --write-tolerances making the same diff pass, header
// differences, shapes and --common-steps, the hash shortcut, and --json.
#include "clothref/diff/diff.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "clothref/io/error.h"
#include "clothref/record/record.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

// Where one value sits in a trace.
struct Location {
  std::size_t line;  // 0-based line index in the file (0 = header, 1 = step 0, ...)
  std::string body;
  std::string field;
  std::size_t particle;
  int component;
};

// [begin, end) of the value text at `where` in `line`.
std::pair<std::size_t, std::size_t> findValue(const std::string& line, const Location& where) {
  std::size_t at = line.find("\"" + where.body + "\":{");
  at = line.find("\"" + where.field + "\":[", at) + where.field.size() + 4;
  for (std::size_t p = 0; p <= where.particle; ++p) at = line.find('[', at) + 1;
  for (int k = 0; k < where.component; ++k) at = line.find(',', at) + 1;
  const std::size_t end = line.find_first_of(",]", at);
  return {at, end};
}

class DiffTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.file(name); }

  std::vector<std::string> write(const std::string& name, const Scene& scene,
                                 TraceSettings settings) {
    if (settings.dt == 0) settings.dt = scene.dt;
    const std::vector<std::string> lines = test::traceLines(scene, settings);
    write(name, lines);
    return lines;
  }

  void write(const std::string& name, const std::vector<std::string>& lines) {
    test::writeLines(path(name), lines);
  }

  DiffReport diff(const std::string& a, const std::string& b, const DiffOptions& options = {}) {
    return diffTraces(path(a), path(b), options);
  }

  test::TempDir dir_;
};

TraceSettings settings(std::int64_t steps, std::int64_t stride,
                       Precision precision = Precision::Float, Method method = Method::Explicit) {
  TraceSettings s;
  s.steps = steps;
  s.stride = stride;
  s.precision = precision;
  s.method = method;
  return s;
}

const Scene& smallCloth() { return *findBuiltinScene("small-cloth"); }

std::string valueText(const std::vector<std::string>& lines, const Location& where) {
  const auto [begin, end] = findValue(lines[where.line], where);
  return lines[where.line].substr(begin, end - begin);
}

// `lines` with the value at `where` replaced by `text` (and the line's hash updated).
std::vector<std::string> withValue(std::vector<std::string> lines, const Location& where,
                                   const std::string& text) {
  const auto [begin, end] = findValue(lines[where.line], where);
  lines[where.line].replace(begin, end - begin, text);
  lines[where.line] = test::rehashed(lines, where.line);
  return lines;
}

float parseFloat(const std::string& text) { return std::stof(text); }

TEST_F(DiffTest, TraceAgainstItselfIsIdentical) {
  write("a.jsonl", smallCloth(), settings(200, 20));
  const DiffReport report = diff("a.jsonl", "a.jsonl");
  EXPECT_EQ(report.verdict, Verdict::Identical);
  EXPECT_EQ(report.steps_compared, 11);
  EXPECT_EQ(report.steps_equal_hash, 11);  // every step skipped by its hash
  EXPECT_EQ(report.values_compared, 11 * (81 + 1) * 6 + 11);
  EXPECT_EQ(report.values_beyond, 0);
  EXPECT_FALSE(report.worst.has_value());
  const std::string text = formatReport(report);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_EQ(text.rfind("identical", 0), 0u) << text;
  const test::CommandResult run = test::runCli("diff " + path("a.jsonl") + " " + path("a.jsonl"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

// Streams (a pipe, memory) diff exactly as files do, and the names given appear in the report.
TEST_F(DiffTest, StreamsDiffLikeFiles) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(200, 20));
  std::vector<std::string> changed = lines;
  changed[3] = withValue(lines, {3, "cloth", "position", 40, 1}, "0.125")[3];
  write("b.jsonl", changed);
  std::string text_a, text_b;
  for (const std::string& line : lines) text_a += line + "\n";
  for (const std::string& line : changed) text_b += line + "\n";
  std::istringstream a(text_a), b(text_b);
  const DiffReport streamed = diffTraces(a, "reference", b, "(pipe)", {});
  const DiffReport files = diff("a.jsonl", "b.jsonl");
  EXPECT_EQ(streamed.verdict, Verdict::Differ);
  EXPECT_EQ(streamed.values_beyond, files.values_beyond);
  EXPECT_EQ(streamed.first_beyond->step, files.first_beyond->step);
  EXPECT_EQ(streamed.path_a, "reference");
  EXPECT_NE(formatReport(streamed).find("reference vs (pipe)"), std::string::npos);
}

TEST_F(DiffTest, OnePerturbedValueIsFoundAtItsStepBodyParticleComponent) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(200, 20));
  const Location where{6, "cloth", "velocity", 40, 1};  // step 100, centre particle, y
  const float original = parseFloat(valueText(lines, where));
  ASSERT_NE(original, 0.0f);
  const float changed = original * 1.5f;
  write("b.jsonl", withValue(lines, where, fmt::format("{}", changed)));

  const DiffReport report = diff("a.jsonl", "b.jsonl");
  EXPECT_EQ(report.verdict, Verdict::Differ);
  EXPECT_TRUE(report.header_diffs.empty());
  EXPECT_EQ(report.values_beyond, 1);
  EXPECT_EQ(report.steps_equal_hash, 10);  // only the edited step was parsed
  ASSERT_TRUE(report.first_beyond.has_value());
  const ValueDiff& first = *report.first_beyond;
  EXPECT_EQ(first.step, 100);
  EXPECT_EQ(first.body, "cloth");
  EXPECT_EQ(first.field, Field::Velocity);
  EXPECT_EQ(first.particle, 40);
  EXPECT_EQ(first.component, 1);
  EXPECT_EQ(first.a, double(original));
  EXPECT_EQ(first.b, double(changed));
  EXPECT_EQ(first.abs, std::abs(double(changed) - double(original)));
  ASSERT_TRUE(report.worst.has_value());
  EXPECT_EQ(report.worst->step, 100);
  EXPECT_EQ(report.worst->particle, 40);
  // only the changed field is listed
  const std::string text = formatReport(report);
  EXPECT_NE(text.find("cloth velocity"), std::string::npos) << text;
  EXPECT_EQ(text.find("cloth position"), std::string::npos) << text;
  EXPECT_NE(text.find("step 100"), std::string::npos) << text;
  EXPECT_NE(text.find("particle 40 y"), std::string::npos) << text;
  const test::CommandResult run = test::runCli("diff " + path("a.jsonl") + " " + path("b.jsonl"));
  EXPECT_EQ(run.exit_code, 1) << run.output;
}

TEST_F(DiffTest, FloatsOneUlpApartAreExactlyOneUlp) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  const Location where{2, "spheres", "position", 0, 1};  // step 50, sphere height
  const float original = parseFloat(valueText(lines, where));
  const float next = std::nextafter(original, 100.0f);
  write("b.jsonl", withValue(lines, where, fmt::format("{}", next)));

  const DiffReport exact = diff("a.jsonl", "b.jsonl");
  ASSERT_TRUE(exact.worst.has_value());
  EXPECT_EQ(exact.worst->ulps, 1u);
  EXPECT_EQ(exact.values_beyond, 1);
  EXPECT_EQ(exact.verdict, Verdict::Differ);

  DiffOptions one_ulp;
  one_ulp.global.ulps = 1;
  const DiffReport within = diff("a.jsonl", "b.jsonl", one_ulp);
  EXPECT_EQ(within.verdict, Verdict::WithinTolerance);
  EXPECT_EQ(within.values_beyond, 0);

  // the same values in a double trace are many double ULPs apart but one float ULP: ULPs are
  // counted in the trace's precision
  EXPECT_EQ(exact.precision, Precision::Float);
  const test::CommandResult run =
      test::runCli("diff --ulps 1 " + path("a.jsonl") + " " + path("b.jsonl"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

TEST_F(DiffTest, ValuesNearZeroAreHandledByTheFloor) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  // particle 0 is a fixed corner: its velocity stays exactly 0
  const Location where{2, "cloth", "velocity", 0, 0};
  ASSERT_EQ(valueText(lines, where), "0");
  write("b.jsonl", withValue(lines, where, "1e-12"));

  DiffOptions relative;
  relative.global.mode = ToleranceMode::Relative;
  relative.global.rel = 1e-3;
  const DiffReport without_floor = diff("a.jsonl", "b.jsonl", relative);
  EXPECT_EQ(without_floor.verdict, Verdict::Differ);
  ASSERT_TRUE(without_floor.first_beyond.has_value());
  EXPECT_EQ(without_floor.first_beyond->rel, 1.0);  // relative error explodes at zero

  DiffOptions floored = relative;
  floored.global.floor = 1e-9;
  const DiffReport with_floor = diff("a.jsonl", "b.jsonl", floored);
  EXPECT_EQ(with_floor.verdict, Verdict::WithinTolerance);
  EXPECT_EQ(with_floor.values_beyond, 0);

  // only when BOTH values are below the floor: 0 against 1e-3 is a difference even with a floor
  write("c.jsonl", withValue(lines, where, "1e-3"));
  const DiffReport one_side = diff("a.jsonl", "c.jsonl", floored);
  EXPECT_EQ(one_side.verdict, Verdict::Differ);
  EXPECT_EQ(one_side.values_beyond, 1);

  // combined: the absolute test passes near zero where the relative one cannot
  DiffOptions combined;
  combined.global.mode = ToleranceMode::Combined;
  combined.global.abs = 1e-9;
  combined.global.rel = 1e-3;
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", combined).verdict, Verdict::WithinTolerance);

  const test::CommandResult run =
      test::runCli("diff --rel 1e-3 --floor 1e-9 " + path("a.jsonl") + " " + path("b.jsonl"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  const test::CommandResult fail =
      test::runCli("diff --rel 1e-3 " + path("a.jsonl") + " " + path("b.jsonl"));
  EXPECT_EQ(fail.exit_code, 1) << fail.output;
}

TEST_F(DiffTest, AbsoluteAndRelativeModesUseTheirBounds) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  const Location where{3, "spheres", "position", 0, 1};  // step 100, sphere height
  const float original = parseFloat(valueText(lines, where));
  write("b.jsonl", withValue(lines, where, fmt::format("{}", original + 1e-3f)));
  const double difference = std::abs(double(original + 1e-3f) - double(original));

  DiffOptions absolute;
  absolute.global.mode = ToleranceMode::Absolute;
  absolute.global.abs = difference;
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", absolute).verdict, Verdict::WithinTolerance);
  absolute.global.abs = difference * 0.99;
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", absolute).verdict, Verdict::Differ);

  DiffOptions relative;
  relative.global.mode = ToleranceMode::Relative;
  const double magnitude = std::max(std::abs(double(original)), std::abs(double(original + 1e-3f)));
  relative.global.rel = difference / magnitude;
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", relative).verdict, Verdict::WithinTolerance);
  relative.global.rel = difference / magnitude * 0.99;
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", relative).verdict, Verdict::Differ);

  // a per-body override applies to that body only
  DiffOptions per_body;
  per_body.bodies["spheres"].position = Tolerance{ToleranceMode::Absolute, 1e-2};
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", per_body).verdict, Verdict::WithinTolerance);
  per_body.bodies.clear();
  per_body.bodies["cloth"].position = Tolerance{ToleranceMode::Absolute, 1e-2};
  EXPECT_EQ(diff("a.jsonl", "b.jsonl", per_body).verdict, Verdict::Differ);
}

TEST_F(DiffTest, NonFiniteValuesCompareByKind) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  const Location where{2, "cloth", "position", 40, 1};
  write("nan.jsonl", withValue(lines, where, "\"NaN\""));
  write("inf.jsonl", withValue(lines, where, "\"Infinity\""));
  // same kind: equal
  EXPECT_EQ(diff("nan.jsonl", "nan.jsonl").verdict, Verdict::Identical);
  // finite vs NaN, NaN vs Infinity: infinite difference, no tolerance passes it
  DiffOptions loose;
  loose.global.mode = ToleranceMode::Absolute;
  loose.global.abs = 1e30;
  for (const char* other : {"nan.jsonl", "inf.jsonl"}) {
    const DiffReport report = diff("a.jsonl", other, loose);
    EXPECT_EQ(report.verdict, Verdict::Differ) << other;
    ASSERT_TRUE(report.worst.has_value());
    EXPECT_TRUE(std::isinf(report.worst->abs));
    EXPECT_EQ(report.worst->particle, 40);
  }
  EXPECT_EQ(diff("nan.jsonl", "inf.jsonl", loose).verdict, Verdict::Differ);
}

TEST_F(DiffTest, WrittenTolerancesMakeTheSameDiffPass) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(200, 20));
  // several perturbations of different sizes and signs, in both bodies and both fields
  std::vector<std::string> edited = lines;
  for (std::size_t line = 2; line < lines.size(); ++line) {
    for (const Location& where :
         {Location{line, "cloth", "position", 40, 1}, Location{line, "cloth", "velocity", 12, 0},
          Location{line, "spheres", "velocity", 0, 1}}) {
      const float value = parseFloat(valueText(edited, where));
      const float changed = value * (1 + 1e-4f * float(line)) + 1e-6f;
      edited = withValue(edited, where, fmt::format("{}", changed));
    }
  }
  write("b.jsonl", edited);
  for (ToleranceMode mode : {ToleranceMode::Ulps, ToleranceMode::Absolute, ToleranceMode::Relative,
                             ToleranceMode::Combined}) {
    DiffOptions options;
    options.global.mode = mode;  // all bounds 0: everything that differs is beyond
    const DiffReport first = diff("a.jsonl", "b.jsonl", options);
    ASSERT_EQ(first.verdict, Verdict::Differ) << toleranceModeName(mode);
    EXPECT_EQ(first.values_beyond, 3 * 10);
    { std::ofstream(path("tolerances.json")) << observedTolerances(first).dump(2); }
    const DiffOptions written = readToleranceFile(path("tolerances.json"));
    EXPECT_EQ(written.bodies.at("cloth").position->mode, mode);
    const DiffReport second = diff("a.jsonl", "b.jsonl", written);
    EXPECT_EQ(second.verdict, Verdict::WithinTolerance) << toleranceModeName(mode);
    EXPECT_EQ(second.values_beyond, 0);
  }
  // the same through the CLI
  const std::string pair = path("a.jsonl") + " " + path("b.jsonl");
  EXPECT_EQ(
      test::runCli("diff --abs 0 --write-tolerances " + path("cli.json") + " " + pair).exit_code,
      1);
  const test::CommandResult pass =
      test::runCli("diff --tolerances " + path("cli.json") + " " + pair);
  EXPECT_EQ(pass.exit_code, 0) << pass.output;
}

TEST_F(DiffTest, HeaderDifferencesAreReportedFirst) {
  const Scene& base = smallCloth();
  write("a.jsonl", base, settings(40, 20));
  Scene stiffer = base;
  stiffer.cloth->spring_coef = 20000;
  write("scene.jsonl", stiffer, settings(40, 20));
  write("method.jsonl", base, settings(40, 20, Precision::Float, Method::Midpoint));
  TraceSettings other_dt = settings(40, 20);
  other_dt.dt = 2e-4;
  write("dt.jsonl", base, other_dt);
  write("precision.jsonl", base, settings(40, 20, Precision::Double));

  struct Case {
    std::string file, pointer;
  };
  for (const Case& c :
       {Case{"scene.jsonl", "/scene/cloth/spring_coef"}, Case{"method.jsonl", "/integrator"},
        Case{"dt.jsonl", "/dt"}, Case{"precision.jsonl", "/precision"}}) {
    const DiffReport report = diff("a.jsonl", c.file);
    EXPECT_EQ(report.verdict, Verdict::Differ) << c.file;
    ASSERT_FALSE(report.header_diffs.empty()) << c.file;
    EXPECT_EQ(report.header_diffs[0].pointer, c.pointer);
    EXPECT_TRUE(report.header_diffs[0].significant);
    const std::string text = formatReport(report);
    // the header line comes before any state line
    const auto header = text.find(c.pointer);
    ASSERT_NE(header, std::string::npos) << text;
    EXPECT_LT(header, text.find("  steps")) << text;
  }
  EXPECT_NE(
      formatReport(diff("a.jsonl", "scene.jsonl")).find("/scene/cloth/spring_coef: 25000 vs 20000"),
      std::string::npos);
}

TEST_F(DiffTest, BuildDifferencesAreInformational) {
  std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(40, 20));
  const auto at = lines[0].find("\"compiler\":\"") + 12;
  lines[0].replace(at, lines[0].find('"', at) - at, "Clang 99.0.0");
  write("b.jsonl", lines);
  const DiffReport report = diff("a.jsonl", "b.jsonl");
  EXPECT_EQ(report.verdict, Verdict::Identical);
  ASSERT_EQ(report.header_diffs.size(), 1u);
  EXPECT_EQ(report.header_diffs[0].pointer, "/build/compiler");
  EXPECT_FALSE(report.header_diffs[0].significant);
  EXPECT_EQ(test::runCli("diff " + path("a.jsonl") + " " + path("b.jsonl")).exit_code, 0);
}

TEST_F(DiffTest, DifferentShapesAreBadInputUnlessCommonSteps) {
  write("a.jsonl", smallCloth(), settings(200, 20));
  write("short.jsonl", smallCloth(), settings(100, 20));
  write("coarse.jsonl", smallCloth(), settings(200, 40));
  Scene smaller = smallCloth();
  smaller.cloth->grid->particles_per_edge = 7;
  smaller.cloth->fixed = {0, 6, 42, 48};  // the corners of a 7 x 7 grid
  validateScene(smaller);
  write("smaller.jsonl", smaller, settings(200, 20));
  write("spring.jsonl", *findBuiltinScene("spring"), settings(200, 20));

  const std::string a = path("a.jsonl");
  for (const char* other : {"short.jsonl", "coarse.jsonl", "smaller.jsonl", "spring.jsonl"}) {
    EXPECT_THROW(diff("a.jsonl", other), InputError) << other;
    const test::CommandResult run = test::runCli("diff " + a + " " + path(other));
    EXPECT_EQ(run.exit_code, 2) << other << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  }

  DiffOptions common;
  common.common_steps = true;
  const DiffReport shorter = diff("a.jsonl", "short.jsonl", common);
  EXPECT_EQ(shorter.verdict, Verdict::Identical);
  EXPECT_EQ(shorter.steps_a, 11);
  EXPECT_EQ(shorter.steps_b, 6);
  EXPECT_EQ(shorter.steps_compared, 6);  // 0, 20, ..., 100
  const DiffReport coarser = diff("a.jsonl", "coarse.jsonl", common);
  EXPECT_EQ(coarser.verdict, Verdict::Identical);
  EXPECT_EQ(coarser.steps_compared, 6);  // 0, 40, ..., 200
  // bodies must still match
  EXPECT_THROW(diff("a.jsonl", "smaller.jsonl", common), InputError);
  EXPECT_EQ(test::runCli("diff --common-steps " + a + " " + path("short.jsonl")).exit_code, 0);
}

TEST_F(DiffTest, EqualHashWithDifferentBytesIsStillCompared) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  // the same values written differently (a space): the hash is equal but the line must be parsed,
  // not skipped (a changed value under a kept hash is a corrupt record: DiffCli tests)
  std::vector<std::string> spaced = lines;
  spaced[2].replace(spaced[2].find("\"bodies\":"), 9, "\"bodies\": ");
  write("b.jsonl", spaced);
  const DiffReport report = diff("a.jsonl", "b.jsonl");
  EXPECT_EQ(report.steps_compared, 3);
  EXPECT_EQ(report.steps_equal_hash, 2);
  EXPECT_EQ(report.values_beyond, 0);
  EXPECT_EQ(report.verdict, Verdict::Identical);
}

TEST_F(DiffTest, MalformedInputExitsTwoWithFileAndLine) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  // one edit per case, on the 0-based line given; the message must name that line (1-based)
  struct Case {
    std::string name;
    std::size_t line;
    std::string text;
  };
  const Location centre{2, "cloth", "position", 40, 1};
  const std::vector<Case> cases = {
      {"truncated", 3, lines[3].substr(0, 300)},
      {"not-json", 2, "hello"},
      {"lowercase-nan", 2, withValue(lines, centre, "nan")[2]},
      {"cut-infinity", 3, withValue(lines, Location{3, "spheres", "velocity", 0, 1}, "-Inf")[3]},
      {"string-value", 2, withValue(lines, centre, "\"1.5\"")[2]},
      {"wrong-shape", 2, withValue(lines, centre, "0,0")[2]},
      {"missing-key", 1,
       lines[1].substr(0, lines[1].find(",\"t\"")) + lines[1].substr(lines[1].find(",\"hash\""))},
      {"wrong-version", 0,
       std::string(lines[0]).replace(lines[0].find("\"version\":1"), 11, "\"version\":9")},
  };
  for (const Case& c : cases) {
    std::vector<std::string> bad = lines;
    bad[c.line] = c.text;
    write(c.name + ".jsonl", bad);
    // the malformed file on either side
    for (const std::string& args : {path("a.jsonl") + " " + path(c.name + ".jsonl"),
                                    path(c.name + ".jsonl") + " " + path("a.jsonl")}) {
      const test::CommandResult run = test::runCli("diff " + args);
      EXPECT_EQ(run.exit_code, 2) << c.name << ": " << run.output;
      EXPECT_EQ(run.output.rfind(
                    fmt::format("clothref: {}:{}: ", path(c.name + ".jsonl"), c.line + 1), 0),
                0u)
          << c.name << ": " << run.output;
      EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    }
  }
  EXPECT_EQ(test::runCli("diff " + path("a.jsonl") + " " + path("absent.jsonl")).exit_code, 2);
  std::ofstream(path("bad-tolerances.json")) << R"({"bodies": {"cloht": {}}})";
  const test::CommandResult tolerances =
      test::runCli("diff --tolerances " + path("bad-tolerances.json") + " " + path("a.jsonl") +
                   " " + path("a.jsonl"));
  EXPECT_EQ(tolerances.exit_code, 2);
  EXPECT_NE(tolerances.output.find("/bodies/cloht: unknown body"), std::string::npos)
      << tolerances.output;
}

TEST_F(DiffTest, JsonReportCarriesVerdictWorstAndFields) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(100, 50));
  const Location where{3, "cloth", "velocity", 40, 2};
  const float original = parseFloat(valueText(lines, where));
  write("b.jsonl", withValue(lines, where, fmt::format("{}", original + 1.0f)));
  const test::CommandResult run =
      test::runCli("diff --json " + path("a.jsonl") + " " + path("b.jsonl") + " 2>/dev/null");
  EXPECT_EQ(run.exit_code, 1);
  const nlohmann::json report = nlohmann::json::parse(run.output);
  EXPECT_EQ(report["verdict"], "differ");
  EXPECT_EQ(report["values"]["beyond_tolerance"], 1);
  EXPECT_EQ(report["first_beyond"]["step"], 100);
  EXPECT_EQ(report["worst"]["body"], "cloth");
  EXPECT_EQ(report["worst"]["field"], "velocity");
  EXPECT_EQ(report["worst"]["particle"], 40);
  EXPECT_EQ(report["worst"]["component"], "z");
  EXPECT_EQ(report["worst"]["a"].get<double>(), double(original));
  ASSERT_EQ(report["fields"].size(), 5u);  // cloth, spheres x position, velocity; time
  EXPECT_EQ(report["fields"][1]["beyond_tolerance"], 1);
  EXPECT_EQ(report["fields"][1]["tolerance"]["mode"], "ulps");
  EXPECT_EQ(report["tolerances"]["default"]["ulps"], 0);
  // a per-body tolerance from a file shows up in the report
  std::ofstream(path("tolerances.json"))
      << R"({"bodies": {"cloth": {"velocity": {"mode": "absolute", "abs": 2}}}})";
  const test::CommandResult loose =
      test::runCli("diff --json --tolerances " + path("tolerances.json") + " " + path("a.jsonl") +
                   " " + path("b.jsonl") + " 2>/dev/null");
  EXPECT_EQ(loose.exit_code, 0) << loose.output;
  const nlohmann::json within = nlohmann::json::parse(loose.output);
  EXPECT_EQ(within["verdict"], "within_tolerance");
  EXPECT_EQ(within["tolerances"]["bodies"]["cloth"]["velocity"]["abs"], 2.0);
  EXPECT_EQ(within["fields"][1]["tolerance"]["mode"], "absolute");
  EXPECT_EQ(within["fields"][0]["tolerance"]["mode"], "ulps");
}

// Runs `clothref ARGS` with a shell's redirections of its own (REDIRECTS), stderr to `err`.
int runWithRedirects(const std::string& args, const std::string& redirects, const std::string& err,
                     std::string& stderr_text) {
  const int status =
      std::system((std::string(CLOTHREF_BIN) + " " + args + " " + redirects + " 2>" + err).c_str());
  std::ifstream in(err);
  stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Inputs that used to abort, exhaust memory or overflow the stack: one line, exit 2.
TEST_F(DiffTest, HostileHeadersAndTolerancesExitTwoWithOneLine) {
  const std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(20, 10));
  auto withHeader = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::vector<std::string> edited = lines;
    edited[0].replace(edited[0].find(from), from.size(), to);
    write(name, edited);
    return path(name);
  };
  // the first body's "particles":N (the scene object has a "particles" key of its own)
  const std::size_t first = lines[0].find("\"particles\":", lines[0].find("\"bodies\""));
  const std::string particles = lines[0].substr(first, lines[0].find('}', first) - first);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {withHeader("dt.jsonl", "\"dt\":", "\"dt\":1e400,\"x\":"), "not valid JSON"},
      {withHeader("particles.jsonl", particles, "\"particles\":1000000000000"), "--max-particles"},
      {withHeader(
           "deep.jsonl", "\"build\":",
           "\"deep\":" + std::string(100000, '[') + std::string(100000, ']') + ",\"build\":"),
       "nested deeper than 64 levels"},
  };
  for (const auto& [file, expected] : cases) {
    const test::CommandResult run = test::runCli("diff " + file + " " + file);
    EXPECT_EQ(run.exit_code, 2) << file << ": " << run.output;
    EXPECT_EQ(run.output.rfind("clothref: " + file + ":1:", 0), 0u) << run.output;
    EXPECT_NE(run.output.find(expected), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  }
  std::ofstream(path("tolerances.json")) << R"({"format": "clothref-tolerances", "version": 1,
      "default": {"mode": "absolute", "abs": 1e400}})";
  const test::CommandResult tolerances =
      test::runCli("diff --tolerances " + path("tolerances.json") + " " + path("a.jsonl") + " " +
                   path("a.jsonl"));
  EXPECT_EQ(tolerances.exit_code, 2) << tolerances.output;
  EXPECT_NE(tolerances.output.find("not valid JSON (line 2"), std::string::npos)
      << tolerances.output;
}

// A file name that is not UTF-8 is shown with U+FFFD in --json and --write-tolerances instead of
// aborting (and leaving the temporary file behind).
TEST_F(DiffTest, NonUtf8FileNamesDoNotAbortJsonOutput) {
  write("a.jsonl", smallCloth(), settings(20, 10));
  const std::string odd = path("caf\xe9.jsonl");
  fs::copy_file(path("a.jsonl"), odd);
  const test::CommandResult json = test::runCli("diff --json '" + odd + "' " + path("a.jsonl"));
  EXPECT_EQ(json.exit_code, 0) << json.output;
  EXPECT_NE(json.output.find("caf\xef\xbf\xbd.jsonl"), std::string::npos) << json.output;
  const test::CommandResult written = test::runCli("diff --write-tolerances " + path("tol.json") +
                                                   " '" + odd + "' " + path("a.jsonl"));
  EXPECT_EQ(written.exit_code, 0) << written.output;
  for (const auto& entry : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  EXPECT_TRUE(fs::exists(path("tol.json")));
}

// A hash edited on a step whose values are unchanged is a corrupt record, not "identical".
TEST_F(DiffTest, EditedHashWithUnchangedValuesIsACorruptRecord) {
  std::vector<std::string> lines = write("a.jsonl", smallCloth(), settings(20, 10));
  const std::size_t at = lines[2].find("\"hash\":\"") + 8;
  lines[2][at] = lines[2][at] == '0' ? '1' : '0';
  write("b.jsonl", lines);
  const test::CommandResult run = test::runCli("diff " + path("a.jsonl") + " " + path("b.jsonl"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_EQ(run.output.rfind("clothref: " + path("b.jsonl") + ":3: /hash: does not match", 0), 0u)
      << run.output;
}

// A report nobody received is not a success: closed stdout is exit 2 with a message.
TEST_F(DiffTest, ClosedStandardOutputIsExitTwo) {
  write("a.jsonl", smallCloth(), settings(20, 10));
  std::string err;
  EXPECT_EQ(runWithRedirects("diff " + path("a.jsonl") + " " + path("a.jsonl"), ">&-",
                             path("err.txt"), err),
            2);
  EXPECT_EQ(err, "clothref diff: standard output: write failed (closed, or the disk is full)\n");
  EXPECT_EQ(runWithRedirects("scenes", ">&-", path("err.txt"), err), 2);
  EXPECT_NE(err.find("clothref scenes: standard output: write failed"), std::string::npos) << err;
  EXPECT_EQ(runWithRedirects("scenes", ">" + path("out.txt"), path("err.txt"), err), 0) << err;
}

// "-" reads a trace from standard input; gzip-compressed traces (trace -o x.jsonl.gz) compare
// like plain ones, in a file or through a pipe.
TEST_F(DiffTest, StandardInputAndGzipTraces) {
  const std::string run = "trace --scene small-cloth --steps 30 --stride 10 -o ";
  ASSERT_EQ(test::runCli(run + path("a.jsonl")).exit_code, 0);
  ASSERT_EQ(test::runCli(run + path("a.jsonl.gz")).exit_code, 0);
  std::ifstream gz(path("a.jsonl.gz"), std::ios::binary);
  EXPECT_EQ(gz.get(), 0x1f);
  for (const std::string& args : {path("a.jsonl.gz") + " " + path("a.jsonl"),
                                  "- " + path("a.jsonl") + " < " + path("a.jsonl"),
                                  path("a.jsonl") + " - < " + path("a.jsonl.gz")}) {
    const test::CommandResult diff = test::runCli("diff " + args);
    EXPECT_EQ(diff.exit_code, 0) << args << ": " << diff.output;
    EXPECT_EQ(diff.output.rfind("identical:", 0), 0u) << diff.output;
  }
}

}  // namespace
}  // namespace clothref
