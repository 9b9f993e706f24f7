// BATCHDIR/index.html (tools/grader/grade/report/class_page.cpp): built from the batch's files
// alone, every name a student controls as JSON data. In a real browser: tests/browser/.
#include "grader/grade/report/class_page.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "grader/grade/batch.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;

TEST(ClassPage, ClassPageFromTheBatchFolders) {
  const test::TempDir dir;
  BatchRow a;
  a.name = "alice";
  a.verdict = grader::Verdict::Graded;
  a.score = 5;
  BatchRow b = a;
  b.name = "bob";  // no results.json: a row without checks
  fs::create_directories(dir.path() / "alice");
  test::writeText(dir.path() / "alice" / "results.json",
                  R"({"tests": [{"name": "Cloth::initializeSpring: count", "status": "failed",
                      "tags": ["Cloth::initializeSpring", "backup-</script>-aliases"]}]})");
  test::writeText(dir.path() / "alice" / "report.html", "x");
  const std::string page = batchIndexHtml(classRows(dir.path(), {a, b}));
  const std::string open = "<script type=\"application/json\" id=\"class-data\">";
  const std::size_t begin = page.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = page.find("</script>", begin);
  ASSERT_NE(end, std::string::npos);
  const auto data =
      nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
  ASSERT_EQ(data["submissions"].size(), 2u);
  EXPECT_EQ(data["checks"], nlohmann::json({"Cloth::initializeSpring: count"}));
  // a results.json without extra_data: its tags, each taken as likely
  EXPECT_EQ(data["submissions"][0]["causes"],
            nlohmann::json::parse(R"([{"id": "backup-</script>-aliases", "likely": true}])"));
  EXPECT_EQ(data["submissions"][0]["checks"]["0"], false);
  EXPECT_EQ(data["submissions"][0]["report"], "alice/report.html");
  EXPECT_EQ(data["submissions"][1]["report"], "bob/report.md");
  EXPECT_TRUE(data["submissions"][1]["checks"].empty());
}

}  // namespace
}  // namespace clothref::grader
