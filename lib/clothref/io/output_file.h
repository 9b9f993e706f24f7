// OutputFile: for a regular file or a new path, writes to a temporary file beside the target and
// renames it into place on commit, so a failed command never leaves a half-written output behind.
// Anything else that exists (a character device such as /dev/null, a FIFO, a socket) is written
// directly, never replaced. "-" means standard output. A path ending in ".gz" is written
// gzip-compressed. While a temporary file exists, SIGINT, SIGTERM and SIGHUP remove it, say so in
// one line on stderr ("clothref trace: interrupted (SIGINT); removed the partial output
// out.jsonl.tmp<pid>") and end the process with the signal's conventional status (128 + N).
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>

namespace clothref {

class GzipOutputBuffer;

// The command the signal message names ("clothref trace"; "clothref" until set). Called once by
// the CLI with the subcommand it runs, before any OutputFile opens.
void setOutputCommandName(const std::string& name);

// Out of memory anywhere, even where an exception cannot pass (nlohmann's destructors allocate;
// a bad_alloc there used to abort): removes the temporary file of the output being written, prints
// "<command>: out of memory" on stderr and ends the process with status 2. Allocates nothing.
// The CLI installs it as the new-handler (std::set_new_handler), so `new` never throws bad_alloc.
[[noreturn]] void exitOutOfMemory();

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
  void open();

  std::string path_;
  std::filesystem::path final_;      // the regular file the rename replaces
  std::filesystem::path temporary_;  // final_ + ".tmp<pid>"
  bool direct_ = false;              // written in place (device, FIFO, socket)
  std::ofstream file_;
  std::unique_ptr<GzipOutputBuffer> gzip_;  // set for a ".gz" path
  std::unique_ptr<std::ostream> gzip_stream_;
  bool committed_ = false;
};

}  // namespace clothref
