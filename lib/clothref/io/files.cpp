#include "clothref/io/files.h"

#include <stdlib.h>
#include <sys/stat.h>

#include <fstream>
#include <system_error>
#include <vector>

#include "clothref/io/error.h"
#include "clothref/io/limits.h"

namespace clothref {

std::string readFile(const std::filesystem::path& path, const std::string& what,
                     std::size_t max_bytes) {
  if (max_bytes == 0) max_bytes = inputLimits().file_bytes;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read the " + what);
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

void requireStreamInput(const std::string& path, const std::string& what) {
  struct stat info {};
  if (path == "-") {
    if (::fstat(0, &info) != 0)
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

}  // namespace clothref
