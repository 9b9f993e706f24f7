# Writes OUTPUT (a header defining CLOTHREF_GIT_REVISION, e.g. "4bb2988c1d2e-dirty") from the git
# tree at SOURCE_DIR; outside a git checkout, from SOURCE_DIR/REVISION (an exported tree, such as
# the Gradescope archive, carries it), else "unknown". Run at every build by
# tools/CMakeLists.txt; the file is rewritten only when the revision changed, so an unchanged
# revision recompiles nothing.
# Arguments: -DSOURCE_DIR=<source tree> -DOUTPUT=<header path>
set(revision unknown)
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} describe --always --dirty --abbrev=12
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(code EQUAL 0 AND NOT out STREQUAL "")
    set(revision "${out}")
  endif()
endif()
if(revision STREQUAL "unknown" AND EXISTS ${SOURCE_DIR}/REVISION)
  file(STRINGS ${SOURCE_DIR}/REVISION lines LIMIT_COUNT 1)
  if(lines MATCHES "^[0-9a-f]+(-dirty)?$")
    set(revision "${lines}")
  endif()
endif()
set(text "// Generated at build time by cmake/GitRevision.cmake: the source revision of this binary.
#pragma once
#define CLOTHREF_GIT_REVISION \"${revision}\"
")
set(old "")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
