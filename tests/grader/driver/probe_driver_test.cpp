// The probe driver (driver/probe_driver.cpp) from the outside, linked with our reference files: it
// serves every group of the protocol's list, and refuses what it does not know (an unknown group,
// a method that is not one of the course's integrators) with exit 70 and the reason on stderr,
// never with another group's or another integrator's answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "clothref/core/method.h"
#include "grader/bridge/probe_keys.h"
#include "grader/grade/probes/integrate/systems.h"
#include "grader/grade/run/build.h"
#include "grader/grade/run/child_process.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace key = probe::key;

class ProbeDriver : public ::testing::Test {
 protected:
  // One probe of the 2022 reference files for the suite (their objects are prebuilt: a link).
  static void SetUpTestSuite() {
    work_ = new test::TempDir();
    const CourseToolchain toolchain = defaultToolchain();
    SubmissionFiles files;
    for (const char* name : {"cloth.cpp", "sphere.cpp", "integrator.cpp"}) {
      files.found[name] = toolchain.reference_dir / "2022" / name;
      files.bytes[name] = test::readText(files.found[name]);
    }
    build_ = new ProbeBuild(buildProbes(files, 2022, toolchain, work_->path() / "build"));
  }
  static void TearDownTestSuite() {
    delete build_;
    delete work_;
  }

  // `request` answered by the probe, in a fresh folder.
  static ChildRun ask(const probe::ProbeMessage& request) {
    const std::filesystem::path dir = work_->path() / ("run-" + std::to_string(runs_++));
    std::filesystem::create_directories(dir);
    return runProbe(build_->probe, request, dir, ChildLimits{});
  }
  static probe::ProbeMessage request(const std::string& group) {
    probe::ProbeMessage message;
    message.texts[key::kGroup] = group;
    message.ints[key::kCases] = {0};
    message.floats[key::kSpringCoef] = {1};
    message.floats[key::kDamperCoef] = {0};
    message.ints[key::kSteps] = {1};
    message.ints[key::kStride] = {1};
    return message;
  }
  static probe::ProbeMessage withMethod(const std::string& group, std::int64_t row) {
    probe::ProbeMessage message = request(group);
    message.ints[key::kMethod] = {row};
    return message;
  }

  static inline test::TempDir* work_ = nullptr;
  static inline ProbeBuild* build_ = nullptr;
  static inline int runs_ = 0;
};

TEST_F(ProbeDriver, ServesEveryGroupOfTheProtocol) {
  ASSERT_TRUE(build_->ok) << build_->problem;
  for (const probe::Name& group : probe::group::kAll) {
    const ChildRun run = ask(withMethod(group.text, 0));
    ASSERT_EQ(run.status, ChildStatus::Ok) << group.text << ": " << run.describe() << "\n"
                                           << run.stderr_head;
    EXPECT_EQ(run.answer->text(key::kGroup), group.text);
  }
}

TEST_F(ProbeDriver, RefusesAnUnknownGroup) {
  ASSERT_TRUE(build_->ok) << build_->problem;
  for (const std::string name : {"no-such-group", ""}) {
    const ChildRun run = ask(request(name));
    EXPECT_EQ(run.status, ChildStatus::ExitedNonZero) << name;
    EXPECT_EQ(run.exit_code, 70) << name;
    EXPECT_NE(run.stderr_head.find("unknown group '" + name + "'"), std::string::npos)
        << run.stderr_head;
    EXPECT_FALSE(run.answer);
  }
}

