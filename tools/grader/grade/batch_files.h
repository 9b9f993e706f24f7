// BATCHDIR's files, written and read without following a link a submission or anyone else
// planted there (docs/reliability.md): the batch writes as root, so a link must never redirect it.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include <unistd.h>

namespace clothref::grader {

// A descriptor that closes itself.
struct Fd {
  int fd = -1;
  explicit Fd(int value = -1) : fd(value) {}
  Fd(Fd&& other) noexcept : fd(std::exchange(other.fd, -1)) {}
  Fd& operator=(Fd&& other) noexcept {
    std::swap(fd, other.fd);
    return *this;
  }
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// "<path>: <strerror(errno)>", the path made safe to print.
std::string errnoText(const std::filesystem::path& path);

// BATCHDIR's folder of a submission, created when missing. It must be a folder, not a link: a link
// planted there would have the batch write (as root) wherever it points.
Fd openFolder(int batch_fd, const std::filesystem::path& batch_dir, const std::string& name);

// Writes `name` in the folder `dir_fd` atomically: a new temporary file beside it (O_EXCL |
// O_NOFOLLOW: never an existing file nor a link), then renamed over the name, which replaces a
// link there instead of writing through it.
void writeNoFollow(int dir_fd, const std::filesystem::path& folder, const std::string& name,
                   const std::string& text);

// The bytes of `name` in the folder `dir_fd`, read without following a link; nullopt when there is
// none, it is a link or not a regular file, or it is larger than `max_bytes`.
std::optional<std::string> readNoFollow(int dir_fd, const std::string& name, std::size_t max_bytes);

}  // namespace clothref::grader
