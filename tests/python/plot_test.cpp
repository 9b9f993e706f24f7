// The Python side (tools/python/clothref): the trace reader gives back the library's numbers in
// (steps, particles, 3) arrays, and `clothref plot` writes non-trivial PNG and SVG files for a
// trace, two overlaid traces, a sweep and a stability table, on small data. Bad input: one line,
// exit 2, no file. Skipped, with a message, when python3 or matplotlib is missing.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <algorithm>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

bool pythonWithMatplotlib() {
  const std::string command =
      std::string(CLOTHREF_PYTHON) + " -c 'import matplotlib, numpy' >/dev/null 2>&1";
  return std::string(CLOTHREF_PYTHON).size() > 0 && std::system(command.c_str()) == 0;
}

class PythonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!pythonWithMatplotlib())
      GTEST_SKIP() << "python3 with matplotlib and numpy not found at '" << CLOTHREF_PYTHON
                   << "' (tools/setup.sh installs python3-matplotlib)";
    // matplotlib's cache goes to the test's own directory
    ::setenv("MPLCONFIGDIR", dir.file("mpl").c_str(), 1);
  }

  // A small trace: the 9x9 cloth and its sphere, 60 steps of 0.1 ms, every 20th recorded.
  std::string smallTrace(const std::string& name, Method method) {
    TraceSettings settings;
    settings.method = method;
    settings.precision = Precision::Float;
    settings.dt = 1e-4;
    settings.steps = 60;
    settings.stride = 20;
    const std::string path = dir.file(name);
    test::writeLines(path, test::traceLines(*findBuiltinScene("small-cloth"), settings));
    return path;
  }

  static void expectImage(const std::string& path, const char* signature, std::size_t min_size) {
    ASSERT_TRUE(fs::exists(path)) << path;
    EXPECT_GT(fs::file_size(path), min_size) << path;
    std::ifstream in(path, std::ios::binary);
    std::string head(8, '\0');
    in.read(head.data(), 8);
    EXPECT_NE(head.find(signature), std::string::npos) << path << " starts with " << head;
  }

  test::TempDir dir;
};

TEST_F(PythonTest, TraceReaderGivesBackTheLibrarysNumbers) {
  const std::string trace = smallTrace("a.jsonl", Method::Explicit);
  const std::string script =
      "import sys; sys.path.insert(0, '" CLOTHREF_PYTHON_DIR
      "');"
      "from clothref.trace import read_trace;"
      "t = read_trace(sys.argv[1]);"
      "c = t.bodies['cloth']['position'];"
      "print(c.shape, t.bodies['spheres']['velocity'].shape, t.step.tolist(), "
      "repr(float(c[3, 40, 1])))";
  const std::string command = std::string(CLOTHREF_PYTHON) + " -B -c \"" + script + "\" " + trace;
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[512] = {};
  const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, pipe);
  ASSERT_EQ(::pclose(pipe), 0);
  const std::string output(buffer, n);
  // 4 recorded steps (0, 20, 40, 60) x 81 particles x 3; one sphere
  EXPECT_NE(output.find("(4, 81, 3) (4, 1, 3) [0, 20, 40, 60]"), std::string::npos) << output;
  // the centre particle's height at step 60, as the library computes it (float widened exactly)
  World<float> world = makeWorld<float>(*findBuiltinScene("small-cloth"), Method::Explicit, 1e-4);
  for (int s = 0; s < 60; ++s) step(world);
  const double y = double(world.cloth->particles.position(1, 40));
  ASSERT_LT(y, 0.0);  // it sagged: a value the reader could not get right by accident
  EXPECT_NE(output.find(fmt::format("{}", y)), std::string::npos)
      << output << " vs " << fmt::format("{}", y);
}

