#include "clothref/output_file.h"

#include <iostream>
#include <system_error>

#include <unistd.h>

#include "clothref/error.h"

namespace clothref {

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path_ == "-") return;
  const std::filesystem::path target(path_);
  temporary_ = target;
  temporary_ += ".tmp" + std::to_string(::getpid());
  file_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!file_) throw InputError(path_ + ": cannot create the output file");
}

OutputFile::~OutputFile() {
  if (path_ == "-" || committed_) return;
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
  std::error_code error;
  std::filesystem::rename(temporary_, path_, error);
  if (error) throw InputError(path_ + ": cannot move the output into place: " + error.message());
  committed_ = true;
}

}  // namespace clothref
