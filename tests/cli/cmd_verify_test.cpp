// `clothref verify`: the JSON report and the table (tools/clothref/cmd_verify.cpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "test_util.h"

namespace clothref {
namespace {

TEST(VerifyCommand, JsonHasOrdersAndChecksAndExitsZero) {
  const auto [code, output] = test::runCli("verify --json", test::Capture::StdoutOnly);
  EXPECT_EQ(code, 0);
  const nlohmann::json report = nlohmann::json::parse(output);
  for (const char* method : {"explicit", "implicit", "midpoint", "rk4", "symplectic"}) {
    ASSERT_TRUE(report["orders"].contains(method)) << method;
    EXPECT_TRUE(report["orders"][method]["double"].is_number()) << method;
    const nlohmann::json& single = report["orders"][method]["float"];
    EXPECT_TRUE(single.is_number() || single.is_null()) << method;
    EXPECT_TRUE(report["float_floor"][method].is_number()) << method;
  }
  EXPECT_NEAR(report["orders"]["rk4"]["double"].get<double>(), 4, 0.2);
  ASSERT_TRUE(report["checks"].is_array());
  EXPECT_GT(report["checks"].size(), 50u);
  for (const nlohmann::json& row : report["checks"]) {
    for (const char* key :
         {"check", "method", "precision", "expected", "observed", "tolerance", "pass"})
      EXPECT_TRUE(row.contains(key)) << key;
    EXPECT_TRUE(row["pass"].get<bool>()) << row.dump();
  }
  EXPECT_TRUE(report["passed"].get<bool>());
}

TEST(VerifyCommand, TablePrintsTheColumnsAndASummary) {
  const auto [code, output] = test::runCli("verify", test::Capture::StdoutOnly);
  EXPECT_EQ(code, 0);
  EXPECT_EQ(output.rfind("check", 0), 0u);
  for (const char* column : {"method", "prec", "expected", "observed", "tolerance", "pass"})
    EXPECT_NE(output.find(column), std::string::npos) << column;
  EXPECT_NE(output.find(" checks, 0 failed"), std::string::npos);
  EXPECT_EQ(output.find(" NO\n"), std::string::npos);
  // every row's last column under the header's "pass", whatever the longest method name
  // (backward-euler) or expected value ("<= ...")
  std::istringstream in(output);
  std::string header;
  ASSERT_TRUE(std::getline(in, header));
  const std::size_t pass = header.rfind("pass");
  ASSERT_NE(pass, std::string::npos);
  int rows = 0;
  for (std::string line; std::getline(in, line) && !line.empty(); ++rows)
    EXPECT_EQ(line.size(), pass + 3) << "misaligned: " << line;  // "yes"
  EXPECT_GT(rows, 100);
  // the orders lines: "expected" in one column for every method
  std::size_t column = std::string::npos;
  int methods = 0;
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find("  expected ");
    if (line.rfind("  ", 0) != 0 || at == std::string::npos) continue;
    ++methods;
    if (column == std::string::npos) column = at;
    EXPECT_EQ(at, column) << "misaligned: " << line;
  }
  EXPECT_EQ(methods, 6);
}

}  // namespace
}  // namespace clothref
