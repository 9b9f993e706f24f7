// The only crossing between the course side (student code + probe driver, course headers) and the
// grader side (clothref library): plain data in std types, no clothref or course header.
//
// A ProbeMessage is a set of named float arrays, named integer arrays and named strings. The
// grader sends one (the probe group and its inputs) on the child's stdin; the child answers with
// one on fd 3, a pipe that is neither its stdout nor its stderr, so printing cannot forge results.
// Frame: "CRPB" magic, the 64-bit nonce of this run (from the request; an answer with another
// nonce is rejected), the payload length, then the entries. Floats travel as raw IEEE bits.
#pragma once
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace probe {

inline constexpr int kResultFd = 3;  // the child writes its answer here
// The variable that sets the byte the driver fills the stack with before each call of a student's
// stub (two hex digits; unset: 00): the second run of a scored probe sets it (probeVariants()).
inline constexpr const char* kStackFillVariable = "CLOTHREF_PROBE_STACK_FILL";

struct ProbeMessage {
  std::uint64_t nonce = 0;
  std::map<std::string, std::vector<float>> floats;
  std::map<std::string, std::vector<std::int64_t>> ints;
  std::map<std::string, std::string> texts;

  const std::vector<float>& f(const std::string& key) const {
    static const std::vector<float> empty;
    auto it = floats.find(key);
    return it == floats.end() ? empty : it->second;
  }
  const std::vector<std::int64_t>& i(const std::string& key) const {
    static const std::vector<std::int64_t> empty;
    auto it = ints.find(key);
    return it == ints.end() ? empty : it->second;
  }
  std::int64_t scalarInt(const std::string& key, std::int64_t fallback = 0) const {
    const auto& v = i(key);
    return v.empty() ? fallback : v[0];
  }
  float scalar(const std::string& key, float fallback = 0) const {
    const auto& v = f(key);
    return v.empty() ? fallback : v[0];
  }
  std::string text(const std::string& key) const {
    auto it = texts.find(key);
    return it == texts.end() ? std::string() : it->second;
  }
};

namespace detail {
inline void putU64(std::string& out, std::uint64_t value) {
  for (int b = 0; b < 8; ++b) out.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
}
inline bool getU64(const std::string& in, std::size_t& at, std::uint64_t& value) {
  if (at > in.size() || in.size() - at < 8) return false;
  value = 0;
  for (int b = 0; b < 8; ++b)
    value |= std::uint64_t(static_cast<unsigned char>(in[at + b])) << (8 * b);
  at += 8;
  return true;
}
inline void putString(std::string& out, const std::string& s) {
  putU64(out, s.size());
  out += s;
}
inline bool getString(const std::string& in, std::size_t& at, std::string& s) {
  std::uint64_t n = 0;
  if (!getU64(in, at, n) || n > in.size() - at) return false;
  s.assign(in, at, n);
  at += n;
  return true;
}
}  // namespace detail

// The whole frame, magic and length included.
inline std::string encodeMessage(const ProbeMessage& message) {
  std::string body;
  detail::putU64(body, message.floats.size());
  for (const auto& [key, values] : message.floats) {
    detail::putString(body, key);
    detail::putU64(body, values.size());
    const std::size_t at = body.size();
    body.resize(at + values.size() * sizeof(float));
    if (!values.empty()) std::memcpy(&body[at], values.data(), values.size() * sizeof(float));
  }
  detail::putU64(body, message.ints.size());
  for (const auto& [key, values] : message.ints) {
    detail::putString(body, key);
    detail::putU64(body, values.size());
    for (std::int64_t v : values) detail::putU64(body, static_cast<std::uint64_t>(v));
  }
  detail::putU64(body, message.texts.size());
  for (const auto& [key, value] : message.texts) {
    detail::putString(body, key);
    detail::putString(body, value);
  }
  std::string frame = "CRPB";
  detail::putU64(frame, message.nonce);
  detail::putU64(frame, body.size());
  return frame + body;
}

// Parses a whole frame; nullopt when it is malformed or truncated.
inline std::optional<ProbeMessage> decodeMessage(const std::string& frame) {
  using detail::getString;
  using detail::getU64;
  if (frame.size() < 20 || frame.compare(0, 4, "CRPB") != 0) return std::nullopt;
  ProbeMessage message;
  std::size_t at = 4;
  std::uint64_t length = 0, count = 0;
  if (!getU64(frame, at, message.nonce) || !getU64(frame, at, length)) return std::nullopt;
  if (length != frame.size() - at) return std::nullopt;
  if (!getU64(frame, at, count)) return std::nullopt;
  for (std::uint64_t e = 0; e < count; ++e) {
    std::string key;
    std::uint64_t n = 0;
    if (!getString(frame, at, key) || !getU64(frame, at, n)) return std::nullopt;
    if (n > (frame.size() - at) / sizeof(float)) return std::nullopt;
    std::vector<float> values(n);
    if (n) std::memcpy(values.data(), &frame[at], n * sizeof(float));
    at += n * sizeof(float);
    message.floats[key] = std::move(values);
  }
  if (!getU64(frame, at, count)) return std::nullopt;
  for (std::uint64_t e = 0; e < count; ++e) {
    std::string key;
    std::uint64_t n = 0;
    if (!getString(frame, at, key) || !getU64(frame, at, n)) return std::nullopt;
    if (n > (frame.size() - at) / 8) return std::nullopt;
    std::vector<std::int64_t> values(n);
    for (auto& v : values) {
      std::uint64_t u = 0;
      getU64(frame, at, u);
      v = static_cast<std::int64_t>(u);
    }
    message.ints[key] = std::move(values);
  }
  if (!getU64(frame, at, count)) return std::nullopt;
  for (std::uint64_t e = 0; e < count; ++e) {
    std::string key, value;
    if (!getString(frame, at, key) || !getString(frame, at, value)) return std::nullopt;
    message.texts[key] = std::move(value);
  }
  if (at != frame.size()) return std::nullopt;
  return message;
}

}  // namespace probe
