// The grader's Markdown as HTML (tools/grader/grade/report/markdown_html.cpp): every character
// escaped, the likely causes and the guesses in blocks of their own.
#include "grader/grade/report/markdown_html.h"

#include <gtest/gtest.h>

#include <string>

#include "report_samples.h"

namespace clothref::grader {
namespace {

TEST(MarkdownHtml, MarkdownBecomesEscapedHtml) {
  const std::string html =
      markdownToHtml("text with `code` and **bold** <i>\n\n- one\n  - two\n\n```\na < b\n```\n");
  EXPECT_EQ(html,
            "<p>text with <code>code</code> and <strong>bold</strong> &lt;i&gt;</p>\n"
            "<ul>\n<li>one\n<ul>\n<li>two</li>\n</ul>\n</li>\n</ul>\n<pre><code>a &lt; b\n"
            "</code></pre>\n");
}

// A comparison's note under it ("  - y differs by ...") is a list inside its item, as CommonMark
// reads it; a line back at the outer indent closes the inner list.
TEST(MarkdownHtml, AnIndentedItemIsAListInsideTheItemAbove) {
  EXPECT_EQ(markdownToHtml("- a\n  - b\n  - c\n- d\ntext\n"),
            "<ul>\n<li>a\n<ul>\n<li>b</li>\n<li>c</li>\n</ul>\n</li>\n<li>d</li>\n</ul>\n"
            "<p>text</p>\n");
  EXPECT_EQ(markdownToHtml("  - x\n- y\n"), "<ul>\n<li>x</li>\n<li>y</li>\n</ul>\n");
}

// The summary's file table (report.cpp's filesSection) must not reach Gradescope as raw pipes.
TEST(MarkdownHtml, MarkdownTablesBecomeHtmlTables) {
  const std::string html = markdownToHtml(
      "before\n| file | used |\n|---|---|\n| cloth.cpp | `a<b` |\n| x.cpp |  |\nafter\n");
  EXPECT_EQ(html,
            "<p>before</p>\n<table>\n<tr><th>file</th><th>used</th></tr>\n"
            "<tr><td>cloth.cpp</td><td><code>a&lt;b</code></td></tr>\n"
            "<tr><td>x.cpp</td><td></td></tr>\n</table>\n<p>after</p>\n");
}

// A check's likely causes and its guesses: each group a block of its own, each cause a paragraph,
// never run into the output's last paragraph nor into each other.
TEST(MarkdownHtml, LikelyCausesAndGuessesAreBlocksOfTheirOwn) {
  TestText text;
  text.output = "Expected 1, yours 2.";
  text.likely = {"**Likely cause** (`a`): one.\n", "**Likely cause** (`b`): two.\n"};
  text.guesses = {"**Possible cause (a guess)** (`c`): three.\n"};
  const std::string html = testHtml(text);
  EXPECT_EQ(html,
            "<p>Expected 1, yours 2.</p>\n"
            "<div class=\"gr-likely\"><p><strong>Likely cause</strong> (<code>a</code>): one.</p>\n"
            "<p><strong>Likely cause</strong> (<code>b</code>): two.</p>\n</div>\n"
            "<div class=\"gr-guesses\"><p><strong>Possible cause (a guess)</strong> "
            "(<code>c</code>): three.</p>\n</div>\n");
  // the Markdown the other writers show: each block after a blank line
  EXPECT_EQ(text.markdown(),
            "Expected 1, yours 2.\n\n**Likely cause** (`a`): one.\n\n**Likely cause** (`b`): "
            "two.\n\n**Possible cause (a guess)** (`c`): three.\n");
}

}  // namespace
}  // namespace clothref::grader
