#include "grader/grade/submission/source_text.h"

#include <algorithm>
#include <cstddef>
#include <regex>
#include <string>
#include <utility>

namespace clothref::grader {

std::string blankedCode(const std::string& source) {
  std::string out = source;
  const auto blank = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to && k < out.size(); ++k)
      if (out[k] != '\n') out[k] = ' ';
  };
  for (std::size_t i = 0; i < source.size();) {
    if (source.compare(i, 2, "//") == 0) {
      const std::size_t end = std::min(source.find('\n', i), source.size());
      blank(i, end);
      i = end;
    } else if (source.compare(i, 2, "/*") == 0) {
      const std::size_t close = source.find("*/", i + 2);
      const std::size_t end = close == std::string::npos ? source.size() : close + 2;
      blank(i, end);
      i = end;
    } else if (source[i] == '"' || source[i] == '\'') {
      const char quote = source[i];
      std::size_t k = i + 1;
      for (; k < source.size() && source[k] != quote && source[k] != '\n'; ++k)
        if (source[k] == '\\') ++k;
      blank(i, k + 1);
      i = k + 1;
    } else {
      ++i;
    }
  }
  return out;
}

namespace {

int lineAt(const std::string& text, std::size_t offset) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + long(offset), '\n'));
}

// The offsets of the braces around the body of `stub` in `code` (blanked): {open, close}, close =
// code.size() when the body never closes; {npos, npos} when the file defines no such function.
std::pair<std::size_t, std::size_t> stubSpan(const std::string& code, const std::string& stub) {
  // "Spheres::collide(Cloth*)" -> the name, and what its parameters must look like
  const std::size_t paren = stub.find('(');
  const std::string name = stub.substr(0, paren);
  const std::string wanted_params =
      paren == std::string::npos ? std::string() : stub.substr(paren + 1, stub.size() - paren - 2);
  const bool check_params = paren != std::string::npos;
  const std::size_t colons = name.find("::");
  const std::regex head("\\b" + name.substr(0, colons) + "\\s*::\\s*" + name.substr(colons + 2) +
                        "\\s*\\(");
  for (auto it = std::sregex_iterator(code.begin(), code.end(), head); it != std::sregex_iterator();
       ++it) {
    std::size_t k = std::size_t(it->position() + it->length());  // after '('
    int depth = 1;
    const std::size_t params_begin = k;
    for (; k < code.size() && depth > 0; ++k) depth += code[k] == '(' ? 1 : code[k] == ')' ? -1 : 0;
    if (depth != 0) break;
    std::string params = code.substr(params_begin, k - 1 - params_begin);
    params.erase(std::remove_if(params.begin(), params.end(),
                                [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
                 params.end());
    if (check_params) {
      const bool wants_none = wanted_params.empty();
      const bool none = params.empty() || params == "void";
      if (wants_none != none) continue;
      if (!wants_none &&
          params.find(wanted_params.substr(0, wanted_params.find('*'))) == std::string::npos)
        continue;
    }
    const std::size_t open = code.find_first_of("{;", k);
    if (open == std::string::npos || code[open] == ';') continue;  // a declaration
    int braces = 0;
    for (std::size_t e = open; e < code.size(); ++e) {
      braces += code[e] == '{' ? 1 : code[e] == '}' ? -1 : 0;
      if (braces == 0) return {open, e};
    }
    return {open, code.size()};
  }
  return {std::string::npos, std::string::npos};
}

}  // namespace

StubLines stubLines(const std::string& source, const std::string& stub) {
  const std::string code = blankedCode(source);
  const auto [open, close] = stubSpan(code, stub);
  if (open == std::string::npos) return {};
  return {lineAt(code, open), lineAt(code, close)};
}

std::string stubCode(const std::string& source, const std::string& stub) {
  const std::string code = blankedCode(source);
  const auto [open, close] = stubSpan(code, stub);
  if (open == std::string::npos) return "";
  return code.substr(open, close - open + 1);
}

}  // namespace clothref::grader
