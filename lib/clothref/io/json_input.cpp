#include "clothref/io/json_input.h"

#include <algorithm>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/io/files.h"
#include "clothref/io/limits.h"

namespace clothref {

using json = nlohmann::json;

namespace {

// Re-reads a JSON text that failed to parse, to say where: the JSON pointer of the value being
// read, and the line and column of the failure (nlohmann's DOM parser gives no position for a
// number too large for a double).
class JsonErrorLocator : public nlohmann::json_sax<json> {
 public:
  explicit JsonErrorLocator(const std::string& text) : text_(text) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    frames_.push_back({false, 0, ""});
    return true;
  }
  bool key(string_t& key) override {
    frames_.back().key = key;
    return true;
  }
  bool end_object() override { return end(); }
  bool start_array(std::size_t) override {
    frames_.push_back({true, 0, ""});
    return true;
  }
  bool end_array() override { return end(); }
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception&) override {
    for (const Frame& frame : frames_)
      pointer_ += "/" + (frame.array ? std::to_string(frame.index) : frame.key);
    // position counts characters read, the failing one included
    const std::size_t offset = std::min(position > 0 ? position - 1 : 0, text_.size());
    line_ = 1 + std::count(text_.begin(), text_.begin() + offset, '\n');
    const std::size_t line_start = text_.rfind('\n', offset == 0 ? 0 : offset - 1);
    column_ = offset - (line_start == std::string::npos || offset == 0 ? 0 : line_start + 1) + 1;
    return false;
  }

  // "<pointer>: not valid JSON (line L, column C)"
  std::string where() const {
    return fmt::format("{}: not valid JSON (line {}, column {})", pointer_.empty() ? "/" : pointer_,
                       line_, column_);
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
  };
  // a value was read: the next element of an enclosing array has the next index
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool end() {
    frames_.pop_back();
    return value();
  }

  const std::string& text_;
  std::vector<Frame> frames_;
  std::string pointer_;
  std::size_t line_ = 0, column_ = 0;
};

// nlohmann's reason without its "[json.exception.parse_error.101] parse error at line 1, column 2:
// "
std::string reasonOf(const json::exception& error) {
  std::string reason = error.what();
  for (const char* prefix : {"] ", ": "}) {
    const auto at = reason.find(prefix);
    if (at != std::string::npos && (prefix[0] == ']' || reason.find("parse error") == 0))
      reason = reason.substr(at + 2);
  }
  return reason;
}

// Refuses nesting deeper than the limit before parsing: a 10^5-deep array parses, but freeing or
// printing it recurses once per level and overflows the stack.
void checkDepth(std::string_view text, const std::string& source) {
  const std::size_t limit = inputLimits().json_depth;
  std::size_t depth = 0, line = 1;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '\n') {
      ++line;
    } else if (c == '[' || c == '{') {
      if (++depth > limit)
        throw InputError(fmt::format(
            "{}: nested deeper than {} levels (line {}; raise the limit with --max-json-depth)",
            source, limit, line));
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// Follows the parse to refuse a key repeated in one object (nlohmann keeps the last silently, so
// `{"dt": 1, "dt": 2}` would read as another value than a reader keeping the first sees).
template <typename Json>
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& source) : source_(source) {}

  bool operator()(int, nlohmann::detail::parse_event_t event, Json& parsed) {
    using Event = nlohmann::detail::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        frames_.push_back({event == Event::array_start, 0, "", {}});
        break;
      case Event::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.template get<std::string>();
        if (!frame.keys.insert(frame.key).second)
          throw InputError(fmt::format("{}: {}: duplicate key", source_, pointer()));
        break;
      }
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        [[fallthrough]];
      case Event::value:
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
    std::set<std::string> keys;
  };
  std::string pointer() const {
    std::string text;
    for (const Frame& frame : frames_)
      text += "/" + (frame.array ? std::to_string(frame.index) : excerpt(frame.key));
    return text;
  }
  const std::string& source_;
  std::vector<Frame> frames_;
};

template <typename Json>
Json parse(std::string_view text, const std::string& source) {
  checkDepth(text, source);
  try {
    return Json::parse(text, DuplicateKeyCheck<Json>(source));
  } catch (const json::exception& error) {
    const std::string copy(text);
    JsonErrorLocator locator(copy);
    json::sax_parse(copy, &locator);
    throw InputError(source + ": " + locator.where() + ": " + excerpt(reasonOf(error), 160));
  }
}

}  // namespace

json parseJson(std::string_view text, const std::string& source) {
  return parse<json>(text, source);
}

nlohmann::ordered_json parseOrderedJson(std::string_view text, const std::string& source) {
  return parse<nlohmann::ordered_json>(text, source);
}

json readJsonFile(const std::string& path, const std::string& what) {
  return parseJson(readFile(path, what), path);
}

}  // namespace clothref
