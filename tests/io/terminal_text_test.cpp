// terminalSafe (lib/clothref/io/terminal_text.h): every control character a name could carry is
// shown escaped; printable text, UTF-8 letters and (when asked) newlines pass unchanged.
#include "clothref/io/terminal_text.h"

#include <gtest/gtest.h>

namespace clothref {
namespace {

TEST(TerminalText, ControlCharactersAreEscaped) {
  EXPECT_EQ(terminalSafe("\x1b[2J\x07\x7f"), "\\x1b[2J\\x07\\x7f");
  EXPECT_EQ(terminalSafe("a\nb\tc\rd"), "a\\x0ab\\x09c\\x0dd");
  EXPECT_EQ(terminalSafe("a\nb\x1b", true), "a\nb\\x1b");
  // C1 controls in UTF-8: U+009B is a one-character CSI
  EXPECT_EQ(terminalSafe("x\xc2\x9b"
                         "31m\xc2\x80"),
            "x\\u009b31m\\u0080");
  EXPECT_EQ(terminalSafe(std::string_view("nul\0end", 7)), "nul\\x00end");
}

TEST(TerminalText, PrintableTextIsUnchanged) {
  EXPECT_EQ(terminalSafe("course2022 rk4 /scene/cloth/spring_coef: 25000"),
            "course2022 rk4 /scene/cloth/spring_coef: 25000");
  EXPECT_EQ(terminalSafe("\xc2\xa0 \xc3\xa9 \xe2\x80\x94 ζ"), "\xc2\xa0 \xc3\xa9 \xe2\x80\x94 ζ");
  EXPECT_EQ(terminalSafe(""), "");
  EXPECT_EQ(terminalSafe("\xc2"), "\xc2");  // a cut sequence is left to the terminal
}

}  // namespace
}  // namespace clothref
