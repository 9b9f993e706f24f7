#include "submission.h"

#include <algorithm>
#include <regex>
#include <sstream>

#include "clothref/io/error.h"
#include "clothref/io/files.h"

namespace clothref::grader {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Student files are small; a huge one is refused rather than read.
constexpr std::size_t kMaxSourceBytes = 16u << 20;

std::string readSource(const std::filesystem::path& path) {
  return readFile(path, "student file", kMaxSourceBytes);
}

bool isUtf8(const std::string& bytes) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= bytes.size() + (extra == 0 ? 1 : 0))
      return false;
    for (int k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(bytes[i + static_cast<std::size_t>(k)]) >> 6) != 2)
        return false;
    i += static_cast<std::size_t>(extra) + 1;
  }
  return true;
}

// Removes comments and string literals so a definition in a comment does not decide the edition.
std::string codeOnly(const std::string& source) {
  std::string out;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (source.compare(i, 2, "//") == 0) {
      while (i < source.size() && source[i] != '\n') ++i;
      out += '\n';
    } else if (source.compare(i, 2, "/*") == 0) {
      const std::size_t end = source.find("*/", i + 2);
      i = end == std::string::npos ? source.size() : end + 1;
      out += ' ';
    } else if (source[i] == '"') {
      for (++i; i < source.size() && source[i] != '"'; ++i)
        if (source[i] == '\\') ++i;
      out += "\"\"";
    } else {
      out += source[i];
    }
  }
  return out;
}

}  // namespace

SubmissionFiles findSubmissionFiles(const std::filesystem::path& dir) {
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error))
    throw InputError(dir.string() +
                     ": not a directory (a submission is a directory holding "
                     "cloth.cpp, sphere.cpp and integrator.cpp)");
  std::map<std::string, std::vector<std::filesystem::path>> candidates;
  auto it = std::filesystem::recursive_directory_iterator(
      dir, std::filesystem::directory_options::skip_permission_denied, error);
  for (; !error && it != std::filesystem::recursive_directory_iterator(); it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name == "__MACOSX" || name == ".git") {
      it.disable_recursion_pending();
      continue;
    }
    if (name.rfind("._", 0) == 0 || !it->is_regular_file(error)) continue;
    const std::string key = lower(name);
    for (const std::string& wanted : studentFileNames())
      if (key == wanted) candidates[wanted].push_back(it->path());
  }
  SubmissionFiles files;
  for (const std::string& wanted : studentFileNames()) {
    auto& list = candidates[wanted];
    if (list.empty()) {
      files.notes.push_back(wanted + ": not found below " + dir.string());
      continue;
    }
    const auto rank = [&](const std::filesystem::path& p) {
      const auto relative = std::filesystem::relative(p, dir);
      const bool in_src = lower(p.parent_path().filename().string()) == "src";
      return std::make_tuple(in_src ? 0 : 1, std::distance(relative.begin(), relative.end()),
                             relative.string());
    };
    std::sort(list.begin(), list.end(),
              [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
    files.found[wanted] = list.front();
    if (list.size() > 1) {
      std::string others;
      for (std::size_t k = 1; k < list.size(); ++k)
        others += (k > 1 ? ", " : "") + std::filesystem::relative(list[k], dir).string();
      files.notes.push_back(wanted + ": used " +
                            std::filesystem::relative(list.front(), dir).string() +
                            "; also found " + others);
    }
    const std::string bytes = readSource(list.front());
    const bool bom = bytes.rfind("\xEF\xBB\xBF", 0) == 0;
    const bool crlf = bytes.find("\r\n") != std::string::npos;
    const bool utf8 = isUtf8(bom ? bytes.substr(3) : bytes);
    if (bom || crlf || !utf8)
      files.notes.push_back(wanted + ":" + std::string(bom ? " UTF-8 byte-order mark;" : "") +
                            (crlf ? " CRLF line ends;" : "") +
                            (utf8 ? "" : " bytes that are not UTF-8 (Big5?);") +
                            " passed to the compiler unchanged");
  }
  return files;
}

int detectEdition(const SubmissionFiles& files, std::string& why) {
  const auto source = [&](const std::string& name) {
    auto it = files.found.find(name);
    return it == files.found.end() ? std::string() : codeOnly(readSource(it->second));
  };
  const std::string sphere = source("sphere.cpp");
  if (std::regex_search(sphere, std::regex(R"(Spheres\s*::\s*setVelocity\s*\()"))) {
    why = "sphere.cpp defines Spheres::setVelocity (2024)";
    return 2024;
  }
  if (std::regex_search(sphere, std::regex(R"(Spheres\s*::\s*collide\s*\(\s*(void\s*)?\))"))) {
    why = "sphere.cpp defines Spheres::collide() (2022)";
    return 2022;
  }
  if (source("cloth.cpp").find("textureBuffer") != std::string::npos) {
    why = "cloth.cpp uses textureBuffer (2024)";
    return 2024;
  }
  why = "no edition marker found";
  return 0;
}

}  // namespace clothref::grader
