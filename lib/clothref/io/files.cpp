#include "clothref/io/files.h"

#include <stdlib.h>

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

}  // namespace clothref
