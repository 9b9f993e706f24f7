#include "grader/grade/run/compiler_messages.h"

#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxLogLines = 200;

std::vector<std::string> splitLines(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A line of gcc's source excerpt under a message ("   12 |   x = 1;", "      |   ^~", "  +++ |+").
bool isExcerpt(const std::string& line) {
  static const std::regex excerpt(R"(^\s*(\d+|\+\+\+)?\s*\|)");
  return std::regex_search(line, excerpt);
}

// The linker's own lines: they name symbols and objects, never a file's text.
bool isLinkMessage(const std::string& line) {
  return line.rfind("/usr/bin/ld:", 0) == 0 || line.rfind("ld:", 0) == 0 ||
         line.rfind("collect2:", 0) == 0 || line.find("undefined reference") != std::string::npos ||
         line.find("multiple definition of") != std::string::npos;
}

bool isError(const std::string& line) {
  return line.find(": error:") != std::string::npos ||
         line.find("fatal error:") != std::string::npos ||
         line.find("undefined reference") != std::string::npos;
}

// The file a message is about, as gcc printed it ("" for a line that names none): the text before
// "file:line:col:", "file: In function ...", or after "In file included from" / "from".
std::string locationOf(const std::string& line) {
  static const std::regex included(R"(^(?:In file included from|\s+from) (.+?):\d+[:,]?\s*$)");
  static const std::regex located(R"(^([^:\s][^:]*):(?:\d+:(?:\d+:)?| In |\s*$))");
  std::smatch match;
  if (std::regex_search(line, match, included)) return match[1].str();
  if (std::regex_search(line, match, located)) return match[1].str();
  return {};
}

// A location that is the compiler or a pseudo-file (cc1plus, <command-line>): its messages quote
// no file.
bool isToolLocation(const std::string& location) {
  return location.find('/') == std::string::npos &&
         (location.find('.') == std::string::npos || location.front() == '<');
}

fs::path resolved(const std::string& printed, const fs::path& work_dir) {
  fs::path path(printed);
  if (path.is_relative()) path = work_dir / path;
  std::error_code error;
  fs::path canonical = fs::weakly_canonical(path, error);
  return error ? path.lexically_normal() : canonical;
}

bool isBelow(const fs::path& path, const fs::path& dir) {
  const auto mismatch = std::mismatch(dir.begin(), dir.end(), path.begin(), path.end());
  return mismatch.first == dir.end() && mismatch.second != path.end();
}

// Whether `source` has a line directive (`#line 12 "name"`, or GCC's `# 12 "name"`): a message may
// then be located in a file name the student made up.
bool hasLineDirective(const fs::path& source) {
  std::ifstream in(source, std::ios::binary);
  static const std::regex directive(R"(^\s*#\s*(line\s+)?[0-9])");
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, directive)) return true;
  return false;
}

struct Site {
  const CompileSite& given;
  fs::path student;                                       // canonical
  fs::path work;                                          // canonical
  std::vector<std::pair<fs::path, std::string>> headers;  // canonical
  bool renames = false;                                   // the student's file has a line directive
  explicit Site(const CompileSite& site) : given(site) {
    std::error_code error;
    if (!site.student_file.empty()) student = resolved(site.student_file.string(), site.work_dir);
    work = fs::weakly_canonical(site.work_dir, error);
    if (error) work = site.work_dir.lexically_normal();
    for (const auto& [dir, shown] : site.header_dirs) headers.push_back({resolved(dir, {}), shown});
    renames = !student.empty() && hasLineDirective(student);
  }
  bool isStudent(const fs::path& path) const { return !student.empty() && path == student; }
  // A name the student's own line directive gave its file: it names no file there is (so no
  // excerpt of another file can come with it), and the student's file renames itself.
  bool isRenamed(const fs::path& path) const {
    std::error_code error;
    return renames && !fs::exists(path, error) && !error;
  }
  bool isHeader(const fs::path& path) const {
    for (const auto& [dir, shown] : headers)
      if (isBelow(path, dir)) return true;
    return false;
  }
};

void replaceAll(std::string& line, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t at = 0; (at = line.find(from, at)) != std::string::npos; at += to.size())
    line.replace(at, from.size(), to);
}

// `line` with the paths a student does not know cut: their file by its name, the course headers
// by theirs, the scratch folder removed.
std::string cleanLine(std::string line, const std::string& location, const Site& site) {
  if (!location.empty() && site.isStudent(resolved(location, site.given.work_dir)))
    replaceAll(line, location, site.given.file_name);
  for (const fs::path& path : {site.given.student_file, site.student})
    replaceAll(line, path.string(), site.given.file_name);
  for (std::size_t k = 0; k < site.headers.size(); ++k) {
    replaceAll(line, site.given.header_dirs[k].first.string() + "/", site.headers[k].second);
    replaceAll(line, site.headers[k].first.string() + "/", site.headers[k].second);
  }
  for (const fs::path& dir : {site.given.work_dir, site.work})
    if (!dir.empty()) replaceAll(line, dir.string() + "/", "");
  return line;
}

