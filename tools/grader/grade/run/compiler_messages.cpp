#include "grader/grade/run/compiler_messages.h"

#include <sstream>
#include <vector>

namespace clothref::grader {

std::string firstCompilerError(const std::string& log, const std::string& file_name) {
  std::istringstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(": error:") == std::string::npos &&
        lines[i].find("fatal error:") == std::string::npos &&
        lines[i].find("undefined reference") == std::string::npos)
      continue;
    // An error inside a file that is neither the student's nor a course or system header (an
    // `#include "/etc/shadow"`): name it, never quote its text (the rlimits fallback compiles
    // with the grader's uid, which may read it).
    const std::string location = lines[i].substr(0, lines[i].find(':'));
    if (lines[i].find("undefined reference") == std::string::npos && !location.empty() &&
        location[0] == '/' && location.rfind("/usr/", 0) != 0 &&
        location.find("/src-") == std::string::npos &&
        location.find("/course/") == std::string::npos)
      return "error in " + location + ", which is not a course header (not quoted)\n";
    std::string quote;
    for (std::size_t k = i; k < lines.size() && k < i + 3; ++k) {
      std::string line = lines[k];
      // Scratch paths say nothing to a student: keep only the file name.
      for (std::size_t at; (at = line.find("/src-")) != std::string::npos;) {
        std::size_t begin = line.rfind(' ', at);
        begin = begin == std::string::npos ? 0 : begin + 1;
        const std::size_t end = line.find(file_name, at);
        if (end == std::string::npos) break;
        line.replace(begin, end - begin, "");
      }
      if (k > i && (line.find(": error:") != std::string::npos ||
                    line.find(": note:") != std::string::npos ||
                    line.find("In function") != std::string::npos))
        break;
      quote += line + "\n";
    }
    return quote;
  }
  return lines.empty() ? std::string("(no compiler output)") : lines.front();
}

}  // namespace clothref::grader
