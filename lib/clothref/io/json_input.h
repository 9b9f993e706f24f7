// The one JSON input reader: every file format the library reads (scene, tolerance file, golden
// manifest, trace header, the grader's rubric) parses through here, so every syntax error says
// the same things: the source, the JSON pointer of the value being read, the line and column,
// and the parser's reason.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace clothref {

// Parses `text`. Throws InputError
//   "<source>: <pointer>: not valid JSON (line L, column C): <reason>"
// for text that is not JSON (a number too large for a double included).
nlohmann::json parseJson(std::string_view text, const std::string& source);
nlohmann::ordered_json parseOrderedJson(std::string_view text, const std::string& source);

// Reads and parses a whole file (io/files.h limits apply); `what` names it in messages.
nlohmann::json readJsonFile(const std::string& path, const std::string& what);

}  // namespace clothref
