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

// "PATH: cannot <verb> the <what> (<the system's reason, e.g. No such file or directory>)": the
// one message for an input file that does not open; `error_number` is errno right after the open.
std::string cannotOpenMessage(const std::filesystem::path& path, const std::string& verb,
                              const std::string& what, int error_number);

// Where an installed clothref keeps its data: `data_from_bin` (e.g. "../share/clothref") taken
// from the folder of the running executable (/proc/self/exe), when that folder exists; else
// empty (a build tree, whose programs use the source tree's paths).
std::filesystem::path installedDataDir(const std::string& data_from_bin);

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
