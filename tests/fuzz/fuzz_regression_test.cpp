// Replays, in the normal build, every committed fuzz input through its target: the seed corpora
// (tests/fuzz/corpus/<target>/) and the inputs that once crashed (tests/fuzz/crashes/<target>/).
// A target may only return or throw InputError; the sanitizer build (CLOTHREF_SANITIZE) replays
// them under ASan and UBSan too.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz/fuzz_targets.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

struct Target {
  const char* name;
  std::function<void(std::string_view)> run;
};

const Target kTargets[] = {
    {"sceneJson", fuzz::sceneJson},
    {"traceHeader", fuzz::traceHeader},
    {"stepLine", fuzz::stepLine},
    {"toleranceFile", fuzz::toleranceFile},
    {"goldenManifest", fuzz::goldenManifest},
    {"diffTwo", fuzz::diffTwo},
    {"rubric", fuzz::rubric},
    {"fileFinder", fuzz::fileFinder},
    {"gzipTrace", fuzz::gzipTrace},
};

std::vector<fs::path> inputsOf(const std::string& kind, const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "fuzz" / kind / target;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  return files;
}

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The seeds are valid inputs: each target reads them without an error.
TEST(FuzzRegression, SeedCorporaAreValidInputs) {
  for (const Target& target : kTargets) {
    const std::vector<fs::path> corpus = inputsOf("corpus", target.name);
    EXPECT_FALSE(corpus.empty()) << target.name << ": no seed corpus";
    for (const fs::path& file : corpus) {
      try {
        target.run(bytesOf(file));
      } catch (const InputError& error) {
        ADD_FAILURE() << file << ": " << error.what();
      }
    }
  }
}

// Inputs that once crashed a target now end, at worst, in an InputError.
TEST(FuzzRegression, CrashInputsEndInAnInputErrorAtWorst) {
  for (const Target& target : kTargets) {
    for (const fs::path& file : inputsOf("crashes", target.name)) {
      SCOPED_TRACE(file.string());
      try {
        target.run(bytesOf(file));
      } catch (const InputError&) {
      }
    }
  }
}

// The step-line target's fixed header is itself valid, so the fuzzer explores step lines, not
// header errors.
TEST(FuzzRegression, StepLineHeaderIsValid) {
  std::istringstream in(std::string(fuzz::kStepLineHeader) + "\n");
  EXPECT_NO_THROW(TraceReader(in, "header"));
}

// The fileFinder harness builds its tree without following a link: a described link to a folder
// outside the scratch folder, then a file and a folder under that link, leave the outside folder
// empty (the harness used to write through links, as root). The FIFO case of the same harness is
// tests/fuzz/crashes/fileFinder/fifo-then-file.txt (it blocked in open until an alarm).
TEST(FuzzRegression, FileFinderNeverWritesThroughALink) {
  char outside[] = "/tmp/clothref-fuzz-outside-XXXXXX";
  ASSERT_NE(mkdtemp(outside), nullptr);
  fuzz::fileFinder(std::string("l out\t") + outside + "\nf out/escaped.cpp\tx\nd out/made\n" +
                   "l deep/link\t" + outside + "\nf deep/link/cloth.cpp\ty\n");
  std::error_code error;
  EXPECT_TRUE(fs::is_empty(outside, error)) << outside;
  fs::remove_all(outside, error);
}

}  // namespace
}  // namespace clothref
