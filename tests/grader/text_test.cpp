// Text a submission controls, made safe: Big5 / CP950 decoded, other bytes U+FFFD, control
// characters escaped, names on one line; the result is always valid UTF-8.
#include "grader/grade/text.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace clothref::grader {
namespace {

TEST(IsValidUtf8, RefusesWhatRfc3629Refuses) {
  EXPECT_TRUE(isValidUtf8("plain ascii, \xE4\xB8\xAD\xE6\x96\x87, \xF0\x9F\x98\x80"));
  EXPECT_FALSE(isValidUtf8("\x80"));              // a continuation byte alone
  EXPECT_FALSE(isValidUtf8("\xC0\xAF"));          // overlong '/'
  EXPECT_FALSE(isValidUtf8("\xED\xA0\x80"));      // a surrogate
  EXPECT_FALSE(isValidUtf8("\xF4\x90\x80\x80"));  // past U+10FFFF
  EXPECT_FALSE(isValidUtf8("\xE4\xB8"));          // cut short
  EXPECT_FALSE(isValidUtf8("caf\xE9"));           // Latin-1
}

TEST(SafeText, DecodesBig5AndCp950LinesAndSaysSo) {
  TextRepairs repairs;
  // "// 中文註解" in Big5, then a line of UTF-8 that stays as it is.
  const std::string text =
      safeText("int a; // \xA4\xA4\xA4\xE5\xB5\xF9\xB8\xD1\nint b; // \xC3\xA9\n", &repairs);
  EXPECT_EQ(text,
            "int a; // \xE4\xB8\xAD\xE6\x96\x87\xE8\xA8\xBB\xE8\xA7\xA3\nint b; // \xC3\xA9\n");
  EXPECT_EQ(repairs.big5_lines, 1);
  EXPECT_EQ(repairs.replaced_bytes, 0);
  EXPECT_NE(repairs.describe().find("Big5 (CP950)"), std::string::npos);
  // The euro sign is CP950's (Microsoft's Big5), not in plain Big5.
  EXPECT_EQ(safeText("\xA3\xE1"), "\xE2\x82\xAC");
}

TEST(SafeText, OtherInvalidBytesBecomeReplacementCharacters) {
  TextRepairs repairs;
  // Latin-1 'é' before a space is not CP950 either; a lone continuation byte neither.
  EXPECT_EQ(safeText("caf\xE9 au lait", &repairs), "caf\xEF\xBF\xBD au lait");
  EXPECT_EQ(safeText("\x80\x80x", &repairs), "\xEF\xBF\xBD\xEF\xBF\xBDx");
  EXPECT_EQ(repairs.replaced_bytes, 3);
  EXPECT_EQ(repairs.big5_lines, 0);
}

TEST(SafeText, ControlCharactersAreEscapedLayoutKept) {
  TextRepairs repairs;
  const std::string nul("a\0b", 3);
  EXPECT_EQ(safeText(nul, &repairs), "a\\x00b");
  EXPECT_EQ(safeText("\x1B[2J\tx\r\ny\rz\x7F", &repairs), "\\x1B[2J\tx\ny\\x0Dz\\x7F");
  EXPECT_EQ(safeText("\xC2\x9B"
                     "31m \xEF\xBF\xBE",
                     &repairs),
            "\\x9B31m \\u{FFFE}");  // C1, U+FFFE
  EXPECT_EQ(repairs.escaped_controls, 6);
  EXPECT_TRUE(isValidUtf8(safeText("\xFF\xFE\x00\x01\xA4", &repairs)));
}

TEST(SafeName, OneLineAlways) {
  EXPECT_EQ(safeName("sub\nmission\t\x1B]0;title\x07"), "sub\\x0Amission\\x09\\x1B]0;title\\x07");
  EXPECT_EQ(safeName(safeName("a\x1B")), "a\\x1B");  // escaping twice changes nothing more
}

// A name can display reversed (U+202E "cloth\u202Eppc.exe"): every control of text direction is
// escaped like a control character, and counted on its own.
TEST(SafeText, TextDirectionControlsAreEscaped) {
  TextRepairs repairs;
  EXPECT_EQ(safeName("a\u202Eb\u2066c\u2069d\u200Ee\u200Ff\u061Cg\u202Ah", &repairs),
            "a\\u{202E}b\\u{2066}c\\u{2069}d\\u{200E}e\\u{200F}f\\u{61C}g\\u{202A}h");
  EXPECT_EQ(repairs.escaped_bidi, 7);
  EXPECT_EQ(repairs.escaped_controls, 0);
  EXPECT_NE(repairs.describe().find("text direction controls"), std::string::npos);
  // Letters of right-to-left scripts are text, not controls.
  EXPECT_EQ(safeText("\u05D0\u0627"), "\u05D0\u0627");
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// A fence no line of the text can close: longer than every run of backticks inside.
TEST(CodeBlock, ItsFenceIsLongerThanAnyBacktickRunInside) {
  EXPECT_EQ(codeBlock("a < b\n"), "```\na < b\n```\n");
  EXPECT_EQ(codeBlock("no newline"), "```\nno newline\n```\n");
  const std::string hostile = "x\n```\n<img src=x onerror=alert(1)>\n`````` \n";
  const std::string block = codeBlock(hostile);
  ASSERT_EQ(lines(block), lines(hostile) + 2);
  EXPECT_EQ(block.rfind("```````\n", 0), 0u) << block;  // 7 backticks: one more than 6
  EXPECT_EQ(block.substr(block.size() - 8), "```````\n") << block;
  EXPECT_EQ(block.substr(8, hostile.size()), hostile);
}

TEST(CodeSpan, DelimitedByMoreBackticksThanInsideAndOnOneLine) {
  EXPECT_EQ(codeSpan("cloth.cpp"), "`cloth.cpp`");
  EXPECT_EQ(codeSpan("a`b"), "``a`b``");
  EXPECT_EQ(codeSpan("`x`"), "`` `x` ``");
  EXPECT_EQ(codeSpan("two\n\nlines"), "`two  lines`");
  EXPECT_EQ(codeSpan(""), "` `");
  EXPECT_EQ(codeSpan(" lead"), "`  lead `");  // CommonMark strips one space each side
}

}  // namespace
}  // namespace clothref::grader
