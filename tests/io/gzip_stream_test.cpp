// Gzip through iostreams (lib/clothref/io/gzip_stream.cpp): concatenated members read like zcat
// reads them, trailing bytes that are not another member are refused, and no input makes the
// reader spin (each case runs under an alarm, so a loop fails the test instead of hanging it).
#include "clothref/io/gzip_stream.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <istream>
#include <sstream>
#include <string>

#include "test_util.h"

namespace clothref {
namespace {

struct ReadResult {
  std::string text;
  std::string error;  // empty when the whole stream was read
};

// Reads all of `compressed` through GzipInputBuffer, as the trace reader does (sbumpc).
ReadResult gunzip(const std::string& compressed) {
  ::alarm(30);  // a reader that spins is killed (SIGALRM) rather than hanging ctest
  std::stringbuf source(compressed);
  ReadResult result;
  if (!startsLikeGzip(source)) {
    result.error = "not gzip";
    return result;
  }
  GzipInputBuffer gzip(source, "test.gz");
  try {
    for (int c = gzip.sbumpc(); c != std::char_traits<char>::eof(); c = gzip.sbumpc())
      result.text.push_back(char(c));
  } catch (const std::ios_base::failure&) {
    result.error = gzip.error();
    EXPECT_FALSE(result.error.empty());
  }
  ::alarm(0);
  return result;
}

// Bytes no compressor shrinks (a fixed linear congruential sequence), so a member is longer than
// the reader's 64 KiB input buffer and its end falls inside a later refill.
std::string incompressible(std::size_t size) {
  std::string text(size, '\0');
  std::uint32_t x = 12345;
  for (char& c : text) {
    x = x * 1664525u + 1013904223u;
    c = char(x >> 24);
  }
  return text;
}

TEST(GzipStream, OneMemberReadsBack) {
  const ReadResult result = gunzip(test::gzipMember("line 1\nline 2\n"));
  EXPECT_EQ(result.error, "");
  EXPECT_EQ(result.text, "line 1\nline 2\n");
}

// (head | gzip; tail | gzip) > multi.gz: zcat reads the concatenation; so do we (this used to
// loop forever at 100 % CPU once the first member ended with input still buffered).
TEST(GzipStream, ConcatenatedMembersReadAsTheirConcatenation) {
  const ReadResult two = gunzip(test::gzipMember("first\n") + test::gzipMember("second\n"));
  EXPECT_EQ(two.error, "");
  EXPECT_EQ(two.text, "first\nsecond\n");

  // empty members anywhere are fine, and contribute nothing
  const ReadResult empties =
      gunzip(test::gzipMember("") + test::gzipMember("a\n") + test::gzipMember("") +
             test::gzipMember("b\n") + test::gzipMember(""));
  EXPECT_EQ(empties.error, "");
  EXPECT_EQ(empties.text, "a\nb\n");

  const ReadResult only_empty = gunzip(test::gzipMember(""));
  EXPECT_EQ(only_empty.error, "");
  EXPECT_EQ(only_empty.text, "");
}

TEST(GzipStream, MembersLongerThanTheInputBufferJoinAcrossRefills) {
  const std::string big = incompressible(150'000);
  const std::string compressed =
      test::gzipMember(big) + test::gzipMember("tail\n") + test::gzipMember(big);
  ASSERT_GT(compressed.size(), 2u * (1u << 16));
  const ReadResult result = gunzip(compressed);
  EXPECT_EQ(result.error, "");
  ASSERT_EQ(result.text.size(), 2 * big.size() + 5);
  EXPECT_EQ(result.text, big + "tail\n" + big);
}

// Trailing bytes after a member that are not another member: refused, with one clear reason
// (gzip itself warns and ignores them; a trace with junk after it is not a trace we wrote).
TEST(GzipStream, TrailingBytesAfterAMemberAreRefused) {
  const std::string member = test::gzipMember("data\n");
  for (const std::string& trailer : {std::string(4, '\0'), std::string("trailing text\n"),
                                     std::string("\n"), std::string(1, '\x8b')}) {
    SCOPED_TRACE(testing::PrintToString(trailer));
    const ReadResult result = gunzip(member + trailer);
    EXPECT_EQ(result.error, "trailing bytes after the gzip data (not another gzip member)");
    // everything before the trailer was delivered
    EXPECT_EQ(result.text, "data\n");
  }
  // also after a second member, and after an empty one
  EXPECT_EQ(gunzip(member + test::gzipMember("more\n") + "x").error,
            "trailing bytes after the gzip data (not another gzip member)");
  EXPECT_EQ(gunzip(member + test::gzipMember("") + std::string(4, '\0')).error,
            "trailing bytes after the gzip data (not another gzip member)");
}

// A member cut short, or a second member that is only its first byte or two, is truncated; a
// second "member" with the magic but a bad method is corrupt.
TEST(GzipStream, TruncatedAndCorruptMembersAreErrors) {
  const std::string member = test::gzipMember("data\n");
  EXPECT_EQ(gunzip(member.substr(0, member.size() - 3)).error,
            "truncated gzip data (the stream ends before its trailer)");
  EXPECT_EQ(gunzip(member + "\x1f").error,
            "truncated gzip data (the stream ends before its trailer)");
  EXPECT_EQ(gunzip(member + "\x1f\x8b").error,
            "truncated gzip data (the stream ends before its trailer)");
  const ReadResult corrupt = gunzip(member + "\x1f\x8b\x07" + std::string(20, '\0'));
  EXPECT_EQ(corrupt.error.rfind("corrupt gzip data (", 0), 0u) << corrupt.error;
}

}  // namespace
}  // namespace clothref