// key::kMethod is a row of clothref's method table: each course row is served, a textbook row
// or a number outside the table is refused, in both groups that integrate.
TEST_F(ProbeDriver, ServesTheCoursesIntegratorsAndRefusesEveryOtherMethod) {
  ASSERT_TRUE(build_->ok) << build_->problem;
  const std::int64_t rows = static_cast<std::int64_t>(kMethods.size());
  for (const char* group : {probe::group::kIntegrate, probe::group::kWholeRun})
    for (std::int64_t row = -1; row <= rows; ++row) {
      const bool course = row >= 0 && row < rows &&
                          kMethods[static_cast<std::size_t>(row)].origin == MethodOrigin::Course;
      const ChildRun run = ask(withMethod(group, row));
      if (course) {
        EXPECT_EQ(run.status, ChildStatus::Ok) << group << " " << row << ": " << run.stderr_head;
        continue;
      }
      EXPECT_EQ(run.status, ChildStatus::ExitedNonZero) << group << " " << row;
      EXPECT_EQ(run.exit_code, 70) << group << " " << row;
      const bool listed = row >= 0 && row < rows;
      EXPECT_NE(run.stderr_head.find(listed ? "is not one of the course's integrators"
                                            : "in the method table"),
                std::string::npos)
          << group << " " << row << ": " << run.stderr_head;
    }
}

// The driver's own simulateOneStep (MiniWorld: the course's loops around the library's formulas,
// its constants from the request) beside the reference integrator is the library's step, bit for
// bit: one step of a random state with contacts, and of the course's cloth, every course method,
// against clothref's simulateOneStep and integrate() on the same state.
TEST_F(ProbeDriver, TheDriversSimulateIsTheLibrarys) {
  ASSERT_TRUE(build_->ok) << build_->problem;
  const std::vector<integrators::System> systems = {integrators::randomSystem(20221, 2022),
                                                    integrators::courseSystem(20221, 2022)};
  const auto same = [](const Mat4X<float>& a, const Mat4X<float>& b) {
    return a.cols() == b.cols() &&
           std::equal(a.data(), a.data() + a.size(), b.data(),
                      [](float x, float y) { return test::bits(x) == test::bits(y); });
  };
  for (int index = 0; index < 4; ++index) {
    probe::ProbeMessage message = withMethod(probe::group::kIntegrate, index);
    message.ints[key::kCases] = {static_cast<std::int64_t>(systems.size())};
    for (std::size_t k = 0; k < systems.size(); ++k)
      integrators::addSystem(message, int(k), systems[k], 1, 0);
    const ChildRun run = ask(message);
    ASSERT_EQ(run.status, ChildStatus::Ok) << run.describe() << "\n" << run.stderr_head;
    const Method method = integrators::integratorMethod(index);
    for (std::size_t k = 0; k < systems.size(); ++k) {
      const integrators::System driver = integrators::answerSystem(*run.answer, int(k), systems[k]);
      const integrators::System library =
          integrators::stepped(systems[k], integrators::clothrefStep(method));
      SCOPED_TRACE(std::string(methodName(method)) + ", system " + std::to_string(k));
      EXPECT_TRUE(same(driver.cloth.particles.position, library.cloth.particles.position));
      EXPECT_TRUE(same(driver.cloth.particles.velocity, library.cloth.particles.velocity));
      EXPECT_TRUE(same(driver.spheres.particles.position, library.spheres.particles.position));
      EXPECT_TRUE(same(driver.spheres.particles.velocity, library.spheres.particles.velocity));
    }
  }
}

// No clothref symbol of the driver is global in the course libraries: a student file that declares
// one by hand (our formulas carry the answer) finds nothing to link to.
TEST(CourseLibrary, HoldsNoGlobalClothrefSymbol) {
  const CourseToolchain toolchain = defaultToolchain();
  for (const char* edition : {"2022", "2024"}) {
    const std::filesystem::path library =
        toolchain.driver_lib_dir / ("libclothref_grader_course_" + std::string(edition) + ".a");
    ASSERT_TRUE(std::filesystem::exists(library)) << library;
    const std::string command = "nm -g --defined-only '" + library.string() + "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    ASSERT_TRUE(pipe);
    std::string symbols;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      symbols.append(buffer, n);
    ASSERT_EQ(::pclose(pipe), 0) << symbols;
    EXPECT_NE(symbols.find("main"), std::string::npos) << symbols;  // nm read the driver
    EXPECT_EQ(symbols.find("_ZN8clothref"), std::string::npos) << symbols;
  }
}

}  // namespace
}  // namespace clothref::grader
