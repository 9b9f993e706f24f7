#include "grader/grade/submission/submission.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <regex>
#include <sstream>

#include "clothref/io/error.h"
#include "grader/grade/submission/source_text.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A walk is bounded: an archive of a whole home folder must not keep the grader busy.
constexpr int kMaxDepth = 24;
constexpr std::size_t kMaxEntries = 200000;

struct Walk {
  std::map<std::string, std::vector<std::string>> candidates;  // wanted name -> relative paths
  std::vector<std::string> notes;
  std::vector<std::string> other_links;  // symbolic links not followed (not a wanted name)
  std::size_t entries = 0;
  bool truncated = false;
};

std::string kindOf(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link (links are not followed)";
  if (S_ISDIR(mode)) return "a folder, not a file";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

const std::string* wantedName(const std::string& name) {
  const std::string key = lower(name);
  for (const std::string& wanted : studentFileNames())
    if (key == wanted) return &wanted;
  return nullptr;
}

void walk(int dir_fd, const std::string& prefix, int depth, Walk& w) {
  const int listing = dup(dir_fd);
  if (listing < 0) return;
  DIR* dir = fdopendir(listing);
  if (!dir) {
    close(listing);
    return;
  }
  std::vector<std::string> names;
  while (const dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    if (name == "." || name == "..") continue;
    if (++w.entries > kMaxEntries) {
      w.truncated = true;
      break;
    }
    names.push_back(name);
  }
  closedir(dir);
  std::sort(names.begin(), names.end());  // the same notes whatever order the disk lists
  for (const std::string& name : names) {
    if (name == "__MACOSX" || name == ".git" || name.rfind("._", 0) == 0) continue;
    struct stat st {};
    if (fstatat(dir_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) continue;
    const std::string relative = prefix + name;
    const std::string* wanted = wantedName(name);
    if (S_ISREG(st.st_mode)) {
      if (wanted) w.candidates[*wanted].push_back(relative);
      continue;
    }
    if (wanted)
      w.notes.push_back(*wanted + ": refused " + codeSpan(safeName(relative)) + ": " +
                        kindOf(st.st_mode) + "; only regular files inside the submission are read");
    else if (S_ISLNK(st.st_mode))
      w.other_links.push_back(relative);
    if (!S_ISDIR(st.st_mode)) continue;
    if (depth >= kMaxDepth) {
      w.truncated = true;
      continue;
    }
    const int sub = openBeneath(dir_fd, name, O_RDONLY | O_DIRECTORY);
    if (sub < 0) continue;  // replaced by a link meanwhile, or unreadable
    walk(sub, relative + "/", depth + 1, w);
    close(sub);
  }
}

std::size_t depthOf(const std::string& relative) {
  return static_cast<std::size_t>(std::count(relative.begin(), relative.end(), '/'));
}

}  // namespace

int openBeneath(int root_fd, const std::string& relative, int flags, bool use_openat2) {
  if (relative.empty() || relative.front() == '/') {
    errno = EXDEV;
    return -1;
  }
  if (use_openat2) {
    open_how how{};
    how.flags = static_cast<std::uint64_t>(flags | O_CLOEXEC | O_NOFOLLOW);
    how.resolve = RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS | RESOLVE_NO_MAGICLINKS;
    const long fd = syscall(SYS_openat2, root_fd, relative.c_str(), &how, sizeof how);
    if (fd >= 0 || errno != ENOSYS) return static_cast<int>(fd);
  }
  // No openat2 (Linux < 5.6): one component at a time, never following a link.
  std::vector<std::string> parts;
  std::istringstream in(relative);
  for (std::string part; std::getline(in, part, '/');) {
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      errno = EXDEV;
      return -1;
    }
    parts.push_back(part);
  }
  if (parts.empty()) {
    errno = ENOENT;
    return -1;
  }
  int current = root_fd;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const bool last = k + 1 == parts.size();
    const int next = openat(current, parts[k].c_str(),
                            (last ? flags : O_RDONLY | O_DIRECTORY) | O_NOFOLLOW | O_CLOEXEC);
    int saved = errno;
    // O_DIRECTORY on a link to a folder says ENOTDIR: name it for what it is.
    struct stat st {};
    if (next < 0 && saved == ENOTDIR &&
        fstatat(current, parts[k].c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode))
      saved = ELOOP;
    if (current != root_fd) close(current);
    if (next < 0) {
      errno = saved;
      return -1;
    }
    current = next;
  }
  return current;
}

