// The one table of probes (grade/probes/probes.cpp): every row a group of the protocol's list and
// every group some row's, the folders from the rows, the integrators from clothref's method table,
// and each edition running the rows of the stubs it grades.
#include "grader/grade/probes/probes.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "clothref/core/method.h"
#include "grader/bridge/probe_keys.h"

namespace clothref::grader {
namespace {

TEST(ProbeTable, EveryRowIsAGroupOfTheProtocolAndEveryGroupHasARow) {
  std::set<std::string> listed, used;
  for (const probe::Name& name : probe::group::kAll) listed.insert(name.text);
  for (const ProbeGroup& row : probeTable()) {
    EXPECT_TRUE(listed.count(row.group)) << row.group << " is not in probe::group";
    EXPECT_TRUE(row.run) << row.group;
    EXPECT_FALSE(row.folders.empty()) << row.group;
    EXPECT_EQ(row.stub.empty(), row.checks.empty()) << row.group;
    for (const PlannedTest& check : row.checks) EXPECT_EQ(check.stub, row.stub) << row.group;
    used.insert(row.group);
  }
  EXPECT_EQ(used, listed);
}

// probeFolders() lists the rows' folders, each once, with the row's stub.
TEST(ProbeTable, FoldersAreTheRowsFoldersEachOnce) {
  std::map<std::string, std::string> expected;
  std::size_t count = 0;
  for (const ProbeGroup& row : probeTable())
    for (const std::string& folder : row.folders) {
      expected[folder] = row.stub;
      ++count;
    }
  const auto folders = probeFolders();
  EXPECT_EQ(folders.size(), count);
  std::map<std::string, std::string> listed(folders.begin(), folders.end());
  EXPECT_EQ(listed.size(), folders.size()) << "a folder is named twice";
  EXPECT_EQ(listed, expected);
}

// One integrator row per course row of the method table, in its order, grading that class's
// integrate and running in that row's folders.
TEST(ProbeTable, IntegratorRowsAreTheMethodTablesCourseRows) {
  std::vector<std::string> expected, rows;
  for (std::size_t k = 0; k < kMethods.size(); ++k)
    if (kMethods[k].origin == MethodOrigin::Course) {
      expected.push_back(std::string(kMethods[k].course_name) + "::integrate");
      for (const ProbeGroup& row : probeTable())
        if (row.stub == expected.back()) {
          EXPECT_EQ(row.group, probe::group::kIntegrate);
          EXPECT_EQ(row.folders,
                    std::vector<std::string>({integratorFolder(static_cast<int>(k), false),
                                              integratorFolder(static_cast<int>(k), true)}));
        }
    }
  for (const ProbeGroup& row : probeTable())
    if (row.group == probe::group::kIntegrate) rows.push_back(row.stub);
  EXPECT_EQ(rows, expected);
}

// An edition runs the rows of the stubs it gives points to (stubTable()), in the table's order,
// and the information-only rows only when asked.
TEST(ProbeTable, AnEditionRunsTheRowsOfTheStubsItGrades) {
  for (const int edition : {2022, 2024})
    for (const bool information : {false, true}) {
      std::vector<std::string> expected, got;
      for (const ProbeGroup& row : probeTable()) {
        double points = 0;
        for (const StubInfo& info : stubTable())
          if (row.stub == info.name) points = edition == 2024 ? info.points_2024 : info.points_2022;
        if (row.stub.empty() ? information : points > 0) expected.push_back(row.folders[0]);
      }
      for (const ProbeGroup& row : probeGroups(edition, information)) got.push_back(row.folders[0]);
      EXPECT_EQ(got, expected) << edition << " " << information;
    }
  const auto has = [](int edition, const std::string& stub) {
    for (const ProbeGroup& row : probeGroups(edition, true))
      if (row.stub == stub) return true;
    return false;
  };
  EXPECT_TRUE(has(2022, stubName(Stub::CollideSpheres)));
  EXPECT_FALSE(has(2024, stubName(Stub::CollideSpheres)));
}

}  // namespace
}  // namespace clothref::grader
