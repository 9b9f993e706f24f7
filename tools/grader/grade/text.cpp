#include "grader/grade/text.h"

#include <iconv.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <vector>

namespace clothref::grader {
namespace {

// The length of the well-formed UTF-8 sequence at `i` and its code point, or 0 when the bytes
// there are not one (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF).
std::size_t sequenceAt(std::string_view s, std::size_t i, char32_t& code) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) {
    code = c;
    return 1;
  }
  std::size_t length = 0;
  char32_t min = 0;
  if ((c & 0xE0) == 0xC0) {
    length = 2, code = c & 0x1F, min = 0x80;
  } else if ((c & 0xF0) == 0xE0) {
    length = 3, code = c & 0x0F, min = 0x800;
  } else if ((c & 0xF8) == 0xF0) {
    length = 4, code = c & 0x07, min = 0x10000;
  } else {
    return 0;  // a continuation byte alone, or 0xF8..0xFF
  }
  if (i + length > s.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

// CP950 (Microsoft's Big5) to UTF-8 with glibc's iconv; false when the bytes are not valid CP950.
bool decodeCp950(std::string_view in, std::string& out) {
  iconv_t cd = iconv_open("UTF-8", "CP950");
  if (cd == reinterpret_cast<iconv_t>(-1)) return false;
  std::vector<char> input(in.begin(), in.end());
  std::string result(in.size() * 3 + 4, '\0');  // a CP950 character is at most 3 UTF-8 bytes
  char* from = input.data();
  std::size_t from_left = input.size();
  char* to = result.data();
  std::size_t to_left = result.size();
  const std::size_t done = iconv(cd, &from, &from_left, &to, &to_left);
  iconv_close(cd);
  if (done == static_cast<std::size_t>(-1) || from_left != 0) return false;
  result.resize(result.size() - to_left);
  out = std::move(result);
  return true;
}

// U+0080..U+009F, encoded C2 80..C2 9F.
bool hasC1(std::string_view utf8) {
  for (std::size_t i = 0; i + 1 < utf8.size(); ++i)
    if (static_cast<unsigned char>(utf8[i]) == 0xC2 &&
        static_cast<unsigned char>(utf8[i + 1]) >= 0x80 &&
        static_cast<unsigned char>(utf8[i + 1]) <= 0x9F)
      return true;
  return false;
}

// The controls of text direction (Unicode's Bidi_Control): embeddings, overrides, isolates and
// marks. Shown escaped, they can no longer make a name display in another order than its bytes.
bool isBidiControl(char32_t code) {
  return code == 0x061C || code == 0x200E || code == 0x200F || (code >= 0x202A && code <= 0x202E) ||
         (code >= 0x2066 && code <= 0x2069);
}

// The longest run of backticks in `text`.
std::size_t longestBacktickRun(std::string_view text) {
  std::size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == '`' ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return longest;
}

void appendEscape(std::string& out, char32_t code) {
  char buffer[16];
  if (code < 0x100)
    std::snprintf(buffer, sizeof buffer, "\\x%02X", static_cast<unsigned>(code));
  else
    std::snprintf(buffer, sizeof buffer, "\\u{%X}", static_cast<unsigned>(code));
  out += buffer;
}

// One line (a '\n' inside only for names, `escape_layout`): decoded or repaired to UTF-8, controls
// escaped (tab and newline too when `escape_layout`).
std::string cleanLine(std::string_view line, bool escape_layout, TextRepairs* repairs) {
  TextRepairs local;
  std::string decoded;
  // glibc's CP950 maps a lone 0x80 to U+0080: a line that decodes to C1 controls is not Big5.
  if (!isValidUtf8(line) && decodeCp950(line, decoded) && isValidUtf8(decoded) && !hasC1(decoded)) {
    ++local.big5_lines;
    line = decoded;
  }
  std::string out;
  out.reserve(line.size());
  for (std::size_t i = 0; i < line.size();) {
    char32_t code = 0;
    const std::size_t length = sequenceAt(line, i, code);
    if (length == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD
      ++local.replaced_bytes;
      ++i;
      continue;
    }
    const bool layout = code == '\t' || code == '\n';
    const bool control = code < 0x20 || code == 0x7F || (code >= 0x80 && code <= 0x9F) ||
                         code == 0xFFFE || code == 0xFFFF;
    if (control && !(layout && !escape_layout)) {
      appendEscape(out, code);
      ++local.escaped_controls;
    } else if (isBidiControl(code)) {
      appendEscape(out, code);
      ++local.escaped_bidi;
    } else {
      out.append(line.substr(i, length));
    }
    i += length;
  }
  if (repairs) *repairs += local;
  return out;
}

}  // namespace

TextRepairs& TextRepairs::operator+=(const TextRepairs& other) {
  big5_lines += other.big5_lines;
  replaced_bytes += other.replaced_bytes;
  escaped_controls += other.escaped_controls;
  escaped_bidi += other.escaped_bidi;
  return *this;
}

std::string TextRepairs::describe() const {
  std::string out;
  const auto add = [&](int count, const char* what) {
    if (count) out += (out.empty() ? "" : "; ") + std::string(what) + ": " + std::to_string(count);
  };
  add(big5_lines, "lines decoded from Big5 (CP950) to UTF-8");
  add(replaced_bytes, "bytes that are neither UTF-8 nor CP950 replaced by U+FFFD");
  add(escaped_controls, "control characters shown as \\xNN");
  add(escaped_bidi, "text direction controls shown as \\u{NNNN}");
  return out;
}

bool isValidUtf8(std::string_view bytes) {
  char32_t code = 0;
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t length = sequenceAt(bytes, i, code);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

std::string safeText(std::string_view text, TextRepairs* repairs) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t begin = 0; begin <= text.size();) {
    std::size_t end = text.find('\n', begin);
    const bool last = end == std::string_view::npos;
    if (last) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    if (!last && !line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF -> LF
    out += cleanLine(line, false, repairs);
    if (last) break;
    out += '\n';
    begin = end + 1;
  }
  return out;
}

std::string safeName(std::string_view name, TextRepairs* repairs) {
  return cleanLine(name, true, repairs);
}

std::string codeBlock(std::string_view text) {
  const std::string fence(std::max<std::size_t>(3, longestBacktickRun(text) + 1), '`');
  std::string out = fence + "\n";
  out += text;
  if (!text.empty() && text.back() != '\n') out += '\n';
  return out + fence + "\n";
}

std::string codeSpan(std::string_view text) {
  std::string inside(text);
  for (char& c : inside)
    if (c == '\n' || c == '\r') c = ' ';
  if (inside.empty()) return "` `";
  const std::string fence(longestBacktickRun(inside) + 1, '`');
  const bool pad = inside.front() == '`' || inside.back() == '`' || inside.front() == ' ' ||
                   inside.back() == ' ';
  return fence + (pad ? " " : "") + inside + (pad ? " " : "") + fence;
}

}  // namespace clothref::grader
