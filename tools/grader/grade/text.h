// Text a submission controls, made safe for every output: valid UTF-8 whatever bytes came in
// (source lines quoted in diagnoses, compiler messages, child stdout/stderr, file and folder
// names), no control characters a terminal would act on, none that XML 1.0 forbids. Every writer
// (report.cpp, batch.cpp, the CLI's stderr lines) goes through these functions.
#pragma once
#include <string>
#include <string_view>

namespace clothref::grader {

// What cleaning did to a text, so a report can say which decoding was applied.
struct TextRepairs {
  int big5_lines = 0;        // lines that were not UTF-8 but valid CP950 (Big5): decoded
  int replaced_bytes = 0;    // bytes that were neither: each became U+FFFD
  int escaped_controls = 0;  // control characters shown as \xNN
  int escaped_bidi = 0;      // text direction controls (U+202E, ...) shown as \u{NNNN}
  bool any() const { return big5_lines || replaced_bytes || escaped_controls || escaped_bidi; }
  TextRepairs& operator+=(const TextRepairs& other);
  // "lines decoded from Big5 (CP950) to UTF-8: 3; bytes that are neither replaced by U+FFFD: 2"
  // (empty when nothing was done).
  std::string describe() const;
};

// True when `bytes` is well-formed UTF-8 (no overlong forms, surrogates or code points past
// U+10FFFF).
bool isValidUtf8(std::string_view bytes);

// Multi-line text (a diagnosis, a quoted compiler error, a child's stderr): each line that is not
// UTF-8 is decoded from CP950 (Big5) when it is valid CP950, else its invalid bytes become
// U+FFFD; CRLF becomes LF; control characters other than newline and tab, and the non-characters
// U+FFFE / U+FFFF, are shown as \xNN (or \u{FFFE}); so are the controls of text direction
// (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069), which would let a name display
// reversed. The result is valid UTF-8 and valid XML 1.0 character data (before markup escaping).
std::string safeText(std::string_view text, TextRepairs* repairs = nullptr);

// A name or path on one line (stderr, report headings, CSV cells): as safeText, and newline and
// tab are escaped too, so a name never breaks a line nor moves the cursor.
std::string safeName(std::string_view name, TextRepairs* repairs = nullptr);

// Markdown that shows `text` as it is, whatever it holds, in every renderer (CommonMark,
// Gradescope's, python-markdown, report/markdown_html.h's): every text a submission or a tool
// controls (compiler output, a probe's stderr, quoted source lines, names) reaches Markdown only
// through these two. Neither cleans the text: give it safeText / safeName output (the writers clean
// again, which changes no backtick).
//
// A fenced block: its fence is a run of backticks longer than the longest run inside `text` (at
// least three), so no line of the text can close it; it starts and ends on a line of its own
// (a newline is added when `text` does not end with one).
std::string codeBlock(std::string_view text);
// An inline code span on one line: delimited by a run of backticks longer than any inside, padded
// with a space where the text starts or ends with a backtick or a space; line breaks become
// spaces (a blank line would end the paragraph, and the span with it).
std::string codeSpan(std::string_view text);

}  // namespace clothref::grader
