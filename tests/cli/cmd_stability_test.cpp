// `clothref stability`: the documented JSON and one-line errors (tools/clothref/cmd_stability.cpp).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

#include "test_util.h"

namespace clothref {
namespace {

TEST(StabilityCli, PrintsTheDocumentedJson) {
  const test::CommandResult result = test::runCli(
      "stability --scene spring-undamped --method rk4 --method explicit "
      "--precision double --json --quiet");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto json = nlohmann::json::parse(result.output);
  ASSERT_EQ(json["results"].size(), 2u);
  for (const auto& item : json["results"])
    for (const char* key :
         {"scene", "method", "precision", "dt_max_measured", "dt_max_theory", "criterion"})
      EXPECT_TRUE(item.contains(key)) << key;
  EXPECT_EQ(json["results"][0]["method"], "rk4");
  EXPECT_NEAR(json["results"][0]["dt_max_theory"].get<double>(), 0.2 * std::sqrt(2.0), 1e-6);
  EXPECT_TRUE(json["results"][1]["dt_max_theory"].is_null());
}

TEST(StabilityCli, BadInputIsOneLineAndExitTwo) {
  for (const char* args : {"stability --method leapfrog", "stability --precision half",
                           "stability --scene no-such-scene"}) {
    const test::CommandResult result = test::runCli(args);
    EXPECT_EQ(result.exit_code, 2) << args;
    EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  }
}

}  // namespace
}  // namespace clothref
