#include "clothref/trace/reader.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <iostream>
#include <limits>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/gzip_stream.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "clothref/trace/format.h"
#include "clothref/trace/hash.h"

namespace clothref {

namespace {

using ordered_json = nlohmann::ordered_json;

const std::pair<std::string_view, double> kBareNonFinite[] = {
    {"NaN", std::numeric_limits<double>::quiet_NaN()},
    {"Infinity", std::numeric_limits<double>::infinity()},
    {"-Infinity", -std::numeric_limits<double>::infinity()}};

// Where a value sits in the step object; turned into a JSON pointer only for an error message,
// so the hot loop builds no strings.
struct Where {
  Where(std::string_view path_) : path(path_) {}
  Where(const std::string& path_) : path(path_) {}
  Where(const char* path_) : path(path_) {}
  Where(std::string_view path_, std::int64_t index_, int component_ = -1)
      : path(path_), index(index_), component(component_) {}

  std::string pointer() const {
    std::string text(path);
    if (index >= 0) text += "/" + std::to_string(index);
    if (component >= 0) text += "/" + std::to_string(component);
    return text;
  }

  std::string_view path;
  std::int64_t index = -1;
  int component = -1;
};

// A JSON-subset parser over one step line. Errors name the JSON pointer and the column.
class StepLineParser {
 public:
  StepLineParser(const TraceReader& reader, std::string_view text) : reader_(reader), text_(text) {}

  // Parses step, t and hash; with `out` also every body's values into it. Without `out` the
  // arrays are skipped, not parsed, but every key is still checked (an unknown key anywhere is
  // refused on every line, also on lines a diff never parses).
  void parse(StepPrefix& prefix, TraceStep* out) {
    bool has_step = false, has_t = false, has_hash = false, has_bodies = false;
    expect('{', "");
    skipSpace();
    if (peek() == '}') fail("", "empty object");
    for (;;) {
      const std::string_view key = string("");
      expect(':', key);
      if (key == "step") {
        once(has_step, key);
        prefix.step = integer("/step");
      } else if (key == "t") {
        once(has_t, key);
        prefix.t = number("/t", false);
      } else if (key == "hash") {
        once(has_hash, key);
        prefix.hash = hash();
      } else if (key == "bodies") {
        once(has_bodies, key);
        bodies(out);
      } else {
        fail("/" + excerpt(key), "unknown key");
      }
      skipSpace();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      expect('}', "");
      break;
    }
    skipSpace();
    if (pos_ != text_.size()) fail("", "unexpected text after the step object");
    if (!has_step) fail("", "missing key \"step\"");
    if (!has_t) fail("", "missing key \"t\"");
    if (!has_hash) fail("", "missing key \"hash\"");
    if (!has_bodies) fail("", "missing key \"bodies\"");
    if (out) out->prefix = prefix;
  }

 private:
  [[noreturn]] void fail(const Where& where, const std::string& problem) const {
    const std::string pointer = where.pointer();
    reader_.fail(
        fmt::format("{}{}{} (column {})", pointer, pointer.empty() ? "" : ": ", problem, pos_ + 1));
  }

  void once(bool& seen, std::string_view key) const {
    if (seen) fail(std::string("/").append(key), "duplicate key");
    seen = true;
  }

  void skipSpace() {
    while (pos_ < text_.size() &&
           (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r'))
      ++pos_;
  }

  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  char peekAt(std::size_t ahead) const {
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
  }

  void needMore(const Where& pointer) const {
    if (pos_ >= text_.size()) fail(pointer, "truncated line: unexpected end");
  }

  void expect(char c, const Where& pointer) {
    skipSpace();
    needMore(pointer);
    if (text_[pos_] != c) fail(pointer, fmt::format("expected '{}', got '{}'", c, text_[pos_]));
    ++pos_;
  }

  // A string without escapes (keys, hashes and non-finite markers never need them).
  std::string_view string(const Where& pointer) {
    expect('"', pointer);
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      if (text_[pos_] == '\\') fail(pointer, "escaped characters are not expected here");
      ++pos_;
    }
    needMore(pointer);
    return text_.substr(start, pos_++ - start);
  }

  std::int64_t integer(const Where& pointer) {
    skipSpace();
    needMore(pointer);
    std::int64_t value = 0;
    const char* begin = text_.data() + pos_;
    const auto [end, error] = std::from_chars(begin, text_.data() + text_.size(), value);
    if (error != std::errc() || (pos_ < text_.size() && end == begin))
      fail(pointer, "expected an integer");
    if (*end == '.' || *end == 'e' || *end == 'E') fail(pointer, "expected an integer");
    pos_ += std::size_t(end - begin);
    return value;
  }

  std::uint64_t hash() {
    const std::string_view text = string("/hash");
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value, 16);
    if (text.size() != 16 || error != std::errc() || end != text.data() + text.size())
      fail("/hash", fmt::format("expected 16 hex digits, got \"{}\"", excerpt(text)));
    for (char c : text)
      if (c >= 'A' && c <= 'F') fail("/hash", "expected lowercase hex digits");
    return value;
  }

