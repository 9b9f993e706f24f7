// The grader corpus (tests/grader/submissions) for tests that grade whole submissions: a case
// laid out as a complete submission folder, and where its files are (grade_test.cpp grades the
// cases in their own layout, src/ folders and stray copies included, and shares corpusFile).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace clothref::test {

inline const std::filesystem::path& corpusDir() {
  static const std::filesystem::path dir =
      std::filesystem::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "submissions";
  return dir;
}

// The file `name` below `dir`, preferring a src/ folder (as the grader does); empty when absent.
inline std::filesystem::path corpusFile(const std::filesystem::path& dir, const std::string& name) {
  std::vector<std::filesystem::path> found;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.path().filename() == name) found.push_back(entry.path());
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    const bool sa = a.parent_path().filename() == "src", sb = b.parent_path().filename() == "src";
    return sa != sb ? sa : a < b;
  });
  return found.empty() ? std::filesystem::path() : found.front();
}

// Corpus case `name` ("2022/force-assign") as a submission with its three files in `target`: a
// mutant that holds only its changed files is laid over its base.
inline std::filesystem::path materialiseCase(const std::string& name,
                                             const std::filesystem::path& target) {
  const std::filesystem::path case_dir = corpusDir() / name;
  std::ifstream in(case_dir / "expected.json");
  const nlohmann::json expected = nlohmann::json::parse(in);
  const std::filesystem::path base = corpusDir() / expected.value("base", name);
  std::filesystem::create_directories(target);
  for (const char* file : {"cloth.cpp", "sphere.cpp", "integrator.cpp"}) {
    const std::filesystem::path own = corpusFile(case_dir, file);
    std::filesystem::copy_file(own.empty() ? corpusFile(base, file) : own, target / file);
  }
  return target;
}

}  // namespace clothref::test
