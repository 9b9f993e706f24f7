// The grader's include rules (docs/layout.md, "The grader's rooms"; cmake/CheckIncludes.cmake):
// the tree keeps them, and the checker names each include that breaks one, with its file and line.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;
const fs::path kRoot = CLOTHREF_SOURCE_DIR;

// The checker on the grader tree at `grader` (relative: to `from`): its exit code and output,
// each run of white space (CMake wraps its messages) one space.
std::pair<int, std::string> check(const fs::path& grader, const fs::path& from = kRoot) {
  const std::string command = "cd '" + from.string() + "' && " + std::string(CLOTHREF_CMAKE) +
                              " -DGRADER='" + grader.string() + "' -P '" +
                              (kRoot / "cmake/CheckIncludes.cmake").string() + "' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return {-1, ""};
  std::string output;
  std::array<char, 4096> buffer;
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  std::string flat;
  for (const char c : output)
    if (!std::isspace(static_cast<unsigned char>(c)))
      flat += c;
    else if (!flat.empty() && flat.back() != ' ')
      flat += ' ';
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, flat};
}

TEST(GraderIncludeRules, TheTreeKeepsThem) {
  const auto [code, output] = check(kRoot / "tools/grader");
  EXPECT_EQ(code, 0) << output;
}

// Each include below breaks one rule (the file, what it includes): the checker fails and names
// every one of them, at the line it was added.
TEST(GraderIncludeRules, EachBrokenRuleIsNamedWithItsFileAndLine) {
  clothref::test::TempDir temp;
  const fs::path copy = temp.path() / "grader";
  fs::copy(kRoot / "tools/grader", copy, fs::copy_options::recursive);
  const std::vector<std::pair<std::string, std::string>> broken = {
      {"grade/run/tools.h", "\"grader/grade/probes/probes.h\""},      // run includes probes
      {"grade/run/spawn.h", "\"grader/grade/report/outputs.h\""},     // run includes report
      {"grade/run/build.h", "\"grader/grade/grade.h\""},              // run includes the grade
      {"grade/probes/util.h", "\"grader/grade/report/outputs.h\""},   // probes include report
      {"grade/explain/stages/stages.h", "\"grader/grade/batch.h\""},  // explain includes the batch
      {"grade/report/outputs.h", "\"grader/grade/run/build.h\""},     // report includes run
      {"grade/report/html_report.h", "\"grader/grade/probes/util.h\""},  // ... or probes
      {"grade/report/class_page.h", "\"grader/grade/batch.h\""},         // ... or the batch
      {"grade/report/outputs.cpp", "\"grader/grade/grade.h\""},          // ... or the grading
      {"grade/grade.h", "\"grader/grade/probes/util.h\""},        // the top level: probes.h only
      {"bridge/probe_protocol.h", "\"grader/grade/results.h\""},  // the bridge is std only
      {"driver/probe_driver.cpp", "\"../bridge/probe_keys.h\""},  // never relative
      {"driver/probe_driver.cpp", "\"clothref/core/cloth.h\""},   // clothref beyond std-only
      {"grade/run/folders.h", "\"cloth.h\""},                     // a course header, grader side
  };
  std::vector<std::string> expected;
  for (const auto& [file, include] : broken) {
    const fs::path path = copy / file;
    int lines = 0;
    {
      std::ifstream in(path);
      ASSERT_TRUE(in) << file;
      for (std::string line; std::getline(in, line);) ++lines;
    }
    std::ofstream(path, std::ios::app) << "#include " << include << "\n";
    expected.push_back("tools/grader/" + file + ":" + std::to_string(lines + 1) + ": #include " +
                       include + " breaks the include rules");
  }
  const auto [code, output] = check(copy);
  EXPECT_NE(code, 0) << output;
  for (const std::string& line : expected)
    EXPECT_NE(output.find(line), std::string::npos) << line << "\n" << output;
  EXPECT_NE(output.find(std::to_string(broken.size()) + " include rule violation(s)"),
            std::string::npos)
      << output;
}

// A relative path (as docs/layout.md writes the command) checks the same files: it once found
// none, and a check of no file passed.
TEST(GraderIncludeRules, ARelativePathChecksTheTree) {
  clothref::test::TempDir temp;
  fs::copy(kRoot / "tools/grader", temp.path() / "grader", fs::copy_options::recursive);
  std::ofstream(temp.path() / "grader/grade/run/tools.h", std::ios::app)
      << "#include \"grader/grade/probes/probes.h\"\n";
  const auto [code, output] = check("grader", temp.path());
  EXPECT_NE(code, 0) << output;
  EXPECT_NE(output.find("tools/grader/grade/run/tools.h:"), std::string::npos) << output;
  EXPECT_NE(check("no-such-folder", temp.path()).first, 0);
}