  // A JSON number, or one of the strings "NaN", "Infinity", "-Infinity". Float values are parsed
  // as float so the bits are exactly those written, then widened (exactly) to double.
  double number(const Where& pointer, bool as_float) {
    skipSpace();
    needMore(pointer);
    if (text_[pos_] == '"') {
      const std::string_view marker = string(pointer);
      if (marker == "NaN") return std::numeric_limits<double>::quiet_NaN();
      if (marker == "Infinity") return std::numeric_limits<double>::infinity();
      if (marker == "-Infinity") return -std::numeric_limits<double>::infinity();
      fail(pointer, fmt::format("expected a number or \"NaN\", \"Infinity\", \"-Infinity\", got "
                                "\"{}\"",
                                excerpt(marker)));
    }
    const std::size_t start = pos_;
    // Python's json.dumps writes bare NaN, Infinity and -Infinity tokens (looked for only when
    // the first character says so: this is the hot loop)
    if (text_[pos_] == 'N' || text_[pos_] == 'I' || (text_[pos_] == '-' && peekAt(1) == 'I')) {
      for (const auto& [token, value] : kBareNonFinite) {
        if (text_.substr(pos_, token.size()) == token) {
          pos_ += token.size();
          return value;
        }
      }
    }
    if (text_[pos_] == '-') ++pos_;
    const char first = peek();
    if (first < '0' || first > '9') {
      if (first == '\0') fail(pointer, "truncated line: unexpected end");
      fail(pointer, fmt::format("expected a number, got '{}'", first));
    }
    std::size_t end = pos_;
    while (end < text_.size()) {
      const char c = text_[end];
      if ((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-')
        ++end;
      else
        break;
    }
    const char* begin = text_.data() + start;
    const char* stop = text_.data() + end;
    double value = 0;
    std::from_chars_result result;
    if (as_float) {
      float single = 0;
      result = std::from_chars(begin, stop, single);
      value = single;
    } else {
      result = std::from_chars(begin, stop, value);
    }
    if (result.ec != std::errc() || result.ptr != stop)
      fail(pointer, fmt::format("malformed or out-of-range number '{}'",
                                excerpt(std::string_view(begin, std::size_t(stop - begin)))));
    pos_ = end;
    return value;
  }

  // Skips one array without parsing its numbers (the fast path for lines read only for their
  // prefix).
  void skipArray(const Where& pointer) {
    skipSpace();
    needMore(pointer);
    if (text_[pos_] != '[') fail(pointer, fmt::format("expected '[', got '{}'", text_[pos_]));
    int depth = 0;
    bool in_string = false;
    for (; pos_ < text_.size(); ++pos_) {
      const char c = text_[pos_];
      if (in_string) {
        if (c == '\\')
          ++pos_;
        else if (c == '"')
          in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '{' || c == '[') {
        ++depth;
      } else if (c == '}' || c == ']') {
        if (--depth == 0) {
          ++pos_;
          return;
        }
      }
    }
    fail(pointer, "truncated line: unexpected end");
  }

  void bodies(TraceStep* out) {
    const std::vector<TraceBody>& declared = reader_.header().bodies;
    const bool as_float = reader_.header().precision == Precision::Float;
    if (out) out->bodies.resize(declared.size());
    std::vector<bool> seen(declared.size(), false);
    expect('{', "/bodies");
    skipSpace();
    if (peek() != '}') {
      for (;;) {
        const std::string_view name = string("/bodies");
        std::size_t index = 0;
        while (index < declared.size() && declared[index].name != name) ++index;
        const std::string pointer = "/bodies/" + excerpt(name);
        if (index == declared.size()) fail(pointer, "body not declared in the header");
        if (seen[index]) fail(pointer, "duplicate key");
        seen[index] = true;
        expect(':', pointer);
        body(pointer, declared[index].particles, as_float, out ? &out->bodies[index] : nullptr);
        skipSpace();
        if (peek() != ',') break;
        ++pos_;
      }
    }
    expect('}', "/bodies");
    for (std::size_t i = 0; i < declared.size(); ++i)
      if (!seen[i]) fail("/bodies", fmt::format("missing body \"{}\"", declared[i].name));
  }

  void body(const std::string& pointer, std::int64_t particles, bool as_float, BodyState* out) {
    bool has_position = false, has_velocity = false;
    expect('{', pointer);
    for (;;) {
      const std::string_view key = string(pointer);
      const std::string field = pointer + "/" + excerpt(key);
      expect(':', field);
      if (key == "position") {
        once(has_position, field.substr(1));
        if (out)
          columns(field, particles, as_float, out->position);
        else
          skipArray(field);
      } else if (key == "velocity") {
        once(has_velocity, field.substr(1));
        if (out)
          columns(field, particles, as_float, out->velocity);
        else
          skipArray(field);
      } else {
        fail(field, "unknown key");
      }
      skipSpace();
      if (peek() != ',') break;
      ++pos_;
    }
    expect('}', pointer);
    if (!has_position) fail(pointer, "missing key \"position\"");
    if (!has_velocity) fail(pointer, "missing key \"velocity\"");
  }

  // [[x, y, z], ...] with exactly `particles` entries.
  void columns(const std::string& pointer, std::int64_t particles, bool as_float,
               std::vector<double>& out) {
    // grown as values are read: memory follows the line's length, not the header's claim
    out.clear();
    expect('[', pointer);
    skipSpace();
    std::int64_t count = 0;
    if (peek() != ']') {
      for (;;) {
        if (count == particles)
          fail(pointer, fmt::format("more than the {} particles the header declares", particles));
        const Where particle(pointer, count);
        expect('[', particle);
        for (int k = 0; k < 3; ++k) {
          if (k) expect(',', particle);
          out.push_back(number(Where(pointer, count, k), as_float));
        }
        skipSpace();
        if (peek() == ',') fail(particle, "expected 3 components [x, y, z]");
        expect(']', particle);
        ++count;
        skipSpace();
        if (peek() != ',') break;
        ++pos_;
      }
    }
    expect(']', pointer);
    if (count != particles)
      fail(pointer, fmt::format("{} particles, the header declares {}", count, particles));
  }

  const TraceReader& reader_;
  std::string_view text_;
  std::size_t pos_ = 0;
};

[[noreturn]] void headerError(const std::string& source, const std::string& problem) {
  throw InputError(source + ":1: header: " + problem);
}

// The key is a C string: a `const std::string&` parameter would make each call's literal a
// temporary, and GCC 13+ then warns (-Wdangling-reference) at every `const ordered_json& x =
// headerKey(...)`, although the reference is into `json`.
const ordered_json& headerKey(const ordered_json& json, const std::string& source,
                              const char* key) {
  const auto it = json.find(key);
  if (it == json.end()) headerError(source, std::string("missing key \"") + key + "\"");
  return *it;
}

std::int64_t headerInteger(const ordered_json& value, const std::string& source,
                           const std::string& pointer, std::int64_t minimum,
                           std::int64_t maximum = std::numeric_limits<std::int64_t>::max(),
                           const char* flag = nullptr) {
  if (!value.is_number_integer()) headerError(source, pointer + ": expected an integer");
  if (value.is_number_unsigned() &&
      value.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
    headerError(source, fmt::format("{}: too large (got {})", pointer, value.get<std::uint64_t>()));
  const auto i = value.get<std::int64_t>();
  if (i < minimum)
    headerError(source, fmt::format("{}: must be >= {} (got {})", pointer, minimum, i));
  if (i > maximum)
    headerError(source, fmt::format("{}: {} is above the limit {} (raise it with {})", pointer, i,
                                    maximum, flag));
  return i;
}

HeaderSceneCheck& sceneCheck() {
  static HeaderSceneCheck check = nullptr;
  return check;
}

}  // namespace

void setHeaderSceneCheck(HeaderSceneCheck check) { sceneCheck() = check; }

TraceHeader parseTraceHeader(const ordered_json& json, const std::string& source) {
  if (!json.is_object()) headerError(source, "expected a JSON object");
  TraceHeader header;
  header.json = json;
  const ordered_json& format = headerKey(json, source, "format");
  if (!format.is_string() || format.get<std::string>() != "clothref-trace")
    headerError(source, "/format: not a clothref trace (expected \"clothref-trace\", got " +
                            excerpt(format.dump()) + ")");
  header.version = int(headerInteger(headerKey(json, source, "version"), source, "/version", 0));
  if (header.version != kTraceVersion)
    headerError(source, fmt::format("/version: unsupported version {} (this build reads {})",
                                    header.version, kTraceVersion));
  static const char* const kKnown[] = {"format",    "version", "scene", "integrator",
                                       "precision", "dt",      "steps", "stride",
                                       "bodies",    "hash",    "build"};
  for (const auto& item : json.items())
    if (std::find(std::begin(kKnown), std::end(kKnown), item.key()) == std::end(kKnown))
      headerError(source, "/" + excerpt(item.key()) + ": unknown key");
  const ordered_json& scene = headerKey(json, source, "scene");
  if (!scene.is_object()) headerError(source, "/scene: expected an object");
  if (sceneCheck()) {
    try {
      sceneCheck()(scene);
    } catch (const InputError& error) {
      headerError(source, std::string("/scene") + error.what());
    }
  }
  const ordered_json& integrator = headerKey(json, source, "integrator");
  if (!integrator.is_string()) headerError(source, "/integrator: expected a string");
  header.integrator = integrator.get<std::string>();
  const ordered_json& precision = headerKey(json, source, "precision");
  const auto parsed = precision.is_string()
                          ? parseEnum(kPrecisionNames, precision.get<std::string>())
                          : std::nullopt;
  if (!parsed)
    headerError(source,
                "/precision: expected \"float\" or \"double\", got " + excerpt(precision.dump()));
  header.precision = *parsed;
  const ordered_json& dt = headerKey(json, source, "dt");
  if (!dt.is_number() || !(dt.get<double>() > 0))
    headerError(source, "/dt: expected a number > 0, got " + excerpt(dt.dump()));
  header.dt = dt.get<double>();
  header.steps = headerInteger(headerKey(json, source, "steps"), source, "/steps", 0,
                               inputLimits().steps, "--max-steps");
  header.stride = headerInteger(headerKey(json, source, "stride"), source, "/stride", 1);
  const ordered_json& bodies = headerKey(json, source, "bodies");
  if (!bodies.is_array()) headerError(source, "/bodies: expected an array");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string pointer = fmt::format("/bodies/{}", i);
    const ordered_json& body = bodies[i];
    if (!body.is_object() || body.size() != 2 || !body.contains("name") ||
        !body["name"].is_string() || !body.contains("particles"))
      headerError(source, pointer + ": expected {\"name\": string, \"particles\": integer}");
    TraceBody parsed{body["name"].get<std::string>(),
                     headerInteger(body["particles"], source, pointer + "/particles", 0,
                                   inputLimits().particles, "--max-particles")};
    for (const TraceBody& other : header.bodies)
      if (other.name == parsed.name)
        headerError(source, pointer + ": duplicate body " + excerpt(parsed.name));
    header.bodies.push_back(std::move(parsed));
  }
  if (!headerKey(json, source, "hash").is_string()) headerError(source, "/hash: expected a string");
  if (!headerKey(json, source, "build").is_object())
    headerError(source, "/build: expected an object");
  return header;
}

TraceReader::TraceReader(const std::string& path) : path_(path) {
  requireStreamInput(path, "trace");
  if (path == "-") {
    path_ = "standard input";
    in_ = &std::cin;
  } else {
    errno = 0;
    owned_ = std::make_unique<std::ifstream>(path, std::ios::binary);
    if (!*owned_) throw InputError(cannotOpenMessage(path, "open", "trace file", errno));
    in_ = owned_.get();
  }
  readHeader();
}

TraceReader::TraceReader(std::istream& in, const std::string& source) : path_(source), in_(&in) {
  readHeader();
}

TraceReader::~TraceReader() = default;

bool TraceReader::readLine(bool& ended_with_newline, std::size_t limit, const char* what,
                           const char* flag) {
  line_.clear();
  ended_with_newline = false;
  std::streambuf& buffer = *in_->rdbuf();
  try {
    for (;;) {
      const int c = buffer.sbumpc();
      if (c == std::char_traits<char>::eof()) return !line_.empty();
      if (c == '\n') {
        ended_with_newline = true;
        return true;
      }
      if (line_.size() == limit) {
        ++line_number_;
        fail(fmt::format("{} longer than {} bytes (raise the limit with {})", what, limit, flag));
      }
      line_.push_back(char(c));
    }
  } catch (const std::ios_base::failure&) {
    fail(gzip_ && !gzip_->error().empty() ? gzip_->error() : "read error");
  }
}

void TraceReader::readHeader() {
  if (startsLikeGzip(*in_->rdbuf())) {
    gzip_ = std::make_unique<GzipInputBuffer>(*in_->rdbuf(), path_);
    gzip_stream_ = std::make_unique<std::istream>(gzip_.get());
    in_ = gzip_stream_.get();
  }
  line_number_ = 0;
  bool ended_with_newline = false;
  // bounded before any JSON parsing: a 240 MB header from a 234 kB gzip took 7.7 GB as a DOM
  const bool read =
      readLine(ended_with_newline, inputLimits().header_bytes, "header line", "--max-header-bytes");
  line_number_ = 1;
  if (!read || line_.empty()) throw InputError(path_ + ":1: empty file, expected a trace header");
  const ordered_json json = parseOrderedJson(line_, path_ + ":1: header");
  header_ = parseTraceHeader(json, path_);
  own_hash_ = header_.json["hash"] == std::string(kTraceHashDescription);
}

void TraceReader::fail(const std::string& problem) const {
  throw InputError(fmt::format("{}:{}: {}", path_, line_number_, problem));
}

bool TraceReader::next() {
  bool ended_with_newline = false;
  if (!readLine(ended_with_newline, inputLimits().line_bytes, "line", "--max-line-bytes")) {
    // a complete trace ends with the last step (always recorded)
    const std::int64_t last = has_step_ ? prefix_.step : -1;
    if (last != header_.steps)
      fail(fmt::format("trace ends after step {}, the header says {} steps (truncated?)", last,
                       header_.steps));
    return false;
  }
  ++line_number_;
  if (line_.empty()) fail("empty line");
  const std::int64_t previous = has_step_ ? prefix_.step : -1;
  StepPrefix prefix;
  StepLineParser(*this, line_).parse(prefix, nullptr);
  // the recorded steps are exactly those the header's steps and stride give, in order
  // (written so no step count near 2^63 overflows: base <= previous <= steps)
  const std::int64_t base = previous - previous % header_.stride;
  const std::int64_t expected = previous < 0                             ? 0
                                : header_.steps - base <= header_.stride ? header_.steps
                                                                         : base + header_.stride;
  if (previous == header_.steps)
    fail(fmt::format("/step: {} after the last step {} the header declares", prefix.step,
                     header_.steps));
  if (prefix.step != expected)
    fail(fmt::format("/step: expected step {} (steps {}, stride {}), got {}", expected,
                     header_.steps, header_.stride, prefix.step));
  // the writer ends every line with a newline; a last line without one was cut short
  if (!ended_with_newline) fail("truncated line: no newline at the end of the file");
  prefix_ = prefix;
  has_step_ = true;
  return true;
}

void TraceReader::parseStep(TraceStep& step) const {
  StepPrefix prefix;
  StepLineParser(*this, line_).parse(prefix, &step);
  // A hash that does not match its own values is a corrupt or edited record, whatever another
  // trace holds. NaN is written as "NaN" whatever its sign and payload bits, so a step holding one
  // cannot be rehashed from its text; its hash is taken as written.
  if (!own_hash_) return;
  for (const BodyState& body : step.bodies)
    for (const std::vector<double>* values : {&body.position, &body.velocity})
      for (double value : *values)
        if (std::isnan(value)) return;
  if (stateHashOf(header_, step) != prefix.hash)
    fail("/hash: does not match the step's own values (a corrupt or edited record)");
}

std::uint64_t stateHashOf(const TraceHeader& header, const TraceStep& step) {
  return withPrecision(header.precision, [&]<typename T>() {
    // BodyView's layout: one (x, y, z, w) column per particle; w is not hashed
    std::vector<std::vector<T>> storage;
    std::vector<BodyView<T>> views;
    for (std::size_t i = 0; i < header.bodies.size() && i < step.bodies.size(); ++i) {
      const BodyState& body = step.bodies[i];
      const std::size_t n = body.position.size() / 3;
      for (const std::vector<double>* values : {&body.position, &body.velocity}) {
        std::vector<T>& columns = storage.emplace_back(4 * n, T(0));
        for (std::size_t p = 0; p < n && 3 * p + 2 < values->size(); ++p)
          for (std::size_t k = 0; k < 3; ++k) columns[4 * p + k] = T((*values)[3 * p + k]);
      }
    }
    for (std::size_t i = 0; i < header.bodies.size() && i < step.bodies.size(); ++i)
      views.push_back({header.bodies[i].name, storage[2 * i].data(), storage[2 * i + 1].data(),
                       int(step.bodies[i].position.size() / 3)});
    return stateHash<T>(std::span<const BodyView<T>>(views));
  });
}

Trace readTrace(const std::string& path) {
  TraceReader reader(path);
  Trace trace{reader.header(), {}};
  while (reader.next()) {
    trace.steps.emplace_back();
    reader.parseStep(trace.steps.back());
  }
  return trace;
}

}  // namespace clothref
