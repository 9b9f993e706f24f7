// Gzip through iostreams (zlib): reading a gzip-compressed trace or tolerance file exactly like a
// plain one, and writing `.gz` outputs. The compressed bytes are read from and written to another
// streambuf (a file, standard input or output), so the same code serves files and pipes.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <streambuf>
#include <string>

namespace clothref {

// True when the next byte of `source` is the first byte of the gzip magic (0x1f): no JSON text
// starts with it, so one byte of look-ahead tells a gzip stream from a plain one.
bool startsLikeGzip(std::streambuf& source);

// Decompresses `source` (gzip, concatenated members allowed). `name` names it in errors; a
// corrupt or truncated stream makes the reading istream bad (badbit), and error() says why.
class GzipInputBuffer : public std::streambuf {
 public:
  GzipInputBuffer(std::streambuf& source, std::string name);
  ~GzipInputBuffer() override;
  GzipInputBuffer(const GzipInputBuffer&) = delete;
  GzipInputBuffer& operator=(const GzipInputBuffer&) = delete;

  // Empty, or "corrupt gzip data (...)" after a failed read (the reader adds file and line).
  const std::string& error() const { return error_; }

 protected:
  int_type underflow() override;

 private:
  struct State;
  std::streambuf& source_;
  std::string name_;
  std::unique_ptr<State> state_;
  std::array<char, 1 << 16> in_{};
  std::array<char, 1 << 16> out_{};
  std::string error_;
  bool finished_ = false;
};

// Compresses everything written into gzip on `sink`; finish() writes the trailer and returns false
// if a write to the sink failed.
class GzipOutputBuffer : public std::streambuf {
 public:
  explicit GzipOutputBuffer(std::streambuf& sink);
  ~GzipOutputBuffer() override;
  GzipOutputBuffer(const GzipOutputBuffer&) = delete;
  GzipOutputBuffer& operator=(const GzipOutputBuffer&) = delete;

  bool finish();

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  bool deflateBuffered(int flush);
  struct State;
  std::streambuf& sink_;
  std::unique_ptr<State> state_;
  std::array<char, 1 << 16> in_{};
  std::array<char, 1 << 16> out_{};
  bool failed_ = false;
  bool finished_ = false;
};

}  // namespace clothref
