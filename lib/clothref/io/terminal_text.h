// Text bound for a terminal (stderr, a report on stdout) that may carry names others control: a
// scene name, a JSON key, a manifest path. Control characters are shown escaped, so no name can
// move the cursor, clear the screen or retitle the window: C0 and DEL as "\x1b", C1 (U+0080 to
// U+009F, UTF-8 C2 80..C2 9F; U+009B is a one-character CSI) as "\u009b".
#pragma once

#include <string>
#include <string_view>

#include <fmt/format.h>

namespace clothref {

// `text` with its control characters escaped; with `keep_newlines`, '\n' stays (a multi-line
// report), else it is escaped too (one name, one line).
inline std::string terminalSafe(std::string_view text, bool keep_newlines = false) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if ((c < 0x20 && !(c == '\n' && keep_newlines)) || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else if (c == 0xc2 && next >= 0x80 && next <= 0x9f) {
      out += fmt::format("\\u{:04x}", next);
      ++i;
    } else {
      out += char(c);
    }
  }
  return out;
}

}  // namespace clothref
