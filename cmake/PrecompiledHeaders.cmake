# Precompiled headers for the heavy packages that the tools' and tests' files read (Eigen, fmt,
# nlohmann-json, and GoogleTest for tests): parsed once per build, not once per file. About half
# of a test file's compile time (4 of 9 s of CPU) is these headers; CI builds every file from
# nothing, twice over with the Gradescope test's build of the CLI.
#
# Off under a compiler launcher (ccache): ccache compiles a file that reads a .gch without caching
# it, so a cached rebuild would lose more than the headers save. The library's areas do not use
# them: each installs as a package of its own, with its own dependencies.
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(clothref_pch_default OFF)
else()
  set(clothref_pch_default ON)
endif()
option(CLOTHREF_PCH "Precompiled headers for the tools and tests (off under a compiler launcher)"
       ${clothref_pch_default})

set(CLOTHREF_PCH_HEADERS <Eigen/Dense> <fmt/format.h> <nlohmann/json.hpp> <algorithm> <filesystem>
    <fstream> <functional> <map> <optional> <sstream> <string> <vector>)

# clothref_pch_target(NAME [HEADERS <h>...] LIBRARIES <target>...): a target that compiles the
# headers above (and HEADERS) once, with the flags of the files that share it: the project's
# options and the macros its LIBRARIES define (GCC skips a .gch built with a macro the file lacks,
# and -Winvalid-pch says so).
function(clothref_pch_target name)
  cmake_parse_arguments(PCH "" "" "HEADERS;LIBRARIES" ${ARGN})
  if(NOT CLOTHREF_PCH)
    return()
  endif()
  add_library(${name} OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch_anchor.cpp)
  target_link_libraries(${name} PRIVATE ${PCH_LIBRARIES})
  target_precompile_headers(${name} PRIVATE ${CLOTHREF_PCH_HEADERS} ${PCH_HEADERS})
endfunction()

# clothref_use_pch(TARGET NAME): TARGET's files read the headers NAME compiled.
function(clothref_use_pch target name)
  if(CLOTHREF_PCH)
    target_precompile_headers(${target} REUSE_FROM ${name})
    target_compile_options(${target} PRIVATE -Winvalid-pch)
    # GCC 12's false positive inside libstdc++ on `"text" + std::string&&` (bug 105329; the
    # -Wrestrict of CMakeLists.txt) shows through a .gch as -Warray-bounds and -Wstringop-overflow
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
      target_compile_options(${target} PRIVATE -Wno-array-bounds -Wno-stringop-overflow)
    endif()
  endif()
endfunction()
