// The one number format and the one expected-against-yours comparison every probe writes
// (tools/grader/grade/explain/compare_text.h).
#include "grader/grade/explain/compare_text.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "grader/grade/report/outputs.h"

namespace clothref::grader::util {
namespace {

TEST(Numbers, SixSignificantDigitsAsPercentG) {
  EXPECT_EQ(num(0.1), "0.1");
  EXPECT_EQ(num(-0.000371004123), "-0.000371004");
  EXPECT_EQ(num(7.4596134e-05), "7.45961e-05");
  EXPECT_EQ(num(123456789.0), "1.23457e+08");
  EXPECT_EQ(num(-0.0), "0");  // never "-0"
  EXPECT_EQ(num(std::nan("")), "NaN");
  EXPECT_EQ(num(-std::numeric_limits<double>::infinity()), "-inf");
}

// The pair: -0.000371004 beside 7.459613e-05 in one vector. Read together, they share
// scientific notation; a vector of decimals stays decimal.
TEST(Numbers, NumbersReadTogetherShareOneNotation) {
  EXPECT_EQ(vec3(std::array<double, 3>{-0.000371004, 7.459613e-05, 0}),
            "(-3.71004e-04, 7.45961e-05, 0)");
  EXPECT_EQ(vec3(std::array<double, 3>{1.5, -0.25, 0}), "(1.5, -0.25, 0)");
  EXPECT_EQ(nums({1.5e-05, 2}), (std::vector<std::string>{"1.5e-05", "2e+00"}));
}

TEST(Compare, TheDifferingComponentIsBoldInBothWithHowManyTolerances) {
  const std::string text =
      compareVectors("v after the call", std::array<double, 3>{1, -0.8, 0},
                     std::array<double, 3>{1, 0.8, 0}, Tolerance{1e-5, 1e-5}, "m/s");
  EXPECT_EQ(text,
            "- v after the call: expected (1, **-0.8**, 0) m/s, yours (1, **0.8**, 0) m/s\n"
            "  - y differs by 1.6 = 89000 x the tolerance (1.8e-05)\n")
      << text;
}

TEST(Compare, RatiosAndTolerancesHaveTwoDigits) {
  EXPECT_EQ(ratio(4.54), "4.5");
  EXPECT_EQ(ratio(409.6), "410");
  EXPECT_EQ(ratio(81604), "82000");
  EXPECT_EQ(ratio(3.4e7), "3.4e+07");
  EXPECT_EQ(tolerance(1.10226e-05), "1.1e-05");
  const std::string text = compareVectors("x", std::array<double, 3>{0, 0, 0},
                                          std::array<double, 3>{1, 0, 2}, Tolerance{0.1, 0});
  EXPECT_NE(text.find("\n  - x differs by 1 = 10 x the tolerance (0.1); z by 2 = 20 x (0.1)\n"),
            std::string::npos)
      << text;
}

TEST(Compare, WithinTheToleranceNothingIsMarked) {
  const std::string text =
      compareVectors("x", std::array<double, 3>{1, 2, 3}, std::array<double, 3>{1, 2, 3.000001},
                     Tolerance{1e-5, 1e-5}, "m", "  ");
  EXPECT_EQ(text,
            "  - x: expected (1, 2, 3) m, yours (1, 2, 3) m: the same within the tolerance\n");
  EXPECT_EQ(text.find("**"), std::string::npos);
}

TEST(Compare, EachDifferingComponentHasItsLineAndNaNIsSaid) {
  const std::string text =
      compareVectors("a", std::array<double, 3>{0, 0, 0}, std::array<double, 3>{std::nan(""), 2, 0},
                     Tolerance{0.5, 0}, "");
  EXPECT_NE(text.find("yours (**NaN**, **2**, 0)"), std::string::npos) << text;
  EXPECT_NE(text.find("\n  - x: yours is not finite; y by 2 = 4 x (0.5)\n"), std::string::npos)
      << text;
}

TEST(Compare, OneNumberAndABitExactTolerance) {
  EXPECT_EQ(compareNumbers("rest length", 0.235702, 0.166667, Tolerance{0, 1e-5}, "m"),
            "- rest length: expected **0.235702** m, yours **0.166667** m\n"
            "  - it differs by 0.069035 = 29000 x the tolerance (2.4e-06)\n");
  EXPECT_NE(compareNumbers("t", 1, 2, Tolerance{}).find("the tolerance is 0"), std::string::npos);
}

// The legend every report shows says what num() does.
TEST(Compare, TheLegendStatesTheFormat) {
  const std::string legend = kNumberLegend;
  EXPECT_NE(legend.find("6 significant digits"), std::string::npos);
  EXPECT_NE(legend.find(num(0.000371004123)), std::string::npos);
  EXPECT_NE(legend.find(num(7.4596134e-05)), std::string::npos);
  EXPECT_NE(legend.find("**bold**"), std::string::npos);
}

}  // namespace
}  // namespace clothref::grader::util
