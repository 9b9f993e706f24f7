#include "clothref/io/output_file.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <system_error>

#include "clothref/io/error.h"
#include "clothref/io/gzip_stream.h"

namespace clothref {

namespace {

// The temporary file a signal must remove, and the line saying so, composed beforehand around
// the signal's name: a signal handler may only call async-signal-safe functions (unlink, write,
// raise), never allocate or format.
char g_temporary[4096];
char g_message_head[256];   // "clothref trace: interrupted ("
char g_message_tail[4352];  // "); removed the partial output PATH\n"
volatile sig_atomic_t g_has_temporary = 0;

std::string& commandName() {
  static std::string name = "clothref";
  return name;
}

const char* signalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

void writeAll(const char* text) {
  [[maybe_unused]] const ssize_t written = ::write(2, text, std::strlen(text));
}

void onSignal(int signal) {
  if (g_has_temporary) {
    ::unlink(g_temporary);
    writeAll(g_message_head);
    writeAll(signalName(signal));
    writeAll(g_message_tail);
  }
  // the default action ends the process with the conventional status (128 + N in a shell)
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

// Copies `text` into `buffer`, cut to fit, always terminated.
template <std::size_t N>
void copyInto(char (&buffer)[N], const std::string& text) {
  const std::size_t size = std::min(text.size(), N - 1);
  std::memcpy(buffer, text.data(), size);
  buffer[size] = '\0';
}

void registerTemporary(const std::filesystem::path& temporary) {
  const std::string path = temporary.string();
  if (path.size() >= sizeof g_temporary) return;  // too long to remove from a handler
  g_has_temporary = 0;
  copyInto(g_temporary, path);
  copyInto(g_message_head, commandName() + ": interrupted (");
  copyInto(g_message_tail, "); removed the partial output " + path + "\n");
  static bool installed = false;
  if (!installed) {
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal, &action, nullptr);
    installed = true;
  }
  g_has_temporary = 1;
}

void unregisterTemporary(const std::filesystem::path& temporary) {
  if (g_has_temporary && temporary.string() == g_temporary) g_has_temporary = 0;
}

bool endsWithGz(const std::string& path) {
  return path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
}

// Atomic replacement (temporary file, then rename) is only for regular files and new paths:
// renaming over a device, FIFO or socket would replace the node itself (as root, /dev/null
// would become a regular file for the whole machine).
bool writesInPlace(const std::filesystem::path& target) {
  std::error_code error;
  const auto status = std::filesystem::status(target, error);  // follows symbolic links
  if (error) return false;                                     // a new path (or unreadable)
  return std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
}

}  // namespace

void setOutputCommandName(const std::string& name) { commandName() = name; }

void exitOutOfMemory() {
  if (g_has_temporary) ::unlink(g_temporary);
  const std::string& name = commandName();  // already allocated: reading it allocates nothing
  [[maybe_unused]] const ssize_t written = ::write(2, name.data(), name.size());
  writeAll(": out of memory\n");
  ::_exit(2);  // kExitBadInput; no destructors or atexit handlers, which might allocate
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path_ == "-") return;
  open();
  if (endsWithGz(path_)) {
    gzip_ = std::make_unique<GzipOutputBuffer>(*file_.rdbuf());
    gzip_stream_ = std::make_unique<std::ostream>(gzip_.get());
  }
}

void OutputFile::open() {
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
  registerTemporary(temporary_);
}

OutputFile::~OutputFile() {
  if (path_ == "-" || direct_ || committed_) return;
  unregisterTemporary(temporary_);
  file_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

std::ostream& OutputFile::stream() {
  if (gzip_stream_) return *gzip_stream_;
  return path_ == "-" ? std::cout : file_;
}

void OutputFile::commit() {
  if (path_ == "-") {
    std::cout.flush();
    if (!std::cout) throw InputError("standard output: write failed");
    committed_ = true;
    return;
  }
  const bool compressed = !gzip_ || (*gzip_stream_ && gzip_->finish());
  file_.close();
  if (!file_ || !compressed) throw InputError(path_ + ": write failed");
  if (!direct_) {
    unregisterTemporary(temporary_);
    std::error_code error;
    std::filesystem::rename(temporary_, final_, error);
    if (error) throw InputError(path_ + ": cannot move the output into place: " + error.message());
  }
  committed_ = true;
}

}  // namespace clothref
