#include "clothref/io/output_file.h"

#include <iostream>
#include <system_error>

#include <unistd.h>

#include "clothref/io/error.h"

namespace clothref {

namespace {

// Atomic replacement (temporary file, then rename) is only for regular files and new paths:
// renaming over a device, FIFO or socket would replace the node itself (as root, /dev/null
// would become a regular file for the whole machine).
bool writesInPlace(const std::filesystem::path& target) {
  std::error_code error;
  const auto status = std::filesystem::status(target, error);  // follows symbolic links
  if (error) return false;                                       // a new path (or unreadable)
  return std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
}

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path_ == "-") return;
  std::filesystem::path target(path_);
  if (writesInPlace(target)) {
    direct_ = true;
    file_.open(target, std::ios::binary);
    if (!file_) throw InputError(path_ + ": cannot open the output for writing");
    return;
  }
  // A symbolic link to a regular file: replace the file it names, keep the link.
  std::error_code error;
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(target, error))) {
    const auto resolved = std::filesystem::canonical(target, error);
    if (!error) target = resolved;
  }
  final_ = target;
  temporary_ = target;
  temporary_ += ".tmp" + std::to_string(::getpid());
  file_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!file_) throw InputError(path_ + ": cannot create the output file");
}

OutputFile::~OutputFile() {
  if (path_ == "-" || direct_ || committed_) return;
  file_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

std::ostream& OutputFile::stream() { return path_ == "-" ? std::cout : file_; }

void OutputFile::commit() {
  if (path_ == "-") {
    std::cout.flush();
    if (!std::cout) throw InputError("standard output: write failed");
    committed_ = true;
    return;
  }
  file_.close();
  if (!file_) throw InputError(path_ + ": write failed");
  if (!direct_) {
    std::error_code error;
    std::filesystem::rename(temporary_, final_, error);
    if (error) throw InputError(path_ + ": cannot move the output into place: " + error.message());
  }
  committed_ = true;
}

}  // namespace clothref
