#include "grader/grade/batch_files.h"

#include <fcntl.h>
#include <sys/stat.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "clothref/io/error.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace fs = std::filesystem;

std::string errnoText(const fs::path& path) {
  return safeName(path.string()) + ": " + std::strerror(errno);
}

Fd openFolder(int batch_fd, const fs::path& batch_dir, const std::string& name) {
  if (::mkdirat(batch_fd, name.c_str(), 0755) != 0 && errno != EEXIST)
    throw InputError(errnoText(batch_dir / name));
  Fd folder(::openat(batch_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (folder.fd < 0)
    throw InputError(safeName((batch_dir / name).string()) + ": " +
                     (errno == ELOOP || errno == ENOTDIR
                          ? std::string("not a folder of the batch (a link or a file there is "
                                        "never written through; remove it)")
                          : std::strerror(errno)));
  return folder;
}

void writeNoFollow(int dir_fd, const fs::path& folder, const std::string& name,
                   const std::string& text) {
  static std::atomic<unsigned long> counter{0};
  const std::string temporary =
      name + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  Fd out(::openat(dir_fd, temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                  0644));
  if (out.fd < 0) throw InputError(errnoText(folder / name));
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(out.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = errnoText(folder / name);
      ::unlinkat(dir_fd, temporary.c_str(), 0);
      throw InputError(why + " (nothing written)");
    }
    done += std::size_t(n);
  }
  if (::renameat(dir_fd, temporary.c_str(), dir_fd, name.c_str()) != 0) {
    const std::string why = errnoText(folder / name);
    ::unlinkat(dir_fd, temporary.c_str(), 0);
    throw InputError(why);
  }
}

std::optional<std::string> readNoFollow(int dir_fd, const std::string& name,
                                        std::size_t max_bytes) {
  Fd in(::openat(dir_fd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  struct stat st {};
  if (in.fd < 0 || ::fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode) ||
      std::size_t(st.st_size) > max_bytes)
    return std::nullopt;
  std::string text(std::size_t(st.st_size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(in.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  text.resize(done);
  return text;
}

}  // namespace clothref::grader