bool readRegularFileBeneath(int root_fd, const std::string& relative, std::size_t max_bytes,
                            std::string& bytes, std::string& why, bool use_openat2) {
  // O_NONBLOCK: opening a FIFO that took a file's place must not wait for a writer.
  const int fd = openBeneath(root_fd, relative, O_RDONLY | O_NONBLOCK | O_NOCTTY, use_openat2);
  if (fd < 0) {
    why = errno == ELOOP   ? "a symbolic link on the way (links are not followed)"
          : errno == EXDEV ? "outside the submission"
                           : std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    why = kindOf(st.st_mode);
    close(fd);
    return false;
  }
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    why = "larger than " + std::to_string(max_bytes) +
          " bytes (raise the limit with --max-file-bytes)";
    close(fd);
    return false;
  }
  bytes.clear();
  char buffer[65536];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
    if (bytes.size() > max_bytes) break;  // grew since fstat
  }
  close(fd);
  if (bytes.size() > max_bytes) {
    why = "larger than " + std::to_string(max_bytes) +
          " bytes (raise the limit with --max-file-bytes)";
    return false;
  }
  return true;
}

namespace {

// The submission folder named by the caller: the folders on the way to it may be links (the
// caller's own), the folder itself may not (a link named like a submission, planted among them,
// would have the grader read, as root, whatever it points to). A trailing '/' is dropped first: it
// would make the kernel follow a last link. -1 with errno set when it cannot be opened.
int openSubmissionFolder(const std::filesystem::path& dir) {
  std::string path = dir.string();
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
}

// Why `dir` did not open (errno `error`); O_DIRECTORY on a link says ENOTDIR: named for what it is.
std::string openProblem(const std::filesystem::path& dir, int error) {
  std::string path = dir.string();
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  struct stat st {};
  if (error == ELOOP || (error == ENOTDIR && lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)))
    return "a symbolic link (a submission folder given as a link is not followed)";
  if (error == ENOTDIR)
    return "not a directory (a submission is a directory holding cloth.cpp, sphere.cpp and "
           "integrator.cpp)";
  return std::strerror(error);
}

}  // namespace

std::vector<std::string> submissionsBelow(const std::filesystem::path& dir) {
  const int root_fd = openSubmissionFolder(dir);
  if (root_fd < 0) return {};
  std::vector<std::string> whole;
  Walk top;
  walk(root_fd, "", kMaxDepth, top);  // depth kMaxDepth: the top level only
  bool files_at_top = false;
  for (const auto& [name, paths] : top.candidates)
    for (const std::string& path : paths) files_at_top = files_at_top || depthOf(path) == 0;
  DIR* listing = files_at_top ? nullptr : fdopendir(dup(root_fd));
  std::vector<std::string> folders;
  if (listing) {
    rewinddir(listing);  // the walk above read the same open directory to its end
    while (const dirent* entry = readdir(listing)) {
      const std::string name = entry->d_name;
      if (name == "." || name == ".." || name == "__MACOSX" || name == ".git" ||
          name.rfind("._", 0) == 0)
        continue;
      struct stat st {};
      if (fstatat(root_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode))
        folders.push_back(name);
    }
    closedir(listing);
  }
  std::sort(folders.begin(), folders.end());
  for (const std::string& folder : folders) {
    const int sub = openBeneath(root_fd, folder, O_RDONLY | O_DIRECTORY);
    if (sub < 0) continue;
    Walk w;
    walk(sub, "", 1, w);
    close(sub);
    bool all = true;
    for (const std::string& wanted : studentFileNames()) all = all && !w.candidates[wanted].empty();
    if (all) whole.push_back(folder);
  }
  close(root_fd);
  if (whole.size() < 2) whole.clear();
  return whole;
}

