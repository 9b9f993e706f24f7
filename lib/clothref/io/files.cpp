#include "clothref/io/files.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/io/limits.h"

namespace clothref {

std::string cannotOpenMessage(const std::filesystem::path& path, const std::string& verb,
                              const std::string& what, int error_number) {
  std::string message = path.string() + ": cannot " + verb + " the " + what;
  if (error_number != 0) message += std::string(" (") + std::strerror(error_number) + ")";
  return message;
}

std::filesystem::path installedDataDir(const std::string& data_from_bin) {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error || data_from_bin.empty()) return {};
  const std::filesystem::path dir = (exe.parent_path() / data_from_bin).lexically_normal();
  return std::filesystem::is_directory(dir, error) ? dir : std::filesystem::path();
}

std::string readFile(const std::filesystem::path& path, const std::string& what,
                     std::size_t max_bytes) {
  if (max_bytes == 0) max_bytes = inputLimits().file_bytes;
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(cannotOpenMessage(path, "read", what, errno));
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw InputError(path.string() + ": larger than " + std::to_string(max_bytes) +
                       " bytes (raise the limit with --max-file-bytes)");
  }
  if (in.bad()) throw InputError(path.string() + ": cannot read the " + what);
  return text;
}

namespace {
bool g_standard_input_closed = false;
}  // namespace

void holdClosedStandardStreams() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1) continue;
    // read-only, so a write to a closed stdout or stderr still fails (EBADF) as it would have
    if (::open("/dev/null", O_RDONLY) != fd) continue;
    if (fd == 0) g_standard_input_closed = true;
  }
}

void requireStreamInput(const std::string& path, const std::string& what) {
  struct stat info {};
  if (path == "-") {
    if (g_standard_input_closed || ::fstat(0, &info) != 0)
      throw InputError("standard input: closed (nothing to read a " + what + " from)");
    if (S_ISDIR(info.st_mode)) throw InputError("standard input: a directory, not a " + what);
    return;
  }
  if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
    throw InputError(path + ": a directory, not a " + what + " file");
}

ScratchDir::ScratchDir(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!::mkdtemp(name.data())) throw InputError(pattern + ": cannot create a temporary directory");
  path_ = name.data();
}

ScratchDir::~ScratchDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

namespace {

[[noreturn]] void failWith(const std::filesystem::path& path, const std::string& problem,
                           int error) {
  throw InputError(path.string() + ": " + problem + ": " + std::strerror(error));
}

}  // namespace

OpenDirectory::OpenDirectory(const std::filesystem::path& path, bool create) : path_(path) {
  if (create) {
    std::error_code error;
    std::filesystem::create_directories(path, error);
    if (error)
      throw InputError(path.string() + ": cannot create the directory: " + error.message());
  }
  fd_ = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) failWith(path, "cannot open the directory", errno);
}

OpenDirectory::~OpenDirectory() {
  if (fd_ >= 0) ::close(fd_);
}

OpenDirectory::OpenDirectory(OpenDirectory&& other) noexcept
    : fd_(other.fd_), path_(std::move(other.path_)) {
  other.fd_ = -1;
}

bool OpenDirectory::has(const std::string& name) const {
  struct stat info {};
  return ::fstatat(fd_, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0;
}

OpenDirectory OpenDirectory::sub(const std::string& name, bool create) const {
  const std::filesystem::path path = path_ / name;
  if (create && ::mkdirat(fd_, name.c_str(), 0777) != 0 && errno != EEXIST)
    failWith(path, "cannot create the directory", errno);
  struct stat info {};
  if (::fstatat(fd_, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(info.st_mode))
    throw InputError(path.string() +
                     ": a symbolic link, not a directory (golden never writes through one)");
  const int fd = ::openat(fd_, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOTDIR) throw InputError(path.string() + ": not a directory");
    // ELOOP: a link created since the check above
    failWith(path, "cannot open the directory", error);
  }
  return OpenDirectory(fd, path);
}

std::vector<std::string> OpenDirectory::files() const {
  // listed by path (the names only); each is then examined and later deleted relative to the
  // descriptor, never followed
  std::vector<std::string> names;
  std::error_code error;
  for (std::filesystem::directory_iterator it(path_, error), end; !error && it != end;
       it.increment(error)) {
    const std::string name = it->path().filename().string();
    struct stat info {};
    if (::fstatat(fd_, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0 &&
        (S_ISREG(info.st_mode) || S_ISLNK(info.st_mode)))
      names.push_back(name);
  }
  if (error) throw InputError(path_.string() + ": cannot list the directory: " + error.message());
  std::sort(names.begin(), names.end());
  return names;
}

void OpenDirectory::replaceFile(const std::string& name, std::string_view text) const {
  const std::filesystem::path path = path_ / name;
  mode_t mode = 0666;  // then the umask, as for any new file
  bool keep_mode = false;
  struct stat info {};
  if (::fstatat(fd_, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(info.st_mode)) {
    mode = info.st_mode & 07777;
    keep_mode = true;
  }
  const std::string temporary = name + ".tmp" + std::to_string(::getpid());
  const int fd = ::openat(fd_, temporary.c_str(),
                          O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode | 0200);
  if (fd < 0) failWith(path, "cannot create the file", errno);
  int error = 0;
  for (std::size_t done = 0; done < text.size() && !error;) {
    const ssize_t written = ::write(fd, text.data() + done, text.size() - done);
    if (written < 0 && errno != EINTR) error = errno;
    if (written > 0) done += std::size_t(written);
  }
  if (!error && keep_mode && ::fchmod(fd, mode) != 0) error = errno;
  if (!error && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && !error) error = errno;
  if (!error && ::renameat(fd_, temporary.c_str(), fd_, name.c_str()) != 0) error = errno;
  if (error) {
    ::unlinkat(fd_, temporary.c_str(), 0);
    failWith(path, "write failed", error);
  }
}

void OpenDirectory::remove(const std::string& name) const {
  if (::unlinkat(fd_, name.c_str(), 0) != 0 && errno != ENOENT)
    failWith(path_ / name, "cannot delete", errno);
}

}  // namespace clothref
