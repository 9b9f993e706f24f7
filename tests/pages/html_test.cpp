// What every page shares (tools/pages/html.cpp): escaping, JSON in a script element, base64 and
// the template filler.
#include "pages/html.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace clothref::pages {
namespace {

TEST(Html, EscapesMarkupQuotesAndBadBytes) {
  EXPECT_EQ(escapeHtml("a<b>&\"'c"), "a&lt;b&gt;&amp;&quot;&#39;c");
  EXPECT_EQ(escapeHtml("caf\xC3\xA9 \xE2\x9C\x93"), "caf\xC3\xA9 \xE2\x9C\x93");  // UTF-8 kept
  EXPECT_EQ(escapeHtml("\xFF"), "\xEF\xBF\xBD");                                  // not UTF-8
  EXPECT_EQ(escapeHtml("\xC0\xAF"), "\xEF\xBF\xBD\xEF\xBF\xBD");                  // overlong '/'
  EXPECT_EQ(escapeHtml("\xED\xA0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // surrogate
  EXPECT_EQ(escapeHtml("\xE2\x9C"), "\xEF\xBF\xBD\xEF\xBF\xBD");                  // cut sequence
  EXPECT_EQ(escapeHtml(std::string("a\0b\x1b[31m\tc\n", 11)), "ab[31m\tc\n");
}

TEST(Html, JsonCannotCloseItsScriptElement) {
  const nlohmann::ordered_json data = {{"name", "</script><script>x()</script>&"}, {"bad", "\xFF"}};
  const std::string text = jsonForScript(data);
  EXPECT_EQ(text.find('<'), std::string::npos);
  EXPECT_EQ(text.find('>'), std::string::npos);
  EXPECT_EQ(text.find('&'), std::string::npos);
  const auto back = nlohmann::json::parse(text);
  EXPECT_EQ(back["name"], "</script><script>x()</script>&");
  EXPECT_EQ(back["bad"], "\xEF\xBF\xBD");
}

TEST(Html, Base64MatchesRfc4648) {
  // the test vectors of RFC 4648 section 10
  const char* cases[][2] = {{"", ""},
                            {"f", "Zg=="},
                            {"fo", "Zm8="},
                            {"foo", "Zm9v"},
                            {"foob", "Zm9vYg=="},
                            {"fooba", "Zm9vYmE="},
                            {"foobar", "Zm9vYmFy"}};
  for (const auto& c : cases) EXPECT_EQ(base64(c[0], std::string(c[0]).size()), c[1]) << c[0];
  const unsigned char high[] = {0xFF, 0xFE, 0xFD};
  EXPECT_EQ(base64(high, 3), "//79");
}

TEST(Html, TemplateFillsEachPlaceholderOnce) {
  EXPECT_EQ(fillTemplate("<p>{{A}} and {{B}}, {{A}}</p>", {{"A", "{{B}}"}, {"B", "b"}}),
            "<p>{{B}} and b, {{B}}</p>");
  EXPECT_THROW(fillTemplate("{{A}} {{C}}", {{"A", "a"}}), std::logic_error);
  EXPECT_THROW(fillTemplate("{{A}}", {{"A", "a"}, {"B", "b"}}), std::logic_error);
}

}  // namespace
}  // namespace clothref::pages