// Whether a message located at `location` may be quoted, and the name of the file when not.
// `excerpt` says whether the source lines under it may be too (not for a renamed file: gcc found
// no file by that name, and the student's own text is in the message).
bool quotable(const std::string& location, const Site& site, std::string& named,
              bool* excerpt = nullptr) {
  if (excerpt) *excerpt = true;
  if (location.empty() || isToolLocation(location)) return true;
  const fs::path path = resolved(location, site.given.work_dir);
  if (site.isStudent(path) || site.isHeader(path)) return true;
  if (site.isRenamed(path)) {
    if (excerpt) *excerpt = false;
    return true;
  }
  named = isBelow(path, site.work) ? path.lexically_relative(site.work).string() : path.string();
  return false;
}

}  // namespace

std::vector<std::pair<fs::path, std::string>> courseHeaderDirs(const fs::path& course_dir,
                                                               int edition,
                                                               const fs::path& eigen_include) {
  return {{course_dir / std::to_string(edition) / "include", ""},
          {course_dir / "common" / "include", ""},
          {eigen_include, eigen_include.string() + "/"},
          {"/usr/include", "/usr/include/"},
          {"/usr/local/include", "/usr/local/include/"},
          {"/usr/lib/gcc", "/usr/lib/gcc/"}};
}

std::string firstCompilerError(const std::string& log, const CompileSite& given) {
  const Site site(given);
  const std::vector<std::string> lines = splitLines(log);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!isError(lines[i])) continue;
    const bool link = isLinkMessage(lines[i]);
    const std::string location = link ? std::string() : locationOf(lines[i]);
    std::string named;
    bool with_excerpt = true;
    if (!quotable(location, site, named, &with_excerpt))
      return "error in " + named + ", which is not a course header (not quoted)\n";
    std::string quote = cleanLine(lines[i], location, site) + "\n";
    // what belongs to it: a message of several lines (a static_assert's text), its excerpt
    // (at most four lines of text and two of excerpt)
    int text_lines = 0, excerpt_lines = 0;
    for (std::size_t k = i + 1; k < lines.size(); ++k) {
      const bool excerpt = isExcerpt(lines[k]);
      if (!excerpt && (isLinkMessage(lines[k]) || !locationOf(lines[k]).empty())) break;
      if (lines[k].empty() || (excerpt && !with_excerpt)) continue;
      if ((excerpt ? ++excerpt_lines : ++text_lines) > (excerpt ? 2 : 4)) break;
      quote += cleanLine(lines[k], location, site) + "\n";
    }
    return quote;
  }
  if (lines.empty()) return "(no compiler output)";
  std::string named;
  const std::string location = locationOf(lines.front());
  if (!quotable(location, site, named)) return "a message about " + named + " (not quoted)";
  return cleanLine(lines.front(), location, site);
}

std::string compilerLog(const std::string& log, const CompileSite& given) {
  const Site site(given);
  const std::vector<std::string> lines = splitLines(log);
  std::string out;
  std::size_t kept = 0, left_out = 0;
  bool keeping = false;  // the current message's excerpt lines follow it
  bool keeping_excerpt = false;
  for (const std::string& line : lines) {
    if (line.empty()) continue;
    if (isExcerpt(line)) {
      if (keeping && keeping_excerpt && kept < kMaxLogLines) {
        out += line + "\n";
        ++kept;
      } else {
        ++left_out;
      }
      continue;
    }
    const bool link = isLinkMessage(line);
    const std::string location = link ? std::string() : locationOf(line);
    // a line without a place of its own continues the message before it (a text of several lines)
    if (link || !location.empty()) {
      const fs::path path = resolved(location, site.given.work_dir);
      keeping = link || site.isStudent(path) || site.isRenamed(path);
      keeping_excerpt = link || site.isStudent(path);
    }
    if (!keeping) {
      ++left_out;
      continue;
    }
    if (kept < kMaxLogLines) {
      out += cleanLine(line, location, site) + "\n";
      ++kept;
    } else {
      ++left_out;
    }
  }
  if (out.empty() || out == firstCompilerError(log, given)) return {};
  if (left_out)
    out += "(" + std::to_string(left_out) + " line" + (left_out == 1 ? "" : "s") +
           " about other files or past " + std::to_string(kMaxLogLines) + " lines left out)\n";
  return out;
}

}  // namespace clothref::grader
