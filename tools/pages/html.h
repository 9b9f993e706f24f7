// What every page clothref writes shares: escaping of text a user or a student controls, JSON data
// embedded in a <script> element, base64 of binary frames, and filling a page template.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace clothref::pages {

// Text for HTML element content or a quoted attribute: & < > " ' escaped, bytes that are not
// UTF-8 replaced by U+FFFD, control characters other than tab and newline dropped, and the
// controls of text direction (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069) shown as
// \u{202E}, so no name displays in another order than its characters.
std::string escapeHtml(std::string_view text);

// `data` as JSON safe inside <script type="application/json">: invalid UTF-8 replaced by U+FFFD
// and < > & written as \u003c \u003e \u0026, so no string can close the element.
std::string jsonForScript(const nlohmann::ordered_json& data);

// Standard base64 (RFC 4648, with padding) of `size` bytes.
std::string base64(const void* bytes, std::size_t size);

// `page` with each {{NAME}} replaced by its value, in one pass (a value is never searched for
// placeholders). Throws std::logic_error for a placeholder without a value or a value without a
// placeholder: both are mistakes in a template, never in user input.
std::string fillTemplate(std::string_view page,
                         const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace clothref::pages
