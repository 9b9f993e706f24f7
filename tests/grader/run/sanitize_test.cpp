// The sanitizer run (grader/grade/run/sanitize.h): finding and cleaning the first sanitizer
// report, and the corpus mutant whose `auto` Eigen expression dangles, rebuilt with ASan by
// itself, quoted in its report.
#include "grader/grade/run/sanitize.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "corpus.h"
#include "grader/bridge/probe_keys.h"
#include "grader/grade/run/sandbox.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;
using test::readText;
using test::runCli;
using test::TempDir;

int countLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(FirstReport, StartsAtTheErrorLineCutsPathsAndPidsAndStopsAtTheLimit) {
  // The shape of an ASan report, with a scratch path and a process id that must not be quoted.
  std::string log = "probe: starting\n";
  log += "=================================================================\n";
  log += "==4242==ERROR: AddressSanitizer: stack-use-after-scope on address 0x7ffc00 at pc 0x55\n";
  log += "READ of size 16 at 0x7ffc00 thread T0\n";
  for (int k = 0; k < 20; ++k)
    log += "    #" + std::to_string(k) +
           " 0x55 in Cloth::computeSpringForce() /tmp/clothref-grade-Xy12/src-cloth/cloth.cpp:" +
           std::to_string(180 + k) + "\n";
  const std::string quote = firstSanitizerReport(log, 6);
  EXPECT_EQ(countLines(quote), 6) << quote;
  EXPECT_EQ(quote.rfind("==ERROR: AddressSanitizer: stack-use-after-scope", 0), 0u) << quote;
  EXPECT_NE(quote.find("in Cloth::computeSpringForce() cloth.cpp:180\n"), std::string::npos)
      << quote;
  EXPECT_EQ(quote.find("/tmp/"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("4242"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("probe: starting"), std::string::npos) << quote;
}

TEST(FirstReport, AddressesAreNotQuotedSoTwoRunsQuoteTheSameText) {
  // Two runs of one crash differ only in their addresses (address-space layout).
  const auto report = [](const std::string& address, const std::string& pc) {
    return "==1==ERROR: AddressSanitizer: stack-use-after-scope on address " + address + " at pc " +
           pc + "\n    #16 " + pc +
           " in Cloth::computeSpringForce() /tmp/clothref-grade-a/src-cloth/cloth.cpp:194\n";
  };
  const std::string first = firstSanitizerReport(report("0x7ffc985ec210", "0x56368fed9830"), 6);
  const std::string second = firstSanitizerReport(report("0x7fff319fb350", "0x55cee057c830"), 6);
  EXPECT_EQ(first, second);
  EXPECT_NE(first.find("on address 0x... at pc 0x..."), std::string::npos) << first;
  EXPECT_EQ(first.find("7ffc"), std::string::npos) << first;
}

TEST(FirstReport, FramesOutsideTheStudentsFilesAndTheFramesObjectsAreSummarised) {
  std::string log = "==7==ERROR: AddressSanitizer: heap-use-after-free on address 0x6020\n";
  log += "READ of size 4 at 0x6020 thread T0\n";
  for (int k = 0; k < 3; ++k)
    log += "    #" + std::to_string(k) + " 0x55 in Eigen::f() /usr/include/eigen3/Eigen/x.h:1\n";
  log += "    #3 0x55 in Spheres::collide() /tmp/clothref-grade-q/src-sphere/sphere.cpp:40\n";
  log += "    #4 0x55 in main (/tmp/clothref-grade-q/probe+0x1)\n\n";
  log += "  This frame has 3 object(s):\n    [32, 48) 'a'\n";
  log += "    [64, 80) 'b' <== Memory access at offset 64 is inside this variable\n";
  EXPECT_EQ(firstSanitizerReport(log),
            "==ERROR: AddressSanitizer: heap-use-after-free on address 0x6020\n"
            "READ of size 4 at 0x6020 thread T0\n"
            "    ... (3 frames outside the student's files)\n"
            "    #3 0x55 in Spheres::collide() sphere.cpp:40\n"
            "    ... (1 frame outside the student's files)\n"
            "  This frame has 3 object(s):\n"
            "    [64, 80) 'b' <== Memory access at offset 64 is inside this variable\n");
}

TEST(FirstReport, FindsUndefinedBehaviourAndNothingInCleanOutput) {
  const std::string ubsan =
      "hello\n/tmp/clothref-grade-ab/src-integrator/integrator.cpp:12:9: runtime error: signed "
      "integer overflow: 2147483647 + 1 cannot be represented in type 'int'\n";
  EXPECT_EQ(firstSanitizerReport(ubsan),
            "integrator.cpp:12:9: runtime error: signed integer overflow: 2147483647 + 1 cannot be "
            "represented in type 'int'\n");
  EXPECT_EQ(firstSanitizerReport("all tests passed\nSegmentation fault\n"), "");
}

// No host path in a quote: a line that names a file outside the student's (the course kit's
// header in a SUMMARY line, the probe executable) shows its file name only (issue 36: in the
// fallback the quoted line showed the host's scratch path).
TEST(FirstReport, NoHostPathIsQuoted) {
  std::string log = "==7==ERROR: AddressSanitizer: heap-use-after-free on address 0x6020\n";
  log += "    #0 0x55 in Cloth::~Cloth() /tmp/clothref-kit-12-Ab/course/2022/include/cloth.h:30\n";
  log += "    #1 0x55 in Cloth::computeSpringForce() /tmp/clothref-grade-q/src-cloth/cloth.cpp:9\n";
  log +=
      "SUMMARY: AddressSanitizer: heap-use-after-free "
      "/tmp/clothref-kit-12-Ab/course/2022/include/cloth.h:30 in Cloth::~Cloth()\n";
  const std::string quote = firstSanitizerReport(log);
  EXPECT_EQ(quote.find("/tmp/"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("clothref-kit"), std::string::npos) << quote;
  EXPECT_NE(quote.find("cloth.cpp:9"), std::string::npos) << quote;
}

// The sanitizer run has every limit a probe run has (issue 36: it had no memory limit at all):
// the same processes, files and disk, its time scaled, a memory limit in place of the address
// space the sanitizers cannot live with, ASan's shadow memory counted in it.
TEST(SanitizerRun, HasEveryLimitOfAProbeRun) {
  const ChildLimits probe = limitsForTimeout(20);
  const ChildLimits limits = sanitizerLimits(probe);
  EXPECT_EQ(limits.processes, probe.processes);
  EXPECT_EQ(limits.open_files, probe.open_files);
  EXPECT_EQ(limits.file_size_bytes, probe.file_size_bytes);
  EXPECT_EQ(limits.disk_bytes, probe.disk_bytes);
  EXPECT_FALSE(limits.keep_files);
  EXPECT_TRUE(limits.sanitizer_channel);
  EXPECT_EQ(limits.wall_seconds, 3 * probe.wall_seconds);
  EXPECT_EQ(limits.cpu_seconds, 3 * probe.cpu_seconds);
  EXPECT_EQ(limits.memory_bytes,
            probe.address_space_bytes + probe.address_space_bytes / 8 + kSanitizerRuntimeBytes);
  // A run waiting for the uid's process slots waits out this run: the probe's wait is as long.
  EXPECT_GE(slotWait(probe), limits.wall_seconds + 2);
  EXPECT_EQ(slotWait(limits), slotWait(probe));
  bool hard_rss = false;
  for (const std::string& variable : limits.environment)
    hard_rss = hard_rss ||
               variable.find("hard_rss_limit_mb=" + std::to_string(limits.memory_bytes >> 20)) !=
                   std::string::npos;
  EXPECT_TRUE(hard_rss);
}

// A report with no line in the student's files is not the student's (issue 36): the instrumented
// run of a student cloth.cpp reports a heap-buffer-overflow in the framework's Cloth::~Cloth()
// (the instrumented constructor allocates with Eigen's own aligned malloc, the uninstrumented
// destructor frees with free), which was quoted as the student's crash.
TEST(FirstReport, AReportOutsideTheStudentsFilesIsNotTheirs) {
  std::string log = "==2==ERROR: AddressSanitizer: heap-buffer-overflow on address 0x6020\n";
  log += "READ of size 8 at 0x6020 thread T0\n";
  log += "    #0 0x55 in free (/usr/lib/x86_64-linux-gnu/libasan.so.8+0xd7ae8)\n";
  log += "    #1 0x55 in Cloth::~Cloth() (/tmp/clothref-grade-q/bin/probe-sanitize+0x1)\n";
  log += "0x6020 is located 8 bytes to the left of 10000-byte region [0x6028,0x8738)\n";
  log += "allocated by thread T0 here:\n";
  log += "    #0 0x55 in malloc (/usr/lib/x86_64-linux-gnu/libasan.so.8+0xd8a1f)\n";
  log +=
      "SUMMARY: AddressSanitizer: heap-buffer-overflow "
      "(/tmp/clothref-grade-q/bin/probe-sanitize+0x1) "
      "in Cloth::~Cloth()\n";
  EXPECT_EQ(firstSanitizerReport(log), "");
  // the same report with a frame in the student's cloth.cpp is theirs
  log.insert(
      log.find("0x6020 is located"),
      "    #2 0x55 in Cloth::computeSpringForce() /tmp/clothref-grade-q/src-cloth/cloth.cpp:9\n");
  EXPECT_NE(firstSanitizerReport(log).find("cloth.cpp:9"), std::string::npos);
}

// An overflow the sanitizers report, at a line of the student's cloth.cpp.
const char* kOverflow =
    "static int overflow() {\n"
    "  volatile int size = 4;  // unknown to UBSan's object-size check: ASan reports it\n"
    "  int *block = new int[size];\n"
    "  volatile int past = 4;\n"
    "  block[past] = 1;\n"
    "  return block[0];\n"
    "}\n";

// What the instrumented build of SanitizerRun's cloth.cpp does first (a static initialiser, before
// the driver reads its request), chosen by the request's text (read from stdin), so that one
// instrumented build serves every test: "MODE=memory" touches 1.5 GiB, "MODE=files" writes 24 MiB
// into its folder, "MODE=forged" prints a report of its own making to stderr; then each overflows
// a buffer.
const char* kAttacks =
    "#if defined(__SANITIZE_ADDRESS__)\n"
    "static const int attack = [] {\n"
    "  std::string request;\n"
    "  char buffer[4096];\n"
    "  for (ssize_t n; (n = read(0, buffer, sizeof buffer)) > 0;) request.append(buffer, n);\n"
    "  if (request.find(\"MODE=memory\") != std::string::npos) {\n"
    "    std::vector<char *> blocks;\n"
    "    for (int k = 0; k < 24; ++k) {\n"
    "      blocks.push_back(static_cast<char *>(std::malloc(64 << 20)));\n"
    "      if (blocks.back()) std::memset(blocks.back(), 1, 64 << 20);\n"
    "    }\n"
    "  } else if (request.find(\"MODE=files\") != std::string::npos) {\n"
    "    std::vector<char> block(1 << 20, 'x');\n"
    "    if (std::FILE *file = std::fopen(\"sanitizer-leftover\", \"wb\")) {\n"
    "      for (int k = 0; k < 24; ++k) std::fwrite(block.data(), 1, block.size(), file);\n"
    "      std::fclose(file);\n"
    "    }\n"
    "  } else if (request.find(\"MODE=forged\") != std::string::npos) {\n"
    "    std::fputs(\"==1==ERROR: AddressSanitizer: heap-buffer-overflow on address 0x6020\\n\"\n"
    "               \"    #0 0x55 in main probe_driver.cpp:88\\n\"\n"
    "               \"SUMMARY: AddressSanitizer: heap-buffer-overflow probe_driver.cpp:88 in main "
    "\"\n"
    "               \"(a fault of the grader)\\n\", stderr);\n"
    "    for (int k = 0; k < 10; ++k) std::fputs(\"    #1 0x55 in padding\\n\", stderr);\n"
    "    std::fflush(stderr);\n"
    "  }\n"
    "  return overflow();\n"
    "}();\n"
    "#endif\n";

// The sanitizer run as a grade makes it (grade.cpp): this grade's isolation and uids, the course
// kit, a scratch folder, the reference's cloth.cpp with kOverflow and kAttacks added.
struct SanitizerRun {
  TempDir temp;
  Isolation isolation = detectIsolation();
  UidLease lease;
  std::unique_ptr<GradeScratch> scratch;
  CourseToolchain toolchain = defaultToolchain();
  SubmissionFiles files;
  ChildLimits limits;
  ProbeBuild base;
  std::unique_ptr<SanitizedProbes> sanitizer;

  explicit SanitizerRun(std::uint64_t address_space = 4ull << 30) {
    if (isolation.uid >= 0) {
      lease = leaseUids();
      isolation.uid = lease.uid;
      isolation.tool_uid = lease.tool_uid;
      isolation.uid_lease = lease.hold;
    }
    isolation.ours = ourFolders(toolchain);
    const fs::path submission = test::materialiseCase("2022/reference", temp.path() / "submission");
    const fs::path cloth = submission / "cloth.cpp";
    test::writeText(cloth, readText(cloth) +
                               "\n#include <unistd.h>\n\n#include <cstdio>\n#include <cstdlib>\n"
                               "#include <cstring>\n#include <string>\n#include <vector>\n" +
                               kOverflow + kAttacks);
    files = findSubmissionFiles(submission);
    scratch = std::make_unique<GradeScratch>(isolation.uid, isolation.tool_uid);
    toolchain.cache_dir = CLOTHREF_GRADER_CACHE;  // the instrumented objects are built once
    toolchain.isolation = isolation;
    if (isolation.kind != IsolationKind::None) {
      const CourseKit& kit = courseKit(toolchain.course_dir, toolchain.driver_lib_dir);
      toolchain.course_dir = kit.course_dir;
      toolchain.driver_lib_dir = kit.lib_dir;
      toolchain.kit = &kit;
    }
    limits = limitsForTimeout(20);
    limits.isolation = isolation;
    limits.address_space_bytes = address_space;
    // the grade's own build, whose objects of the files not rebuilt the instrumented probe takes
    base = buildProbes(files, 2022, toolchain, scratch->build());
    sanitizer = std::make_unique<SanitizedProbes>(files, 2022, toolchain, *scratch, limits, base);
  }
  // The quote of one run in `mode`, in `folder` below the scratch's probes folder; `group` a
  // probe group's name, or (by default) text no group has, whose run all three files make.
  std::string explain(const std::string& mode, const fs::path& folder,
                      const std::string& group = "") {
    probe::ProbeMessage request;
    request.texts[probe::key::kGroup] = group.empty() ? "forces MODE=" + mode : group;
    return sanitizer->explain(request, scratch->probes() / folder);
  }
  // What the run left to read when a quote is not the one expected (its stderr's start).
  std::string said(const fs::path& folder) const {
    return readText(scratch->probes() / folder / "child.stderr").substr(0, 2000);
  }
};

// The sanitizer run has a memory limit like every run (issue 36: it had none; student code
// touched 5 GiB in it): here a probe limited to 256 MiB of address space touches 1.5 GiB in its
// instrumented build, and would then overflow a buffer. Stopped first, nothing is reported; the
// same build without the memory reports the overflow.
TEST(SanitizerRun, HasAMemoryLimit) {
  SanitizerRun run(256ull << 20);
  const std::string quote = run.explain("memory", "memory");
  EXPECT_EQ(quote.find("heap-buffer-overflow"), std::string::npos)
      << "the instrumented run touched 1.5 GiB unhindered:\n"
      << quote;
  EXPECT_NE(run.explain("none", "none").find("heap-buffer-overflow"), std::string::npos)
      << run.said("none");
}

// What the sanitizer run wrote goes with it, as any run's (issue 36: it was kept until the grade
// ended, and the next run's disk limit did not count it).
TEST(SanitizerRun, LeavesNoFilesBehind) {
  SanitizerRun run;
  const std::string quote = run.explain("files", "files");
  EXPECT_NE(quote.find("heap-buffer-overflow"), std::string::npos) << quote << run.said("files");
  std::uintmax_t left = 0;
  std::error_code error;
  for (auto it = fs::recursive_directory_iterator(run.scratch->probes() / "files", error);
       it != fs::recursive_directory_iterator(); it.increment(error))
    if (it->is_regular_file(error)) left += it->file_size(error);
  EXPECT_LE(left, 3u * (64u << 10)) << "the sanitizer run's files outlived it";
}

// The report is read from the sanitizers' own channel: text the student prints to stderr, shaped
// like a report and padded, is never quoted as one (issue 36: it was, "... probe_driver.cpp:88
// (a fault of the grader)").
TEST(SanitizerRun, AReportPrintedByTheStudentIsNotQuoted) {
  SanitizerRun run;
  const std::string quote = run.explain("forged", "forged");
  EXPECT_EQ(quote.find("fault of the grader"), std::string::npos) << quote;
  EXPECT_NE(quote.find("heap-buffer-overflow"), std::string::npos) << quote;
  EXPECT_NE(quote.find("cloth.cpp:"), std::string::npos) << quote;
}

// A crash in a group that runs only cloth.cpp rebuilds cloth.cpp alone (issue 39: all three files
// were rebuilt, most of a crashing grade's time): the report still names its line, the set's
// folder holds no other student file, and the other files are the grade's own objects. The
// whole run's set, asked next, compiles the two others in a folder of its own and reuses cloth.o.
TEST(SanitizerRun, AGroupRebuildsOnlyTheFilesItRuns) {
  SanitizerRun run;
  ASSERT_TRUE(run.base.ok) << run.base.problem;
  const std::string quote = run.explain("none", "springs", probe::group::kSprings);
  EXPECT_NE(quote.find("cloth.cpp:"), std::string::npos) << quote << run.said("springs");
  const fs::path set = run.scratch->root() / "sanitize-probe-cloth";
  EXPECT_TRUE(fs::exists(set / "src-cloth" / "cloth.cpp"));
  for (const char* other : {"src-sphere", "src-integrator"})
    EXPECT_FALSE(fs::exists(set / other)) << other << " was compiled again for a cloth crash";
  for (const char* base : {"sphere-base.o", "integrator-base.o"})
    EXPECT_TRUE(fs::exists(set / base)) << base;
  const std::string whole = run.explain("none", "whole", probe::group::kWholeRun);
  EXPECT_NE(whole.find("cloth.cpp:"), std::string::npos) << whole << run.said("whole");
  const fs::path all = run.scratch->root() / "sanitize-probe-cloth-sphere-integrator";
  EXPECT_TRUE(fs::exists(all / "src-sphere" / "sphere.cpp"));
  EXPECT_FALSE(fs::exists(all / "src-cloth")) << "cloth.cpp was compiled twice";
}

// Only the run that crashed is quoted: a report the instrumented run makes at exit, after the
// probe answered (here a static object's destructor), is not the crash being explained (issue 36:
// such a report from Cloth::~Cloth() was quoted as the student's, and in the fallback with the
// host's scratch path). The -O2 build crashes in computeSpringForce; the instrumented one does not.
class AtExit : public ::testing::TestWithParam<const char*> {};

TEST_P(AtExit, AReportAfterTheAnswerIsNotTheCrash) {
  const std::string isolation = GetParam();
  if (isolation == "rlimits" && geteuid() != 0) GTEST_SKIP() << "the fallback needs root";
  TempDir temp;
  const fs::path submission = test::materialiseCase("2022/reference", temp.path() / "submission");
  const fs::path cloth = submission / "cloth.cpp";
  std::string text = readText(cloth);
  const std::string head = "void Cloth::computeSpringForce() {\n";
  ASSERT_NE(text.find(head), std::string::npos);
  text.replace(text.find(head), head.size(),
               head +
                   "#if !defined(__SANITIZE_ADDRESS__)\n"
                   "  { volatile int *nowhere = nullptr; *nowhere = 1; }\n#endif\n");
  text += std::string("\n") + kOverflow +
          "#if defined(__SANITIZE_ADDRESS__)\n"
          "struct AtExitOverflow {\n  ~AtExitOverflow() { overflow(); }\n} at_exit_overflow;\n"
          "#endif\n";
  test::writeText(cloth, text);
  setenv("CLOTHREF_GRADER_ISOLATION", isolation.c_str(), 1);
  const auto run = runCli(
      "grade '" + submission.string() + "' --no-whole-run --timeout 20 --cache-dir '" +
      std::string(CLOTHREF_GRADER_CACHE) + "' --results '" + temp.file("results.json") + "'");
  unsetenv("CLOTHREF_GRADER_ISOLATION");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string results = readText(temp.file("results.json"));
  EXPECT_NE(results.find("crashed"), std::string::npos);
  EXPECT_EQ(results.find("heap-buffer-overflow"), std::string::npos) << results.substr(0, 4000);
  // no path of the grader's (its scratch folder, the course kit) in what the student reads
  for (const char* ours : {"clothref-grade-", "clothref-kit-", "/bin/probe"})
    EXPECT_EQ(results.find(ours), std::string::npos) << ours << results.substr(0, 4000);
}

INSTANTIATE_TEST_SUITE_P(Isolations, AtExit, ::testing::Values("auto", "rlimits"));

}  // namespace
}  // namespace clothref::grader
