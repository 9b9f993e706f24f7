// The one JSON input reader: every file format names the source, the JSON pointer, the line and
// the column of a syntax error.
#include "clothref/io/json_input.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "clothref/diff/diff.h"
#include "clothref/golden/golden.h"
#include "clothref/io/error.h"
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
  EXPECT_EQ(message.rfind("file.json: /a/2: not valid JSON (line 3, column 6): ", 0), 0u) << message;
}

TEST(JsonInput, NumberTooLargeForADoubleIsASyntaxErrorWithItsPlace) {
  const std::string message = errorOf([] { parseOrderedJson("{\"dt\": 1e400}", "h"); });
  EXPECT_EQ(message.rfind("h: /dt: not valid JSON (line 1, column ", 0), 0u) << message;
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

}  // namespace
}  // namespace clothref
