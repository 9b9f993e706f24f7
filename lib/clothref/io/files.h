// Whole-file input and a scratch directory: the one way the library reads a file into memory and
// makes temporary files.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace clothref {

// The bytes of `path`. Throws InputError "PATH: cannot read the <what>" when it cannot be opened
// or read, and "PATH: larger than LIMIT bytes" past `max_bytes` (so /dev/zero cannot exhaust
// memory); 0 means the process's limit, inputLimits().file_bytes (io/limits.h).
std::string readFile(const std::filesystem::path& path, const std::string& what,
                     std::size_t max_bytes = 0);

// Throws InputError when the input `path` ("-": standard input) can never be read as a stream of
// text: "PATH: a directory, not a <what>", "standard input: closed (nothing to read a <what>
// from)". Through iostreams both read like an empty file, which is the wrong message.
void requireStreamInput(const std::string& path, const std::string& what);

// A fresh directory under the system temporary directory, removed with its contents when this
// goes out of scope. `prefix` names the directory (prefix-XXXXXX).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace clothref
