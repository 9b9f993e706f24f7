// The one JSON input reader: every file format names the source, the JSON pointer, the line and
// the column of a syntax error.
#include "clothref/io/json_input.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "clothref/diff/diff.h"
#include "clothref/golden/golden.h"
#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/limits.h"
#include "clothref/scene/scene.h"
#include "clothref/trace/reader.h"
#include "test_util.h"

namespace clothref {
namespace {

std::string errorOf(auto&& call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(JsonInput, SyntaxErrorNamesSourcePointerLineAndColumn) {
  const std::string message =
      errorOf([] { parseJson("{\n  \"a\": [1,\n  2, x]\n}", "file.json"); });
  EXPECT_EQ(message.rfind("file.json: /a/2: not valid JSON (line 3, column 6): ", 0), 0u)
      << message;
}

TEST(JsonInput, NumberTooLargeForADoubleIsASyntaxErrorWithItsPlace) {
  const std::string message = errorOf([] { parseOrderedJson("{\"dt\": 1e400}", "h"); });
  EXPECT_EQ(message.rfind("h: /dt: not valid JSON (line 1, column ", 0), 0u) << message;
}

// A key repeated in one object is refused with its pointer (nlohmann would keep the last one
// silently); the same key in different objects is fine.
TEST(JsonInput, DuplicateKeysAreRefused) {
  EXPECT_EQ(errorOf([] { parseJson("{\"dt\": 1, \"dt\": 2}", "f.json"); }),
            "f.json: /dt: duplicate key");
  EXPECT_EQ(errorOf([] {
              parseOrderedJson("{\"a\": [{}, {\"x\": 1, \"y\": {\"z\": 1, \"z\": 1}}]}", "h");
            }),
            "h: /a/1/y/z: duplicate key");
  EXPECT_EQ(
      errorOf([] { parseJson("{\"a\": {\"x\": 1}, \"b\": {\"x\": 1}, \"x\": [1, 2]}", "f"); }),
      "(no error)");
}

TEST(JsonInput, ValidTextParses) {
  EXPECT_EQ(parseJson("{\"a\": [1, 2]}", "x")["a"][1], 2);
  // the ordered form keeps the key order (trace headers are compared by JSON pointer, written in
  // a fixed order)
  EXPECT_EQ(parseOrderedJson("{\"b\": 1, \"a\": 2}", "x").begin().key(), "b");
}

// Every file format that reads JSON reports the same way.
TEST(JsonInput, EveryFormatUsesIt) {
  const test::TempDir dir;
  const std::string broken = dir.file("broken.json");
  std::ofstream(broken) << "{\n  \"x\": tru\n}\n";
  const std::string expected = broken + ": /x: not valid JSON (line 2, column ";
  for (const std::string& message :
       {errorOf([&] { loadScene(broken); }), errorOf([&] { readToleranceFile(broken); }),
        errorOf([&] { readManifest(broken); })})
    EXPECT_EQ(message.rfind(expected, 0), 0u) << message;
  const std::string trace = dir.file("trace.jsonl");
  std::ofstream(trace) << "{\"format\": \"clothref-trace\",\n";
  const std::string message = errorOf([&] { TraceReader reader(trace); });
  EXPECT_EQ(message.rfind(trace + ":1: header: /format: not valid JSON (line 1, column ", 0), 0u)
      << message;
}

// Nesting deeper than the limit is refused before parsing (freeing a 10^5-deep document
// recursed once per level and overflowed the stack); strings and raised limits are respected.
TEST(JsonInput, NestingDeeperThanTheLimitIsRefused) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_EQ(errorOf([&] { parseJson(deep, "deep.json"); }),
            "deep.json: nested deeper than 64 levels (line 1; raise the limit with "
            "--max-json-depth)");
  EXPECT_EQ(errorOf([&] { parseJson("[\"" + std::string(1000, '[') + "\"]", "s.json"); }),
            "(no error)");
  const std::size_t saved = inputLimits().json_depth;
  inputLimits().json_depth = 200;
  EXPECT_EQ(errorOf([&] { parseJson(std::string(100, '[') + std::string(100, ']'), "x"); }),
            "(no error)");
  inputLimits().json_depth = saved;
}

// A 10 MB unterminated string comes back as a short error line, not a 10 MB one.
TEST(JsonInput, ErrorsQuoteShortExcerpts) {
  const std::string message =
      errorOf([] { parseJson("{\"a\": \"" + std::string(10 << 20, 'x'), "big.json"); });
  EXPECT_EQ(message.rfind("big.json: /a: not valid JSON", 0), 0u) << message.substr(0, 300);
  EXPECT_LT(message.size(), 300u);
}

// Files larger than the limit are refused while reading (/dev/zero cannot grow without bound).
TEST(JsonInput, FilesLargerThanTheLimitAreRefused) {
  const test::TempDir dir;
  std::ofstream(dir.file("big.json")) << "[" << std::string(5000, ' ') << "]";
  const std::size_t saved = inputLimits().file_bytes;
  inputLimits().file_bytes = 4096;
  EXPECT_EQ(
      errorOf([&] { readJsonFile(dir.file("big.json"), "scene file"); }),
      dir.file("big.json") + ": larger than 4096 bytes (raise the limit with --max-file-bytes)");
  inputLimits().file_bytes = saved;
  EXPECT_EQ(errorOf([&] { readJsonFile(dir.file("big.json"), "scene file"); }), "(no error)");
}

}  // namespace
}  // namespace clothref
