// The page sources (tools/pages/assets/: HTML templates, the viewer's JavaScript, the CSS),
// compiled into the binary at build time (embed_assets.cmake), so a page is written without the
// source tree.
#pragma once

#include <string_view>

namespace clothref::pages {

// The bytes of the asset file `name` (e.g. "viewer.js"); throws std::logic_error for an unknown
// name (a programming error: the names are fixed in tools/pages/CMakeLists.txt).
std::string_view pageAsset(std::string_view name);

}  // namespace clothref::pages
