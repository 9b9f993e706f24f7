// Patterns in a student's source (source_patterns.h).
#include "grader/grade/submission/source_patterns.h"

#include <regex>
#include <sstream>

namespace clothref::grader {

std::vector<SourceQuote> autoExpressionLines(const std::string& file, const std::string& source) {
  std::istringstream in(source);
  static const std::regex declaration(R"(\bauto\s*&{0,2}\s*\w+\s*=\s*([^;]*);)");
  static const std::regex over_state(
      R"((position|velocity|acceleration)\s*\([^;]*\)\s*[-+*/]|[-+*/]\s*[\w>.-]*(position|velocity|acceleration)\s*\()");
  static const std::regex plain_value(
      R"(\.\s*(normalized|eval|norm|squaredNorm|stableNorm|sum|dot|cross3|cross|value)\s*\([^()]*\)\s*$)");
  std::vector<SourceQuote> lines;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    std::smatch match;
    if (!std::regex_search(line, match, declaration)) continue;
    const std::string value = match[1].str();
    if (!std::regex_search(value, over_state) || std::regex_search(value, plain_value)) continue;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back({file, number, line.substr(line.find_first_not_of(" \t"))});
  }
  return lines;
}

SourceHints sourceHints(const std::string& source) {
  SourceHints hints;
  const auto has = [&](const char* pattern) {
    return std::regex_search(source, std::regex(pattern));
  };
  hints.alias_backup =
      has(R"(auto\s*&?\s*\w+\s*=\s*particles\s*;)") ||
      has(R"(std::vector\s*<\s*Particles\s*\*\s*>\s*\w+\s*(=\s*particles|\(\s*particles\s*\)|\{\s*particles\s*\}))") ||
      has(R"(Eigen::Ref\s*<)") ||
      has(R"(auto\s*&?\s*\w+\s*=\s*\w+\s*(->|\.)\s*(position|velocity)\s*\(\s*\)\s*;)");
  hints.value_backup = has(R"(std::vector\s*<\s*(Particles|Eigen::Matrix4Xf)\s*>)") ||
                       has(R"((Particles|Eigen::Matrix4Xf)\s+\w+\s*(=|\(|\{|;))");
  hints.integer_half = has(R"((^|[^.\w])1\s*/\s*2(?![.\w]))");
  hints.integer_sixth = has(R"((^|[^.\w])1\s*/\s*6(?![.\w]))");
  return hints;
}

}  // namespace clothref::grader
