// appendStepLine: the exact text of a step line (docs/trace-format.md), numbers shortest
// round-trip in the body's own precision, non-finite values as strings, bodies in the given order,
// and the hash of the same bodies (trace/hash.h).
#include "clothref/trace/step_line.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "clothref/trace/hash.h"

namespace clothref {
namespace {

template <typename T>
std::string line(std::int64_t step, double t, const std::vector<BodyView<T>>& bodies) {
  std::string out = "prefix|";  // the line is appended, never written over
  appendStepLine<T>(out, step, t, std::span<const BodyView<T>>(bodies));
  return out;
}

TEST(StepLine, FloatTextIsShortestInFloat) {
  // columns are (x, y, z, w): w is never written
  const std::array<float, 8> position = {0.1f, -1.8333334f, 2, 1, 1e-45f, 3e38f, -0.0f, 1};
  const std::array<float, 8> velocity = {0, 0.5f, -7, 0, 1, 2, 3, 0};
  const std::vector<BodyView<float>> bodies = {{"cloth", position.data(), velocity.data(), 2}};
  const std::string hash = hashToHex(stateHash(std::span<const BodyView<float>>(bodies)));
  EXPECT_EQ(line<float>(12, 0.0012, bodies),
            "prefix|{\"step\":12,\"t\":0.0012,\"hash\":\"" + hash +
                "\",\"bodies\":{\"cloth\":{\"position\":[[0.1,-1.8333334,2],[1e-45,3e+38,-0]],"
                "\"velocity\":[[0,0.5,-7],[1,2,3]]}}}\n");
}

TEST(StepLine, DoubleTextIsShortestInDouble) {
  const std::array<double, 4> position = {0.1, 1.0 / 3.0, -2.5, 1};
  const std::array<double, 4> velocity = {double(0.1f), 0, 0, 0};
  const std::vector<BodyView<double>> bodies = {{"spheres", position.data(), velocity.data(), 1}};
  const std::string text = line<double>(0, 0, bodies);
  EXPECT_NE(text.find("\"position\":[[0.1,0.3333333333333333,-2.5]]"), std::string::npos) << text;
  EXPECT_NE(text.find("\"velocity\":[[0.10000000149011612,0,0]]"), std::string::npos) << text;
}

TEST(StepLine, NonFiniteValuesAreStrings) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::array<float, 4> position = {std::nanf(""), inf, -inf, 1};
  const std::array<float, 4> velocity = {0, 0, 0, 0};
  const std::vector<BodyView<float>> bodies = {{"cloth", position.data(), velocity.data(), 1}};
  const std::string text = line<float>(3, std::numeric_limits<double>::infinity(), bodies);
  EXPECT_NE(text.find("\"t\":\"Infinity\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"position\":[[\"NaN\",\"Infinity\",\"-Infinity\"]]"), std::string::npos)
      << text;
}

TEST(StepLine, BodiesInOrderAndNoneIsValid) {
  const std::array<float, 4> a = {1, 2, 3, 1};
  const std::array<float, 4> b = {4, 5, 6, 1};
  const std::vector<BodyView<float>> two = {{"cloth", a.data(), a.data(), 1},
                                            {"spheres", b.data(), b.data(), 1}};
  const std::string text = line<float>(1, 1e-4, two);
  const std::size_t cloth = text.find("\"cloth\":{\"position\":[[1,2,3]],\"velocity\":[[1,2,3]]}");
  const std::size_t spheres =
      text.find("\"spheres\":{\"position\":[[4,5,6]],\"velocity\":[[4,5,6]]}");
  ASSERT_NE(cloth, std::string::npos) << text;
  ASSERT_NE(spheres, std::string::npos) << text;
  EXPECT_LT(cloth, spheres);
  EXPECT_EQ(text.substr(text.size() - 3), "}}\n");

  const std::string empty = line<float>(0, 0, {});
  EXPECT_NE(empty.find(",\"bodies\":{}}\n"), std::string::npos) << empty;
}

}  // namespace
}  // namespace clothref
