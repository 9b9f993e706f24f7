// Whole-file input, a scratch directory, and a directory written without following links: the one
// way the library reads a file into memory, makes temporary files and writes into a golden set.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

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

// "PATH: cannot <verb> the <what> (<the system's reason, e.g. No such file or directory>)": the
// one message for an input file that does not open; `error_number` is errno right after the open.
std::string cannotOpenMessage(const std::filesystem::path& path, const std::string& verb,
                              const std::string& what, int error_number);

// Where an installed clothref keeps its data: `data_from_bin` (e.g. "../share/clothref") taken
// from the folder of the running executable (/proc/self/exe), when that folder exists; else
// empty (a build tree, whose programs use the source tree's paths).
std::filesystem::path installedDataDir(const std::string& data_from_bin);

// Called first thing by the CLI: a closed standard input, output or error is held by /dev/null
// (read-only), so no file the command opens takes its descriptor (a trace opened as descriptor 1
// would receive the summary meant for a closed stdout; one opened as 0 would be read for "-").
// A closed standard input is remembered for requireStreamInput.
void holdClosedStandardStreams();

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

// A directory held open by its file descriptor, for writing and deleting files in it without ever
// following a symbolic link (golden/): every name is resolved relative to the descriptor, a
// subdirectory is opened with O_NOFOLLOW, a file is replaced by a temporary file and renameat (a
// link at the name is replaced, never written through) and deleted with unlinkat (a link is
// removed, not its target). Errors are InputError, one line naming the path.
class OpenDirectory {
 public:
  // Opens `path` (the caller named it, so a link there is followed); with `create`, makes it
  // and its parents first when missing.
  OpenDirectory(const std::filesystem::path& path, bool create);
  ~OpenDirectory();
  OpenDirectory(OpenDirectory&& other) noexcept;
  OpenDirectory(const OpenDirectory&) = delete;
  OpenDirectory& operator=(const OpenDirectory&) = delete;
  OpenDirectory& operator=(OpenDirectory&&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // True when the entry `name` exists (a link counts, whatever it points to).
  bool has(const std::string& name) const;

  // The subdirectory `name`, made first with `create`. Refuses a symbolic link ("PATH/name: a
  // symbolic link, not a directory (golden never writes through one)"), a non-directory, and
  // one it cannot open, with the system's reason.
  OpenDirectory sub(const std::string& name, bool create) const;

  // Names of the entries that are regular files or symbolic links (not followed), sorted.
  std::vector<std::string> files() const;

  // Replaces the file `name` with `text` atomically (temporary file, fsync, renameat). A
  // regular file there keeps its permission bits (a 0444 file stays 0444).
  void replaceFile(const std::string& name, std::string_view text) const;

  // Deletes the entry `name` (a link itself, never its target); a missing entry is no error.
  void remove(const std::string& name) const;

 private:
  OpenDirectory(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace clothref
