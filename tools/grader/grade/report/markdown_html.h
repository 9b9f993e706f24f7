// The grader's Markdown as HTML, for the student's report page and for the outputs results.json
// gives as HTML (a check with a picture, the Gradescope summary): every character of the text is
// escaped first, so nothing in it becomes markup of its own.
#pragma once
#include <string>
#include <string_view>

#include "grader/grade/report/outputs.h"

namespace clothref::grader {

// Paragraphs, "- " lists, "| a | b |" tables, ``` blocks, `code`, **bold**.
std::string markdownToHtml(std::string_view markdown);

// A test's output, then its likely causes and its guesses, each group a <div> of its own
// (gr-likely, gr-guesses) holding one block per cause: never one paragraph.
std::string testHtml(const TestText& text);

}  // namespace clothref::grader
