// The limits of every kind of run (grader/grade/run/limits_table.h): docs/reliability.md shows the
// table the code makes, and every run of student code has each kind of limit.
#include "grader/grade/run/limits_table.h"

#include <gtest/gtest.h>

#include <string>

#include "test_util.h"

namespace clothref::grader {
namespace {

// The docs' table is the code's, row for row (regenerate it from runLimitsMarkdown()).
TEST(RunLimitsTable, TheDocsShowTheCodesTable) {
  const std::string docs =
      test::readText(std::string(CLOTHREF_SOURCE_DIR) + "/docs/reliability.md");
  const std::string table = runLimitsMarkdown();
  EXPECT_NE(docs.find(table), std::string::npos) << "docs/reliability.md should hold:\n" << table;
}

// Every run of student code has a limit of each kind: none of its cells is empty (the repair run,
// which issue 38 adds, says "not yet").
TEST(RunLimitsTable, EveryRunHasEveryLimit) {
  const auto rows = runLimitsTable();
  ASSERT_EQ(rows.size(), 7u);
  for (const RunLimitsRow& row : rows) {
    if (row.wall.rfind("not yet", 0) == 0) continue;
    for (const std::string* cell :
         {&row.wall, &row.cpu, &row.memory, &row.processes, &row.open_files, &row.disk})
      EXPECT_FALSE(cell->empty()) << row.run;
    EXPECT_EQ(row.memory.find("no memory"), std::string::npos) << row.run;
  }
}

}  // namespace
}  // namespace clothref::grader
