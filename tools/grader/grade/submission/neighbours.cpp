#include "grader/grade/submission/neighbours.h"

#include <cctype>

#include "grader/grade/submission/submission.h"

namespace clothref::grader {

namespace fs = std::filesystem;

bool isUnder(const fs::path& path, const fs::path& root) {
  std::string p = path.lexically_normal().string(), r = root.lexically_normal().string();
  // "/srv/subs/" and "/srv/subs" are one folder; "/" stays itself
  while (p.size() > 1 && p.back() == '/') p.pop_back();
  while (r.size() > 1 && r.back() == '/') r.pop_back();
  return p == r || (p.size() > r.size() && p.compare(0, r.size(), r) == 0 &&
                    (r == "/" || p[r.size()] == '/'));
}

namespace {

// Whether `dir` (a folder beside the submission) holds a student file within three levels: another
// student's submission, in a TA's usual layout (subs/alice, subs/bob).
bool holdsStudentFiles(const fs::path& dir) {
  std::error_code error;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::none, error);
       !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (it.depth() > 2) it.disable_recursion_pending();
    std::string name = it->path().filename().string();
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const std::string& file : studentFileNames())
      if (name == file) return true;
  }
  return false;
}

}  // namespace

std::vector<fs::path> neighbours(const fs::path& dir, bool can_cover) {
  std::error_code error;
  const fs::path submission = fs::weakly_canonical(fs::absolute(dir), error);
  const fs::path parent = submission.parent_path();
  if (parent.empty() || parent == submission) return {};
  const fs::path temp = fs::weakly_canonical(fs::temp_directory_path(error), error);
  static const char* const system[] = {"/",        "/home",    "/root", "/tmp", "/var",
                                       "/var/tmp", "/srv",     "/opt",  "/mnt", "/media",
                                       "/run",     "/dev/shm", "/usr",  "/etc"};
  bool coverable = can_cover && !isUnder(temp, parent);
  for (const char* folder : system) coverable = coverable && parent != fs::path(folder);
  if (coverable) return {parent};
  std::vector<fs::path> found;
  if (can_cover) found.push_back(submission);
  for (const auto& entry : fs::directory_iterator(parent, error)) {
    const fs::path path = entry.path();
    if (path == submission || entry.is_symlink(error) || !entry.is_directory(error)) continue;
    if (isUnder(temp, path) || isUnder(path, "/usr") || isUnder(path, "/proc")) continue;
    if (holdsStudentFiles(path)) found.push_back(path);
  }
  return found;
}

}  // namespace clothref::grader
