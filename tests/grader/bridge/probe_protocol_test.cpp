// The bridge frame: what the child sends back is parsed exactly, and anything malformed is refused.
#include "grader/bridge/probe_protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

probe::ProbeMessage sample() {
  probe::ProbeMessage m;
  m.nonce = 0x0123456789abcdefull;
  m.floats["x"] = {1.0f, -0.0f, std::numeric_limits<float>::quiet_NaN(), 1e-45f};
  m.floats["empty"] = {};
  m.ints["n"] = {-3, 1ll << 40};
  m.texts["group"] = "forces";
  return m;
}

TEST(ProbeProtocol, RoundTripKeepsEveryBit) {
  const auto decoded = probe::decodeMessage(probe::encodeMessage(sample()));
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->nonce, 0x0123456789abcdefull);
  const auto& x = decoded->f("x");
  ASSERT_EQ(x.size(), 4u);
  EXPECT_TRUE(std::signbit(x[1]));
  EXPECT_TRUE(std::isnan(x[2]));
  EXPECT_EQ(x[3], 1e-45f);
  EXPECT_TRUE(decoded->f("empty").empty());
  EXPECT_EQ(decoded->i("n"), (std::vector<std::int64_t>{-3, 1ll << 40}));
  EXPECT_EQ(decoded->text("group"), "forces");
}

TEST(ProbeProtocol, TruncatedOrPaddedFramesAreRefused) {
  const std::string frame = probe::encodeMessage(sample());
  for (std::size_t cut = 0; cut < frame.size(); ++cut)
    EXPECT_FALSE(probe::decodeMessage(frame.substr(0, cut))) << cut;
  EXPECT_FALSE(probe::decodeMessage(frame + "x"));
}

TEST(ProbeProtocol, PrintedTextIsNotAFrame) {
  EXPECT_FALSE(probe::decodeMessage("All tests passed! score: 100\n"));
  std::string frame = probe::encodeMessage(sample());
  frame[0] = 'X';
  EXPECT_FALSE(probe::decodeMessage(frame));
}

TEST(ProbeProtocol, HugeDeclaredLengthsAreRefusedWithoutAllocating) {
  probe::ProbeMessage m;
  m.floats["x"] = {1.0f};
  std::string frame = probe::encodeMessage(m);
  // The float count sits after magic, nonce, length, entry count, key length and key.
  const std::size_t count_at = 4 + 8 + 8 + 8 + 8 + 1;
  for (int b = 0; b < 8; ++b) frame[count_at + b] = '\xff';
  EXPECT_FALSE(probe::decodeMessage(frame));
}

}  // namespace
