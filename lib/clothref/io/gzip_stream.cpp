#include "clothref/io/gzip_stream.h"

#include <zlib.h>

namespace clothref {

struct GzipInputBuffer::State {
  z_stream z{};
};
struct GzipOutputBuffer::State {
  z_stream z{};
};

bool startsLikeGzip(std::streambuf& source) { return source.sgetc() == 0x1f; }

GzipInputBuffer::GzipInputBuffer(std::streambuf& source, std::string name)
    : source_(source), name_(std::move(name)), state_(std::make_unique<State>()) {
  // 15 + 32: the largest window, gzip or zlib header detected automatically
  if (inflateInit2(&state_->z, 15 + 32) != Z_OK) error_ = "cannot start gzip decoding";
  setg(out_.data(), out_.data(), out_.data());
}

GzipInputBuffer::~GzipInputBuffer() { inflateEnd(&state_->z); }

GzipInputBuffer::int_type GzipInputBuffer::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  if (!error_.empty()) throw std::ios_base::failure(error_);
  z_stream& z = state_->z;
  for (;;) {
    if (z.avail_in == 0) {
      const std::streamsize got = source_.sgetn(in_.data(), std::streamsize(in_.size()));
      if (got <= 0) {
        if (!finished_) {
          error_ = "truncated gzip data (the stream ends before its trailer)";
          throw std::ios_base::failure(error_);
        }
        return traits_type::eof();
      }
      z.next_in = reinterpret_cast<Bytef*>(in_.data());
      z.avail_in = uInt(got);
    }
    if (finished_) {
      // Bytes after a member: another member (like zcat), which starts with the gzip magic (0x1f
      // is no valid zlib header, so inflate then insists on 0x8b); anything else (zero padding,
      // text) is refused rather than ignored. Checked on every member end, so input left in the
      // buffer after Z_STREAM_END can never make inflate spin.
      if (*z.next_in != 0x1f) {
        error_ = "trailing bytes after the gzip data (not another gzip member)";
        throw std::ios_base::failure(error_);
      }
      inflateReset(&z);
      finished_ = false;
    }
    z.next_out = reinterpret_cast<Bytef*>(out_.data());
    z.avail_out = uInt(out_.size());
    const int status = inflate(&z, Z_NO_FLUSH);
    if (status == Z_STREAM_END) {
      finished_ = true;
    } else if (status != Z_OK && status != Z_BUF_ERROR) {
      error_ = std::string("corrupt gzip data (") + (z.msg ? z.msg : "inflate failed") + ")";
      throw std::ios_base::failure(error_);
    }
    const std::size_t produced = out_.size() - z.avail_out;
    if (produced > 0) {
      setg(out_.data(), out_.data(), out_.data() + produced);
      return traits_type::to_int_type(*gptr());
    }
  }
}

GzipOutputBuffer::GzipOutputBuffer(std::streambuf& sink)
    : sink_(sink), state_(std::make_unique<State>()) {
  // 15 + 16: the largest window with a gzip header; level 6 is zlib's default
  failed_ = deflateInit2(&state_->z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK;
  setp(in_.data(), in_.data() + in_.size());
}

GzipOutputBuffer::~GzipOutputBuffer() { deflateEnd(&state_->z); }

bool GzipOutputBuffer::deflateBuffered(int flush) {
  z_stream& z = state_->z;
  z.next_in = reinterpret_cast<Bytef*>(pbase());
  z.avail_in = uInt(pptr() - pbase());
  int status = Z_OK;
  do {
    z.next_out = reinterpret_cast<Bytef*>(out_.data());
    z.avail_out = uInt(out_.size());
    status = deflate(&z, flush);
    if (status == Z_STREAM_ERROR) return false;
    const std::streamsize produced = std::streamsize(out_.size() - z.avail_out);
    if (produced > 0 && sink_.sputn(out_.data(), produced) != produced) return false;
  } while (z.avail_out == 0 || (flush == Z_FINISH && status != Z_STREAM_END));
  setp(in_.data(), in_.data() + in_.size());
  return true;
}

GzipOutputBuffer::int_type GzipOutputBuffer::overflow(int_type c) {
  if (failed_ || finished_ || !deflateBuffered(Z_NO_FLUSH)) {
    failed_ = true;
    return traits_type::eof();
  }
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

// Buffered data stays buffered (a flush per line would ruin the compression); finish() writes it.
int GzipOutputBuffer::sync() { return failed_ ? -1 : 0; }

bool GzipOutputBuffer::finish() {
  if (!finished_) {
    failed_ = failed_ || !deflateBuffered(Z_FINISH);
    finished_ = true;
    failed_ = failed_ || sink_.pubsync() != 0;
  }
  return !failed_;
}

}  // namespace clothref
