#include "grader/grade/probes/probes.h"

#include <utility>

#include "grader/bridge/probe_keys.h"

namespace clothref::grader {

namespace {

// Whether `edition` grades `stub`: it has points in that edition's column of stubTable().
bool gradedIn(const std::string& stub, int edition) {
  for (const StubInfo& info : stubTable())
    if (stub == info.name) return (edition == 2024 ? info.points_2024 : info.points_2022) > 0;
  return false;
}

}  // namespace

std::vector<ProbeGroup> probeTable() {
  std::vector<ProbeGroup> table;
  const auto add = [&table](std::vector<ProbeGroup> rows) {
    for (ProbeGroup& row : rows) table.push_back(std::move(row));
  };
#define CLOTHREF_PROBE_ADD_ROWS(identifier, text, name) add(probeRows##name());
  CLOTHREF_PROBE_GROUPS(CLOTHREF_PROBE_ADD_ROWS)
#undef CLOTHREF_PROBE_ADD_ROWS
  return table;
}

std::vector<ProbeGroup> probeGroups(int edition, bool information) {
  std::vector<ProbeGroup> groups;
  for (ProbeGroup& row : probeTable())
    if (row.stub.empty() ? information : gradedIn(row.stub, edition))
      groups.push_back(std::move(row));
  return groups;
}

std::string integratorFolder(int method, bool course_size) {
  return std::string(probe::group::kIntegrate) + "-" + std::to_string(method) +
         (course_size ? "-course" : "");
}

std::vector<std::pair<std::string, std::string>> probeFolders() {
  std::vector<std::pair<std::string, std::string>> folders;
  for (const ProbeGroup& row : probeTable())
    for (const std::string& folder : row.folders) folders.push_back({folder, row.stub});
  return folders;
}

std::vector<PlannedTest> plannedTests(int edition) {
  std::vector<PlannedTest> tests;
  for (const ProbeGroup& group : probeGroups(edition, false))
    tests.insert(tests.end(), group.checks.begin(), group.checks.end());
  return tests;
}

}  // namespace clothref::grader
