#include "grader/grade/run/folders.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "clothref/io/error.h"

namespace clothref::grader {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(errno));
}

// A folder we make, then give to `uid` (when >= 0) with `mode`: mkdir, chown, chmod, in that
// order, so it is never open to others in between.
void makeFolder(const fs::path& path, int uid, mode_t mode) {
  if (mkdir(path.c_str(), 0700) != 0) fail(path, "cannot make the folder");
  if (uid >= 0 && chown(path.c_str(), static_cast<uid_t>(uid), static_cast<gid_t>(uid)) != 0)
    fail(path, "cannot hand the folder to its uid");
  if (chmod(path.c_str(), mode) != 0) fail(path, "cannot set the folder's mode");
}

// The entries of the open folder `dir_fd` (not "." or ".."), read once.
std::vector<std::string> entryNames(int dir_fd) {
  std::vector<std::string> names;
  const int own = dup(dir_fd);
  if (own < 0) return names;
  DIR* dir = fdopendir(own);
  if (!dir) {
    close(own);
    return names;
  }
  while (const dirent* entry = readdir(dir)) {
    const std::string name = entry->d_name;
    if (name != "." && name != "..") names.push_back(name);
  }
  closedir(dir);
  return names;
}

int openFolderBeneath(int dir_fd, const std::string& name) {
  return openat(dir_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
}

// Walks the tree below the open folder `root_fd` depth first, without recursion (a student can
// nest folders tens of thousands deep) and without following a link: `enter(dir_fd, name, info)`
// is called for every entry and returns whether to descend into it (folders only); `leave(dir_fd,
// name)` is called once a descended folder's entries are done. `stop()` ends the walk early.
template <typename Enter, typename Leave, typename Stop>
void walkTree(int root_fd, Enter&& enter, Leave&& leave, Stop&& stop) {
  struct Frame {
    int fd;
    std::vector<std::string> names;
    std::size_t next = 0;
    std::string name;  // this folder's name in the frame below
  };
  std::vector<Frame> stack;
  const int root = dup(root_fd);
  if (root < 0) return;
  stack.push_back({root, entryNames(root), 0, ""});
  while (!stack.empty()) {
    Frame& top = stack.back();
    if (top.next == top.names.size() || stop()) {
      const int fd = top.fd;
      const std::string name = top.name;
      stack.pop_back();
      close(fd);
      if (!stack.empty()) leave(stack.back().fd, name);
      continue;
    }
    const std::string name = top.names[top.next++];
    struct stat info {};
    if (fstatat(top.fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
    if (!enter(top.fd, name, info) || !S_ISDIR(info.st_mode)) continue;
    const int sub = openFolderBeneath(top.fd, name);
    if (sub < 0) continue;
    stack.push_back({sub, entryNames(sub), 0, name});
  }
}

void removeBelow(int dir_fd) {
  walkTree(
      dir_fd,
      [](int fd, const std::string& name, const struct stat& info) {
        if (S_ISDIR(info.st_mode)) return true;
        unlinkat(fd, name.c_str(), 0);
        return false;
      },
      [](int fd, const std::string& name) { unlinkat(fd, name.c_str(), AT_REMOVEDIR); },
      [] { return false; });
}

std::uint64_t blocks(const struct stat& info) {
  const std::uint64_t size = S_ISREG(info.st_mode) ? static_cast<std::uint64_t>(info.st_size) : 0;
  return std::max<std::uint64_t>(4096, (size + 4095) / 4096 * 4096);
}

// Bytes below `dir_fd` of entries owned by `uid` (any owner when < 0); the walk stops once the
// count passes `cap`.
std::uint64_t bytesBelowFd(int dir_fd, int uid, std::uint64_t cap) {
  std::uint64_t total = 0;
  walkTree(
      dir_fd,
      [&](int, const std::string&, const struct stat& info) {
        if (uid < 0 || info.st_uid == static_cast<uid_t>(uid)) total += blocks(info);
        return S_ISDIR(info.st_mode);
      },
      [](int, const std::string&) {}, [&] { return total > cap; });
  return total;
}

std::uint64_t copyBelow(int from_fd, int to_fd, std::uint64_t& left,
                        std::vector<std::string>* skipped) {
  std::uint64_t copied = 0;
  std::vector<int> targets = {to_fd};  // the copy's folder at each depth of the walk
  std::vector<std::string> path = {""};
  const auto skip = [&](const std::string& name, const std::string& why) {
    if (skipped) skipped->push_back(path.back() + name + " (" + why + ")");
  };
  walkTree(
      from_fd,
      [&](int fd, const std::string& name, const struct stat& info) {
        if (S_ISDIR(info.st_mode)) {
          if (mkdirat(targets.back(), name.c_str(), 0700) != 0 && errno != EEXIST) {
            skip(name, "cannot make the folder");
            return false;
          }
          const int target = openFolderBeneath(targets.back(), name);
          if (target < 0) {
            skip(name, "cannot open the copy");
            return false;
          }
          targets.push_back(target);
          path.push_back(path.back() + name + "/");
          return true;
        }
        if (!S_ISREG(info.st_mode)) {
          skip(name, S_ISLNK(info.st_mode) ? "a symbolic link, not followed" : "not a file");
          return false;
        }
        if (static_cast<std::uint64_t>(info.st_size) > left) {
          skip(name, "past the size limit");
          return false;
        }
        const int in = openat(fd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
        struct stat opened {};
        const int out = in >= 0 && fstat(in, &opened) == 0 && S_ISREG(opened.st_mode)
                            ? openat(targets.back(), name.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600)
                            : -1;
        if (out < 0) {
          if (in >= 0) close(in);
          skip(name, "cannot copy it");
          return false;
        }
        char buffer[65536];
        for (ssize_t n; left > 0 &&
                        (n = read(in, buffer, std::min<std::uint64_t>(sizeof buffer, left))) > 0;) {
          if (write(out, buffer, static_cast<std::size_t>(n)) != n) break;
          copied += static_cast<std::uint64_t>(n);
          left -= static_cast<std::uint64_t>(n);
        }
        close(in);
        close(out);
        return false;
      },
      [&](int, const std::string&) {
        close(targets.back());
        targets.pop_back();
        path.pop_back();
      },
      [] { return false; });
  return copied;
}

}  // namespace

bool removeTree(const fs::path& path) {
  struct stat info {};
  if (lstat(path.c_str(), &info) != 0) return errno == ENOENT;
  if (S_ISDIR(info.st_mode)) {
    const int fd = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) {
      removeBelow(fd);
      close(fd);
    }
    return rmdir(path.c_str()) == 0;
  }
  return unlink(path.c_str()) == 0;
}

std::uint64_t copyTree(const fs::path& from, const fs::path& to, std::uint64_t max_bytes,
                       std::vector<std::string>* skipped) {
  const int from_fd = open(from.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (from_fd < 0) {
    if (skipped) skipped->push_back(from.string() + " (cannot open the folder)");
    return 0;
  }
  std::error_code error;
  fs::create_directories(to, error);
  const int to_fd = open(to.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  std::uint64_t copied = 0;
  if (to_fd >= 0) {
    copied = copyBelow(from_fd, to_fd, max_bytes, skipped);
    close(to_fd);
  } else if (skipped) {
    skipped->push_back(to.string() + " (cannot open the copy's folder)");
  }
  close(from_fd);
  return copied;
}

std::uint64_t bytesBelow(const fs::path& path, int uid, std::uint64_t stop_after) {
  const int fd = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return 0;
  const std::uint64_t total = bytesBelowFd(fd, uid, stop_after);
  close(fd);
  return total;
}

namespace {

// Folders any user may write into, found below `dir` down to `depth` more levels (links not
// followed, other file systems entered; /proc, /sys and /usr skipped: the kernel's, and the
// system's, which no user may write).
void findWorldWritable(const fs::path& dir, int depth, std::vector<fs::path>& found) {
  const int fd = open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  for (const std::string& name : entryNames(fd)) {
    struct stat info {};
    if (fstatat(fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISDIR(info.st_mode))
      continue;
    const fs::path path = dir / name;
    if (path == "/proc" || path == "/sys" || path == "/usr") continue;
    if (info.st_mode & S_IWOTH) found.push_back(path);
    if (depth > 0) findWorldWritable(path, depth - 1, found);
  }
  close(fd);
}

}  // namespace

const std::vector<fs::path>& sharedTemporaryFolders() {
  static const std::vector<fs::path> folders = [] {
    std::vector<fs::path> candidates;
    std::error_code error;
    candidates.push_back(fs::temp_directory_path(error));
    for (const char* usual : {"/tmp", "/var/tmp", "/dev/shm"}) candidates.push_back(usual);
    findWorldWritable("/", 2, candidates);  // /run/lock, and any other the host has
    std::vector<fs::path> all;
    for (const fs::path& candidate : candidates) {
      if (candidate.empty()) continue;
      const fs::path real = fs::canonical(candidate, error);
      if (error || !fs::is_directory(real, error)) continue;
      if (std::find(all.begin(), all.end(), real) == all.end()) all.push_back(real);
    }
    return all;
  }();
  return folders;
}

std::uint64_t bytesOwnedBy(int uid, const std::vector<fs::path>& folders) {
  std::uint64_t total = 0;
  for (const fs::path& folder : folders) {
    const int fd = open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    for (const std::string& name : entryNames(fd)) {
      struct stat info {};
      if (fstatat(fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0 ||
          info.st_uid != static_cast<uid_t>(uid))
        continue;
      total += blocks(info);
      if (!S_ISDIR(info.st_mode)) continue;
      const int sub = openFolderBeneath(fd, name);
      if (sub < 0) continue;
      total += bytesBelowFd(sub, -1, ~std::uint64_t{0} >> 1);
      close(sub);
    }
    close(fd);
  }
  return total;
}

void removeOwnedBy(int uid, const std::vector<fs::path>& folders) {
  for (const fs::path& folder : folders) {
    const int fd = open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    for (const std::string& name : entryNames(fd)) {
      struct stat info {};
      if (fstatat(fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0 ||
          info.st_uid != static_cast<uid_t>(uid))
        continue;
      if (S_ISDIR(info.st_mode)) {
        const int sub = openFolderBeneath(fd, name);
        if (sub >= 0) {
          removeBelow(sub);
          close(sub);
        }
        unlinkat(fd, name.c_str(), AT_REMOVEDIR);
      } else {
        unlinkat(fd, name.c_str(), 0);
      }
    }
    close(fd);
  }
}

GradeScratch::GradeScratch(int probe_uid, int tool_uid)
    : probe_uid_(probe_uid), tool_uid_(tool_uid) {
  std::error_code error;
  std::string pattern = (fs::temp_directory_path(error) / "clothref-grade-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw InputError(pattern +
                     ": cannot create a temporary folder (TMPDIR): " + std::strerror(errno));
  root_ = pattern;
  try {
    const bool uids = probe_uid >= 0;
    if (chmod(root_.c_str(), uids ? 0711 : 0700) != 0) fail(root_, "cannot set the folder's mode");
    makeFolder(build(), uids ? tool_uid : -1, 0700);
    makeFolder(bin(), -1, uids ? 0711 : 0700);
    makeFolder(probes(), -1, uids ? 0711 : 0700);
  } catch (...) {
    removeTree(root_);
    throw;
  }
}

GradeScratch::~GradeScratch() { removeTree(root_); }

fs::path GradeScratch::extraBuild(const std::string& name) const {
  const fs::path folder = root_ / name;
  makeFolder(folder, probe_uid_ >= 0 ? tool_uid_ : -1, 0700);
  return folder;
}

fs::path GradeScratch::publish(const fs::path& built, const std::string& name) const {
  const fs::path target = bin() / (name.empty() ? built.filename().string() : name);
  const int in = open(built.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (in < 0) fail(built, "cannot read the linked probe");
  const int out = open(target.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0500);
  if (out < 0) {
    close(in);
    fail(target, "cannot write the probe");
  }
  char buffer[65536];
  bool ok = true;
  for (ssize_t n; (n = read(in, buffer, sizeof buffer)) > 0;)
    ok = ok && write(out, buffer, static_cast<std::size_t>(n)) == n;
  close(in);
  // root:<probe gid> 0550: the probe uid runs it, cannot change it; no other student reads it
  if (probe_uid_ >= 0) ok = ok && fchown(out, 0, static_cast<gid_t>(probe_uid_)) == 0;
  ok = ok && fchmod(out, probe_uid_ >= 0 ? 0550 : 0500) == 0;
  close(out);
  if (!ok) fail(target, "cannot write the probe");
  return target;
}

namespace {

// The kits of this process, removed at exit; a kit whose process is gone (killed) is removed by
// the next grader that makes one.
struct Kits {
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<CourseKit>> by_source;
  ~Kits() {
    for (auto& [source, kit] : by_source) removeTree(kit->root);
  }
};
Kits& kits() {
  static Kits all;
  return all;
}

void removeStaleKits(const fs::path& temp) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(temp, error)) {
    const std::string name = entry.path().filename().string();
    const std::string prefix = "clothref-kit-";
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid =
        name.substr(prefix.size(), name.find('-', prefix.size()) - prefix.size());
    struct stat info {};
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos ||
        lstat(entry.path().c_str(), &info) != 0 || info.st_uid != geteuid())
      continue;
    if (!fs::exists("/proc/" + pid, error)) removeTree(entry.path());
  }
}

}  // namespace

const CourseKit& courseKit(const fs::path& course_dir, const fs::path& driver_lib_dir) {
  Kits& all = kits();
  std::lock_guard<std::mutex> lock(all.mutex);
  const std::string source = course_dir.string() + "\n" + driver_lib_dir.string();
  auto found = all.by_source.find(source);
  if (found != all.by_source.end()) return *found->second;
  std::error_code error;
  const fs::path temp = fs::temp_directory_path(error);
  removeStaleKits(temp);
  std::string pattern = (temp / ("clothref-kit-" + std::to_string(getpid()) + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data()))
    throw InputError(pattern +
                     ": cannot create a temporary folder (TMPDIR): " + std::strerror(errno));
  auto kit = std::make_unique<CourseKit>();
  kit->root = pattern;
  kit->course_dir = kit->root / "course";
  kit->lib_dir = kit->root / "lib";
  std::vector<std::string> skipped;
  copyTree(course_dir, kit->course_dir, ~std::uint64_t{0}, &skipped);
  fs::create_directories(kit->lib_dir, error);
  for (const auto& entry : fs::directory_iterator(driver_lib_dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("libclothref_grader_course_", 0) == 0 && entry.path().extension() == ".a")
      fs::copy_file(entry.path(), kit->lib_dir / name, fs::copy_options::overwrite_existing, error);
  }
  // readable by every uid (public headers, and the driver every probe links anyway)
  for (const auto& entry : fs::recursive_directory_iterator(kit->root, error))
    chmod(entry.path().c_str(), entry.is_directory(error) ? 0755 : 0644);
  chmod(kit->root.c_str(), 0755);
  if (!skipped.empty()) {
    removeTree(kit->root);
    throw std::runtime_error("cannot copy the course headers: " + skipped.front());
  }
  return *(all.by_source[source] = std::move(kit));
}

fs::path kitHeader(const CourseKit& kit, const fs::path& header) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  const fs::path folder = kit.root / header.parent_path().filename();
  const fs::path target = folder / header.filename();
  std::error_code error;
  if (fs::exists(target.string() + ".gch", error)) return target;
  const fs::path temporary = kit.root / (folder.filename().string() + ".tmp");
  removeTree(temporary);
  fs::create_directories(temporary, error);
  for (const std::string& name :
       {header.filename().string(), header.filename().string() + ".gch"}) {
    const fs::path from = header.parent_path() / name, to = temporary / name;
    // A hard link costs nothing; across file systems, a copy (the header is about 130 MB).
    if (link(from.c_str(), to.c_str()) != 0)
      fs::copy_file(from, to, fs::copy_options::overwrite_existing, error);
    chmod(to.c_str(), 0644);
  }
  chmod(temporary.c_str(), 0755);
  fs::rename(temporary, folder, error);
  if (error) removeTree(temporary);
  return target;
}

}  // namespace clothref::grader
