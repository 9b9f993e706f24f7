// OutputFile: for a regular file or a new path, writes to a temporary file beside the target and
// renames it into place on commit, so a failed command never leaves a half-written output behind.
// Anything else that exists (a character device such as /dev/null, a FIFO, a socket) is written
// directly, never replaced. "-" means standard output.
#pragma once

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

namespace clothref {

class OutputFile {
 public:
  // Throws InputError when the file cannot be created.
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::ostream& stream();
  // Flushes and moves the file into place; throws InputError when writing failed.
  void commit();

 private:
  std::string path_;
  std::filesystem::path final_;      // the regular file the rename replaces
  std::filesystem::path temporary_;  // final_ + ".tmp<pid>"
  bool direct_ = false;              // written in place (device, FIFO, socket)
  std::ofstream file_;
  bool committed_ = false;
};

}  // namespace clothref
