#include "pages/html.h"

#include <cstdint>
#include <stdexcept>

namespace clothref::pages {

namespace {

// Length of the valid UTF-8 sequence starting at text[i], or 0 (overlong forms, surrogates and
// code points above U+10FFFF are invalid, as in RFC 3629).
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  std::uint32_t code = 0;
  if ((lead & 0xE0) == 0xC0) {
    length = 2;
    code = lead & 0x1F;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3;
    code = lead & 0x0F;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4;
    code = lead & 0x07;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  static constexpr std::uint32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < kSmallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

// U+200E, U+200F, U+202A..U+202E, U+2066..U+2069 (three bytes each in UTF-8).
bool isBidiControl(std::string_view c) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(c[k]); };
  if (b(0) != 0xE2) return false;
  if (b(1) == 0x80) return b(2) == 0x8E || b(2) == 0x8F || (b(2) >= 0xAA && b(2) <= 0xAE);
  return b(1) == 0x81 && b(2) >= 0xA6 && b(2) <= 0xA9;
}

std::string bidiCode(std::string_view c) {
  const unsigned code = ((static_cast<unsigned char>(c[0]) & 0x0Fu) << 12) |
                        ((static_cast<unsigned char>(c[1]) & 0x3Fu) << 6) |
                        (static_cast<unsigned char>(c[2]) & 0x3Fu);
  static const char* const kHex = "0123456789ABCDEF";
  std::string out;
  for (int shift = 12; shift >= 0; shift -= 4) out += kHex[(code >> shift) & 0xF];
  return out;
}

}  // namespace

std::string escapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = utf8Length(text, i);
    if (length == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD
      ++i;
      continue;
    }
    if (length == 3 && isBidiControl(text.substr(i, 3))) {
      // a control of text direction would display what follows in another order: shown
      out += "\\u{" + bidiCode(text.substr(i, 3)) + "}";
      i += length;
      continue;
    }
    if (length == 2 && text.compare(i, 2, "\xD8\x9C") == 0) {  // U+061C ARABIC LETTER MARK
      out += "\\u{61C}";
      i += length;
      continue;
    }
    if (length > 1) {
      out.append(text.substr(i, length));
      i += length;
      continue;
    }
    const char c = text[i++];
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        break;
    }
  }
  return out;
}

std::string jsonForScript(const nlohmann::ordered_json& data) {
  const std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(json.size() + json.size() / 64);
  for (const char c : json) {
    // outside strings JSON has none of these, so escaping them everywhere is safe
    if (c == '<')
      out += "\\u003c";
    else if (c == '>')
      out += "\\u003e";
    else if (c == '&')
      out += "\\u0026";
    else
      out += c;
  }
  return out;
}

std::string base64(const void* bytes, std::size_t size) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const unsigned char*>(bytes);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v =
        (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i < size) {
    std::uint32_t v = std::uint32_t(in[i]) << 16;
    if (i + 1 < size) v |= std::uint32_t(in[i + 1]) << 8;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < size ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string fillTemplate(std::string_view page,
                         const std::vector<std::pair<std::string, std::string>>& values) {
  std::vector<bool> used(values.size(), false);
  std::string out;
  out.reserve(page.size());
  std::size_t at = 0;
  while (true) {
    const std::size_t open = page.find("{{", at);
    if (open == std::string_view::npos) break;
    const std::size_t close = page.find("}}", open + 2);
    if (close == std::string_view::npos) break;
    const std::string_view name = page.substr(open + 2, close - open - 2);
    std::size_t k = 0;
    while (k < values.size() && values[k].first != name) ++k;
    if (k == values.size())
      throw std::logic_error("page template: no value for {{" + std::string(name) + "}}");
    used[k] = true;
    out.append(page.substr(at, open - at));
    out += values[k].second;
    at = close + 2;
  }
  out.append(page.substr(at));
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!used[k])
      throw std::logic_error("page template: no placeholder {{" + values[k].first + "}}");
  return out;
}

}  // namespace clothref::pages