TEST_F(PythonTest, EnergiesOfAKnownState) {
  // the spring scene at rest 0.2 m past its rest length: 1/2 k u^2 = 1/2 100 0.04 = 2 J; and
  // course2022's four 125 kg spheres 1 m up: 4 * 125 * 9.8 = 4900 J of gravitational energy
  TraceSettings settings;
  settings.steps = 0;
  settings.stride = 1;
  settings.dt = 1e-3;
  settings.precision = Precision::Double;
  const std::string spring = dir.file("spring.jsonl"), course = dir.file("course.jsonl");
  test::writeLines(spring, test::traceLines(*findBuiltinScene("spring"), settings));
  test::writeLines(course, test::traceLines(*findBuiltinScene("course2022"), settings));
  const std::string script =
      "import sys; sys.path.insert(0, '" CLOTHREF_PYTHON_DIR
      "');"
      "from clothref.trace import read_trace; from clothref.energy import EnergyModel;"
      "out = [];"
      "[out.append(EnergyModel(t.header['scene'], t.bodies['cloth']['position'][0]).energies("
      "{k: {f: a[0] for f, a in v.items()} for k, v in t.bodies.items()})) for t in "
      "(read_trace(p) for p in sys.argv[1:])];"
      "print('%.9f %.9f %.9f %.6f %.9f' % (out[0]['spring'], out[0]['kinetic'], "
      "out[0]['gravitational'], out[1]['gravitational'], out[1]['spring']))";
  const std::string command =
      std::string(CLOTHREF_PYTHON) + " -B -c \"" + script + "\" " + spring + " " + course;
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[256] = {};
  const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, pipe);
  ASSERT_EQ(::pclose(pipe), 0);
  EXPECT_EQ(std::string(buffer, n),
            "2.000000000 0.000000000 0.000000000 4900.000000 0.000000000\n");
}

