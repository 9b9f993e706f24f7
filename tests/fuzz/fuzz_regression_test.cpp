// Replays, in the normal build, every committed fuzz input through its target: the seed corpora
// (tests/fuzz/corpus/<target>/) and the inputs that once crashed (tests/fuzz/crashes/<target>/).
// A target may only return or throw InputError; the sanitizer build (CLOTHREF_SANITIZE) replays
// them under ASan and UBSan too.
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
    {"sceneJson", fuzz::sceneJson},         {"traceHeader", fuzz::traceHeader},
    {"stepLine", fuzz::stepLine},           {"toleranceFile", fuzz::toleranceFile},
    {"goldenManifest", fuzz::goldenManifest}, {"diffTwo", fuzz::diffTwo},
};

std::vector<fs::path> inputsOf(const std::string& kind, const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "fuzz" / kind / target;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  return files;
}

TEST(FuzzRegression, EveryCommittedInputIsHandled) {
  for (const Target& target : kTargets) {
    const std::vector<fs::path> corpus = inputsOf("corpus", target.name);
    EXPECT_FALSE(corpus.empty()) << target.name << ": no seed corpus";
    std::vector<fs::path> inputs = corpus;
    for (const fs::path& crash : inputsOf("crashes", target.name)) inputs.push_back(crash);
    for (const fs::path& file : inputs) {
      std::ifstream in(file, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      SCOPED_TRACE(file.string());
      EXPECT_NO_THROW(target.run(bytes));
    }
  }
}

// The step-line target's fixed header is itself valid, so the fuzzer explores step lines, not
// header errors.
TEST(FuzzRegression, StepLineHeaderIsValid) {
  std::istringstream in(std::string(fuzz::kStepLineHeader) + "\n");
  EXPECT_NO_THROW(TraceReader(in, "header"));
}

}  // namespace
}  // namespace clothref