// A file in a folder without rules fails: a new room needs its rules.
TEST(GraderIncludeRules, AFolderWithoutRulesFails) {
  clothref::test::TempDir temp;
  const fs::path copy = temp.path() / "grader";
  fs::copy(kRoot / "tools/grader", copy, fs::copy_options::recursive);
  fs::create_directories(copy / "attic");
  std::ofstream(copy / "attic/old.cpp") << "#include <vector>\n";
  const auto [code, output] = check(copy);
  EXPECT_NE(code, 0) << output;
  EXPECT_NE(output.find("tools/grader/attic/old.cpp: no room has include rules"), std::string::npos)
      << output;
}

// The files of grade/ as modules (a header and its .cpp one node, named by the path without the
// extension) and the modules each includes.
std::map<std::string, std::set<std::string>> gradeModules() {
  static const std::regex include(R"re(^\s*#\s*include\s*"grader/(grade/[^"]+)\.(h|cpp)")re");
  std::map<std::string, std::set<std::string>> graph;
  const fs::path root = kRoot / "tools/grader";
  for (const auto& entry : fs::recursive_directory_iterator(root / "grade")) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
    std::string module = fs::relative(entry.path(), root).replace_extension().string();
    std::set<std::string>& edges = graph[module];
    std::ifstream in(entry.path());
    std::smatch match;
    for (std::string line; std::getline(in, line);)
      if (std::regex_search(line, match, include) && match[1].str() != module)
        edges.insert(match[1].str());
  }
  return graph;
}

// The modules on a cycle of `graph`: its strongly connected components of more than one module
// (Tarjan's algorithm).
std::set<std::string> onCycles(const std::map<std::string, std::set<std::string>>& graph) {
  std::map<std::string, int> index, low;
  std::vector<std::string> stack;
  std::set<std::string> on_stack, cycles;
  int next = 0;
  std::function<void(const std::string&)> visit = [&](const std::string& v) {
    index[v] = low[v] = next++;
    stack.push_back(v);
    on_stack.insert(v);
    const auto edges = graph.find(v);
    if (edges != graph.end())
      for (const std::string& w : edges->second) {
        if (!index.count(w)) {
          visit(w);
          low[v] = std::min(low[v], low[w]);
        } else if (on_stack.count(w)) {
          low[v] = std::min(low[v], index[w]);
        }
      }
    if (low[v] != index[v]) return;
    std::vector<std::string> component;
    do {
      component.push_back(stack.back());
      on_stack.erase(stack.back());
      stack.pop_back();
    } while (component.back() != v);
    if (component.size() > 1) cycles.insert(component.begin(), component.end());
  };
  for (const auto& [module, edges] : graph)
    if (!index.count(module)) visit(module);
  return cycles;
}

// Cycles that are known and owned elsewhere: run/'s (its build and cache, its child process,
// sandbox, spawn and tools include each other). A module leaves this list when its cycle is gone
// (the test fails on a listed module that is on no cycle, so the list only shrinks).
const std::set<std::string> kKnownOnCycles = {"grade/run/build",         "grade/run/child_process",
                                              "grade/run/compile_cache", "grade/run/sandbox",
                                              "grade/run/spawn",         "grade/run/tools"};

// docs/layout.md: no two files of grade/ include each other, directly or through others.
TEST(GraderRooms, NoTwoFilesIncludeEachOther) {
  const auto graph = gradeModules();
  ASSERT_GT(graph.size(), 40u);  // the tree was read
  const std::set<std::string> on_cycles = onCycles(graph);
  for (const std::string& module : on_cycles)
    EXPECT_TRUE(kKnownOnCycles.count(module)) << module << " is on an include cycle";
  for (const std::string& module : kKnownOnCycles)
    EXPECT_TRUE(on_cycles.count(module)) << module << " is on no cycle: take it off the known list";
  // The check finds one: two modules of the mistakes room including each other.
  auto broken = graph;
  broken["grade/mistakes/models"].insert("grade/mistakes/integrator");
  broken["grade/mistakes/integrator"].insert("grade/mistakes/models");
  const std::set<std::string> cycles = onCycles(broken);
  EXPECT_TRUE(cycles.count("grade/mistakes/models") && cycles.count("grade/mistakes/integrator"));
}

// docs/layout.md: no file of grade/ is longer than 400 lines (run/'s three longest are known and
// owned by its own issue).
TEST(GraderRooms, NoFileIsLongerThan400Lines) {
  const std::set<std::string> known = {"grade/run/child_process.cpp", "grade/run/folders.cpp",
                                       "grade/run/sandbox.cpp"};
  const fs::path root = kRoot / "tools/grader";
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root / "grade")) {
    if (!entry.is_regular_file()) continue;
    ++files;
    std::ifstream in(entry.path());
    int lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    const std::string name = fs::relative(entry.path(), root).string();
    if (!known.count(name)) {
      EXPECT_LE(lines, 400) << name;
    }
  }
  EXPECT_GT(files, 80);
}

}  // namespace