TEST_F(PythonTest, PlotsATraceAndTwoOverlaidTraces) {
  const std::string a = smallTrace("a.jsonl", Method::Explicit);
  const std::string b = smallTrace("b.jsonl", Method::Rk4);
  const test::CommandResult one =
      test::runCli("plot " + a + " --times 0 0.006 -o " + dir.file("one"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  expectImage(dir.file("one-cloth.png"), "PNG", 20000);
  expectImage(dir.file("one-energy.png"), "PNG", 20000);
  expectImage(dir.file("one-cloth.svg"), "<?xml", 20000);
  const test::CommandResult two = test::runCli(
      "plot " + a + " " + b + " --labels ref student --formats png -o " + dir.file("two"));
  ASSERT_EQ(two.exit_code, 0) << two.output;
  expectImage(dir.file("two-cloth.png"), "PNG", 20000);
  EXPECT_FALSE(fs::exists(dir.file("two-cloth.svg")));
}

TEST_F(PythonTest, PlotsASweepAndAStabilityTable) {
  const std::string sweep = dir.file("sweep.json");
  ASSERT_EQ(test::runCli("sweep --scene spring --method explicit --method rk4 --repeats 1 "
                         "--substeps 1 --substeps 10 --substeps 40 --substeps 160 --peer --quiet "
                         "--json " +
                         sweep)
                .exit_code,
            0);
  const test::CommandResult charts =
      test::runCli("plot --sweep " + sweep + " --formats png -o " + dir.file("wp"));
  ASSERT_EQ(charts.exit_code, 0) << charts.output;
  expectImage(dir.file("wp-spring.png"), "PNG", 30000);

  const std::string stability = dir.file("stability.json");
  const test::CommandResult table =
      test::runCli("stability --scene spring-undamped --precision double --json --quiet");
  ASSERT_EQ(table.exit_code, 0) << table.output;
  std::ofstream(stability) << table.output;
  const test::CommandResult chart =
      test::runCli("plot --stability " + stability + " --formats png -o " + dir.file("st"));
  ASSERT_EQ(chart.exit_code, 0) << chart.output;
  expectImage(dir.file("st.png"), "PNG", 15000);

  // the docs table is computed from the same two files
  const std::string command = "PYTHONPATH=" CLOTHREF_PYTHON_DIR " " + std::string(CLOTHREF_PYTHON) +
                              " -B -m clothref.methods_table " + sweep + " " + stability;
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string markdown;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    markdown.append(buffer, n);
  ASSERT_EQ(::pclose(pipe), 0) << markdown;
  // the observed orders on the spring, from the sweep: 4 for rk4, 1 for explicit (+- 0.2)
  const auto order = [&markdown](const std::string& method) {
    const std::size_t at = markdown.find("| " + method + " | ");
    return at == std::string::npos ? -1.0 : std::stod(markdown.substr(at + method.size() + 5));
  };
  EXPECT_NEAR(order("rk4"), 4.0, 0.2) << markdown;
  EXPECT_NEAR(order("explicit"), 1.0, 0.2) << markdown;
  // the odeint peer's points (--peer) are charted, not tabled
  EXPECT_EQ(markdown.find("odeint"), std::string::npos) << markdown;
}

// Runs `python3 -B -c SCRIPT ARGS` with the project's package importable; stdout and the status.
test::CommandResult runScript(const std::string& script, const std::string& args) {
  const std::string command = "PYTHONPATH=" CLOTHREF_PYTHON_DIR " MPLBACKEND=Agg " +
                              std::string(CLOTHREF_PYTHON) + " -B -c \"" + script + "\" " + args;
  test::CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST_F(PythonTest, ReaderAndPlotReadGzipAndStandardInput) {
  const std::string plain = smallTrace("a.jsonl", Method::Explicit);
  const std::string packed = dir.file("a.jsonl.gz");
  ASSERT_EQ(std::system(("gzip -c " + plain + " > " + packed).c_str()), 0);
  // the same numbers from the file, its gzip, and the gzip piped in (read twice: kept)
  const std::string script =
      "import sys; from clothref.trace import read_trace;"
      "t = [read_trace(p) for p in sys.argv[1:]];"
      "print(all((x.bodies['cloth']['position'] == t[0].bodies['cloth']['position']).all() "
      "for x in t), [x.step.tolist() for x in t][2])";
  const auto read = runScript(script, plain + " " + packed + " - - < " + packed);
  ASSERT_EQ(read.exit_code, 0) << read.output;
  EXPECT_EQ(read.output, "True [0, 20, 40, 60]\n");
  const auto plotted =
      test::runCli("plot - --times 0 0.006 --formats png -o " + dir.file("in") + " < " + packed);
  ASSERT_EQ(plotted.exit_code, 0) << plotted.output;
  expectImage(dir.file("in-cloth.png"), "PNG", 20000);
  // a cut gzip stream is one line naming the file
  test::writeText(dir.file("cut.jsonl.gz"), test::readText(packed).substr(0, 300));
  const auto cut = test::runCli("plot " + dir.file("cut.jsonl.gz") + " -o " + dir.file("cut"));
  EXPECT_EQ(cut.exit_code, 2) << cut.output;
  EXPECT_NE(cut.output.find("cut.jsonl.gz"), std::string::npos) << cut.output;
  EXPECT_EQ(std::count(cut.output.begin(), cut.output.end(), '\n'), 1) << cut.output;
}

TEST_F(PythonTest, ClothPanelsShareLimitsAndTwoTracesGetADifferencePanel) {
  const std::string a = smallTrace("a.jsonl", Method::Explicit);
  const std::string b = smallTrace("b.jsonl", Method::Rk4);
  // the figures plot_traces makes, caught before they are saved
  const std::string script =
      "import sys; import numpy as np; import clothref.plot as p; figures = {};"
      "p.save = lambda f, prefix, suffix, formats: figures.setdefault(suffix, f) and [];"
      "p.main(['trace'] + sys.argv[1:] + ['--times', '0', '0.003', '0.006', '-o', 'x']);"
      "axes = figures['-cloth'].axes;"
      "cloth = [x for x in axes if x.name == '3d']; flat = [x for x in axes if x.name != '3d'];"
      "print(len(cloth), len(set((x.get_xlim(), x.get_ylim(), x.get_zlim()) for x in cloth)), "
      "len(flat), flat[0].get_yscale() if flat else '', "
      "bool(np.nanmax(flat[0].lines[0].get_ydata()) > 0) if flat else '')";
  const auto two = runScript(script, a + " " + b);
  ASSERT_EQ(two.exit_code, 0) << two.output;
  // three 3-D panels with one set of limits, and the log-scale difference panel with a difference
  EXPECT_EQ(two.output, "3 1 1 log True\n");
  const auto one = runScript(script, a);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_EQ(one.output, "3 1 0  \n");
}

TEST_F(PythonTest, BadInputIsOneLineExitTwoAndNoFile) {
  std::ofstream(dir.file("bad.jsonl")) << "{\"format\": \"something-else\"}\n";
  std::ofstream(dir.file("bad.json")) << "[1, 2]\n";
  for (const std::string& args :
       {"plot " + dir.file("bad.jsonl") + " -o " + dir.file("out"),
        "plot " + dir.file("missing.jsonl") + " -o " + dir.file("out"),
        "plot --sweep " + dir.file("bad.json") + " -o " + dir.file("out"),
        "plot --stability " + dir.file("bad.jsonl") + " -o " + dir.file("out"),
        std::string("plot -o ") + dir.file("out")}) {
    const test::CommandResult result = test::runCli(args);
    EXPECT_EQ(result.exit_code, 2) << args << ": " << result.output;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1)
        << args << ": " << result.output;
  }
  for (const auto& entry : fs::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().rfind("out", 0), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace clothref
