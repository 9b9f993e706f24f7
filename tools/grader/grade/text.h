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
  bool any() const { return big5_lines || replaced_bytes || escaped_controls; }
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
// U+FFFE / U+FFFF, are shown as \xNN (or \u{FFFE}). The result is valid UTF-8 and valid XML 1.0
// character data (before markup escaping).
std::string safeText(std::string_view text, TextRepairs* repairs = nullptr);

// A name or path on one line (stderr, report headings, CSV cells): as safeText, and newline and
// tab are escaped too, so a name never breaks a line nor moves the cursor.
std::string safeName(std::string_view name, TextRepairs* repairs = nullptr);

}  // namespace clothref::grader
