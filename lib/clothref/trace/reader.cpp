#include "clothref/trace/reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/trace/format.h"

namespace clothref {

namespace {

using ordered_json = nlohmann::ordered_json;

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

  // Parses step, t and hash; with `values` also every body into `out`. Without `values` it stops
  // as soon as the three prefix keys are read (the writer puts them first).
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
        if (!std::isfinite(prefix.t)) fail("/t", "must be a finite number");
      } else if (key == "hash") {
        once(has_hash, key);
        prefix.hash = hash();
      } else if (key == "bodies") {
        once(has_bodies, key);
        if (out) {
          bodies(*out);
        } else {
          skipValue("/bodies");
        }
      } else {
        fail(std::string("/").append(key), "unknown key");
      }
      if (!out && has_step && has_t && has_hash) return;
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
      fail("/hash", fmt::format("expected 16 hex digits, got \"{}\"", text));
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
                                marker));
    }
    const std::size_t start = pos_;
    if (text_[pos_] == '-') ++pos_;
    const char first = peek();
    if (first < '0' || first > '9') {
      if (first == 'N' || first == 'n' || first == 'I' || first == 'i')
        fail(pointer,
             "bare NaN/Infinity token (non-finite values are written as the strings "
             "\"NaN\", \"Infinity\", \"-Infinity\")");
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
                                std::string_view(begin, std::size_t(stop - begin))));
    pos_ = end;
    return value;
  }

  // Skips one JSON value (used only when "bodies" comes before the prefix keys).
  void skipValue(const Where& pointer) {
    skipSpace();
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

  void bodies(TraceStep& out) {
    const std::vector<TraceBody>& declared = reader_.header().bodies;
    const bool as_float = reader_.header().precision == Precision::Float;
    out.bodies.resize(declared.size());
    std::vector<bool> seen(declared.size(), false);
    expect('{', "/bodies");
    skipSpace();
    if (peek() != '}') {
      for (;;) {
        const std::string_view name = string("/bodies");
        std::size_t index = 0;
        while (index < declared.size() && declared[index].name != name) ++index;
        const std::string pointer = "/bodies/" + std::string(name);
        if (index == declared.size()) fail(pointer, "body not declared in the header");
        if (seen[index]) fail(pointer, "duplicate key");
        seen[index] = true;
        expect(':', pointer);
        body(pointer, declared[index].particles, as_float, out.bodies[index]);
        skipSpace();
        if (peek() != ',') break;
        ++pos_;
      }
    }
    expect('}', "/bodies");
    for (std::size_t i = 0; i < declared.size(); ++i)
      if (!seen[i]) fail("/bodies", fmt::format("missing body \"{}\"", declared[i].name));
  }

  void body(const std::string& pointer, std::int64_t particles, bool as_float, BodyState& out) {
    bool has_position = false, has_velocity = false;
    expect('{', pointer);
    for (;;) {
      const std::string_view key = string(pointer);
      const std::string field = pointer + "/" + std::string(key);
      expect(':', field);
      if (key == "position") {
        once(has_position, field.substr(1));
        columns(field, particles, as_float, out.position);
      } else if (key == "velocity") {
        once(has_velocity, field.substr(1));
        columns(field, particles, as_float, out.velocity);
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
    out.resize(std::size_t(3 * particles));
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
          out[std::size_t(3 * count + k)] = number(Where(pointer, count, k), as_float);
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

const ordered_json& headerKey(const ordered_json& json, const std::string& source,
                              const std::string& key) {
  const auto it = json.find(key);
  if (it == json.end()) headerError(source, "missing key \"" + key + "\"");
  return *it;
}

std::int64_t headerInteger(const ordered_json& value, const std::string& source,
                           const std::string& pointer, std::int64_t minimum) {
  if (!value.is_number_integer()) headerError(source, pointer + ": expected an integer");
  const auto i = value.get<std::int64_t>();
  if (i < minimum)
    headerError(source, fmt::format("{}: must be >= {} (got {})", pointer, minimum, i));
  return i;
}

}  // namespace

TraceHeader parseTraceHeader(const ordered_json& json, const std::string& source) {
  if (!json.is_object()) headerError(source, "expected a JSON object");
  TraceHeader header;
  header.json = json;
  const ordered_json& format = headerKey(json, source, "format");
  if (format != "clothref-trace")
    headerError(source, "/format: not a clothref trace (expected \"clothref-trace\", got " +
                            format.dump() + ")");
  header.version = int(headerInteger(headerKey(json, source, "version"), source, "/version", 0));
  if (header.version != kTraceVersion)
    headerError(source, fmt::format("/version: unsupported version {} (this build reads {})",
                                    header.version, kTraceVersion));
  static const char* const kKnown[] = {"format",    "version", "scene", "integrator",
                                       "precision", "dt",      "steps", "stride",
                                       "bodies",    "hash",    "build"};
  for (const auto& item : json.items())
    if (std::find(std::begin(kKnown), std::end(kKnown), item.key()) == std::end(kKnown))
      headerError(source, "/" + item.key() + ": unknown key");
  if (!headerKey(json, source, "scene").is_object())
    headerError(source, "/scene: expected an object");
  const ordered_json& integrator = headerKey(json, source, "integrator");
  if (!integrator.is_string()) headerError(source, "/integrator: expected a string");
  header.integrator = integrator.get<std::string>();
  const ordered_json& precision = headerKey(json, source, "precision");
  const auto parsed = precision.is_string()
                          ? parseEnum(kPrecisionNames, precision.get<std::string>())
                          : std::nullopt;
  if (!parsed)
    headerError(source, "/precision: expected \"float\" or \"double\", got " + precision.dump());
  header.precision = *parsed;
  const ordered_json& dt = headerKey(json, source, "dt");
  if (!dt.is_number() || !(dt.get<double>() > 0))
    headerError(source, "/dt: expected a number > 0, got " + dt.dump());
  header.dt = dt.get<double>();
  header.steps = headerInteger(headerKey(json, source, "steps"), source, "/steps", 0);
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
                     headerInteger(body["particles"], source, pointer + "/particles", 0)};
    for (const TraceBody& other : header.bodies)
      if (other.name == parsed.name)
        headerError(source, pointer + ": duplicate body " + parsed.name);
    header.bodies.push_back(std::move(parsed));
  }
  if (!headerKey(json, source, "hash").is_string()) headerError(source, "/hash: expected a string");
  if (!headerKey(json, source, "build").is_object())
    headerError(source, "/build: expected an object");
  return header;
}

TraceReader::TraceReader(const std::string& path)
    : path_(path), owned_(std::make_unique<std::ifstream>(path, std::ios::binary)), in_(owned_.get()) {
  if (!*owned_) throw InputError(path + ": cannot open the trace file");
  readHeader();
}

TraceReader::TraceReader(std::istream& in, const std::string& source) : path_(source), in_(&in) {
  readHeader();
}

void TraceReader::readHeader() {
  line_number_ = 1;
  if (!std::getline(*in_, line_) || line_.empty())
    throw InputError(path_ + ":1: empty file, expected a trace header");
  const ordered_json json = parseOrderedJson(line_, path_ + ":1: header");
  header_ = parseTraceHeader(json, path_);
}

void TraceReader::fail(const std::string& problem) const {
  throw InputError(fmt::format("{}:{}: {}", path_, line_number_, problem));
}

bool TraceReader::next() {
  if (!std::getline(*in_, line_)) {
    if (in_->bad()) fail("read error");
    // a complete trace ends with the last step (always recorded)
    const std::int64_t last = has_step_ ? prefix_.step : -1;
    if (last != header_.steps)
      fail(fmt::format("trace ends after step {}, the header says {} steps (truncated?)", last,
                       header_.steps));
    return false;
  }
  const bool ended_with_newline = !in_->eof();
  ++line_number_;
  if (line_.empty()) fail("empty line");
  const std::int64_t previous = has_step_ ? prefix_.step : -1;
  StepPrefix prefix;
  StepLineParser(*this, line_).parse(prefix, nullptr);
  // the recorded steps are exactly those the header's steps and stride give, in order
  const std::int64_t expected =
      previous < 0 ? 0
                   : std::min(previous - previous % header_.stride + header_.stride, header_.steps);
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