std::string severalSubmissionsProblem(const std::filesystem::path& dir,
                                      const std::vector<std::string>& names) {
  std::string list;
  for (std::size_t k = 0; k < names.size() && k < 5; ++k)
    list += (k ? ", " : "") + safeName(names[k]);
  if (names.size() > 5) list += ", ...";
  std::string shown = dir.string();
  while (shown.size() > 1 && shown.back() == '/') shown.pop_back();
  shown = safeName(shown);
  return std::to_string(names.size()) + " submissions below " + shown + " (" + list +
         "): give them as " + shown + "/* with --out BATCHDIR, or --one-submission to grade " +
         shown + " as one";
}

SubmissionFiles findSubmissionFiles(const std::filesystem::path& dir, std::size_t max_file_bytes) {
  // The folder named by the caller (not by the student) may itself be reached through folders
  // that are links, but it is no link itself; nothing below it is followed either.
  const int root_fd = openSubmissionFolder(dir);
  if (root_fd < 0) throw InputError(safeName(dir.string()) + ": " + openProblem(dir, errno));
  Walk w;
  walk(root_fd, "", 0, w);
  SubmissionFiles files;
  files.notes = w.notes;
  if (!w.other_links.empty()) {
    std::string list;
    for (std::size_t k = 0; k < w.other_links.size() && k < 3; ++k)
      list += (k ? ", " : "") + codeSpan(safeName(w.other_links[k]));
    files.notes.push_back(std::to_string(w.other_links.size()) +
                          " symbolic link(s) not followed: " + list +
                          (w.other_links.size() > 3 ? ", ..." : ""));
  }
  if (w.truncated)
    files.notes.push_back("the search stopped after " + std::to_string(kMaxEntries) +
                          " entries or " + std::to_string(kMaxDepth) + " folder levels");
  for (const std::string& wanted : studentFileNames()) {
    auto& list = w.candidates[wanted];
    if (list.empty()) {
      const bool refused = std::any_of(w.notes.begin(), w.notes.end(), [&](const auto& note) {
        return note.rfind(wanted + ": refused ", 0) == 0;
      });
      if (!refused)
        files.notes.push_back(wanted + ": not found below " + codeSpan(safeName(dir.string())));
      continue;
    }
    const auto rank = [&](const std::string& p) {
      const std::size_t slash = p.rfind('/');
      const std::string parent = slash == std::string::npos ? "" : p.substr(0, slash);
      const std::string parent_name = parent.substr(parent.rfind('/') + 1);
      return std::make_tuple(lower(parent_name) == "src" ? 0 : 1, depthOf(p), p);
    };
    std::sort(list.begin(), list.end(),
              [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
    std::string chosen, bytes;
    std::vector<std::string> others;
    for (const std::string& candidate : list) {
      std::string why;
      if (!chosen.empty()) {
        others.push_back(candidate);
      } else if (readRegularFileBeneath(root_fd, candidate, max_file_bytes, bytes, why)) {
        chosen = candidate;
      } else {
        files.notes.push_back(wanted + ": refused " + codeSpan(safeName(candidate)) + ": " + why);
      }
    }
    if (chosen.empty()) continue;
    files.found[wanted] = dir / chosen;
    files.bytes[wanted] = bytes;
    if (!others.empty()) {
      std::string text;
      for (std::size_t k = 0; k < others.size(); ++k)
        text += (k ? ", " : "") + codeSpan(safeName(others[k]));
      files.notes.push_back(wanted + ": used " + codeSpan(safeName(chosen)) + "; also found " +
                            text);
      files.choices.push_back({wanted, chosen, others});
    }
    const bool bom = bytes.rfind("\xEF\xBB\xBF", 0) == 0;
    const bool crlf = bytes.find("\r\n") != std::string::npos;
    const bool utf8 = isValidUtf8(bom ? bytes.substr(3) : bytes);
    if (bom || crlf || !utf8)
      files.notes.push_back(wanted + ":" + std::string(bom ? " UTF-8 byte-order mark;" : "") +
                            (crlf ? " CRLF line ends;" : "") +
                            (utf8 ? "" : " bytes that are not UTF-8 (Big5?);") +
                            " passed to the compiler unchanged");
  }
  close(root_fd);
  return files;
}

int detectEdition(const SubmissionFiles& files, std::string& why) {
  const auto source = [&](const std::string& name) {
    auto it = files.bytes.find(name);
    return it == files.bytes.end() ? std::string() : blankedCode(it->second);
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
