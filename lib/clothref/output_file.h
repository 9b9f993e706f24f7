// OutputFile: writes to a temporary file beside the target and renames it into place on commit,
// so a failed command never leaves a half-written output behind. "-" means standard output.
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
  std::filesystem::path temporary_;
  std::ofstream file_;
  bool committed_ = false;
};

}  // namespace clothref
