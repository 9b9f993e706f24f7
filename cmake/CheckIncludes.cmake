# Checks the include rules (docs/layout.md): the library's areas, run as `cmake
# -DROOT=lib/clothref -P cmake/CheckIncludes.cmake`, and the grader's rooms, run as `cmake
# -DGRADER=tools/grader -P cmake/CheckIncludes.cmake` (either or both). The build runs it before
# any library area or grader file compiles, so a wrong include fails the build with the file, the
# line and the rule it breaks.
#
# For each area (a folder of lib/clothref): the other areas it may include ("clothref/<area>/...")
# and the non-standard headers it may include (<prefix...>). Standard C++ headers (<vector>) are
# always allowed.

set(RULES_base_AREAS "")
set(RULES_base_EXTERNAL "")
set(RULES_formula_AREAS "")
set(RULES_formula_EXTERNAL "")
set(RULES_fast_AREAS "formula")
set(RULES_fast_EXTERNAL "immintrin.h;cpuid.h;x86intrin.h")
set(RULES_core_AREAS "base;fast;formula")
set(RULES_core_EXTERNAL "Eigen/")
set(RULES_io_AREAS "base")
set(RULES_io_EXTERNAL "nlohmann/;fmt/;stdlib.h;unistd.h;fcntl.h;sys/;signal.h;zlib.h")
set(RULES_scene_AREAS "base;core;io;solver")
set(RULES_scene_EXTERNAL "Eigen/;nlohmann/;fmt/")
set(RULES_trace_AREAS "base;io")
set(RULES_trace_EXTERNAL "nlohmann/;fmt/;xxhash.h")
set(RULES_diff_AREAS "base;io;trace")
set(RULES_diff_EXTERNAL "nlohmann/;fmt/")
set(RULES_record_AREAS "base;core;io;scene;trace")
set(RULES_record_EXTERNAL "Eigen/;nlohmann/;fmt/")
set(RULES_golden_AREAS "base;core;io;scene;trace;diff;record")
set(RULES_golden_EXTERNAL "Eigen/;nlohmann/;fmt/;unistd.h")
set(RULES_verify_AREAS "base;core;io;scene;solver")
set(RULES_verify_EXTERNAL "Eigen/;nlohmann/;fmt/;boost/numeric/odeint/")
set(RULES_solver_AREAS "base;core")
set(RULES_solver_EXTERNAL "Eigen/")
set(RULES_analysis_AREAS "base;core;io;scene;trace;record;verify;solver")
set(RULES_analysis_EXTERNAL "Eigen/;nlohmann/;fmt/")
# the umbrella header clothref/clothref.h (one include for a consumer): only the areas it gathers
set(RULES_clothref.h_AREAS "core;record;scene;trace")
set(RULES_clothref.h_EXTERNAL "")

# The grader's rooms (tools/grader; docs/layout.md, "The grader's rooms"): the folder of each, as
# a regular expression over the file's path in tools/grader, and what its files may include, as
# regular expressions over the include as written, its opening delimiter included: "grader/grade/
# run/ is a room, "grader/grade/results.h one file, "clothref/io/ a library area, <Eigen/ a
# package, "[^/]+$ a course header by its bare name (the course's include path finds it).
# Standard C++ headers (<vector>) are always allowed; a path with ".." never is.
set(GRADER_ROOMS bridge course reference driver submission run mistakes explain probes report
    grade prebuild)
# the one crossing of the two sides: std only
set(GRADER_bridge_FILES "^bridge/")
set(GRADER_bridge_MAY "")
# the course's stand-in headers and framework, and our course-form reference files
set(GRADER_course_FILES "^course/")
set(GRADER_course_MAY "\"[^/]+$" "<Eigen/" "<glad/" "<stdint\\.h>")
set(GRADER_reference_FILES "^reference/")
set(GRADER_reference_MAY "\"[^/]+$" "<Eigen/")
# the child's main and its groups: the course's headers, the bridge, the driver's own, and
# clothref's std-only formulas and method table (never another clothref header: the course's names
# and clothref's never meet)
set(GRADER_driver_FILES "^driver/")
set(GRADER_driver_MAY "\"[^/]+$" "\"grader/bridge/" "\"grader/driver/" "\"clothref/formula/"
    "\"clothref/core/method\\.h\"" "<Eigen/" "<unistd\\.h>")
# reading a submission (its files, their source text and patterns, the edition they were written
# for and that edition's course values): of the top level only the plain-data results and text
set(GRADER_submission_FILES "^grade/submission/")
set(GRADER_submission_MAY "\"grader/grade/submission/" "\"grader/grade/(results|text)\\.h\""
    "\"clothref/(io|scene)/" "<unistd\\.h>" "<fcntl\\.h>" "<dirent\\.h>" "<sys/" "<linux/")
# running untrusted code: never the probes, the reports or the grade's top level beyond its
# plain-data results and text helpers
set(GRADER_run_FILES "^grade/run/")
set(GRADER_run_MAY "\"grader/bridge/" "\"grader/grade/run/" "\"grader/grade/submission/"
    "\"grader/grade/(results|text)\\.h\""
    "\"clothref/io/" "<unistd\\.h>" "<fcntl\\.h>" "<signal\\.h>" "<sched\\.h>" "<poll\\.h>"
    "<grp\\.h>" "<dirent\\.h>" "<sys/" "<linux/")
# the mistake models: the library's course code with a student's mistake switched on, chosen by
# data; the edition's values (submission/edition.h), the rubric's accepted variants
set(GRADER_mistakes_FILES "^grade/mistakes/")
set(GRADER_mistakes_MAY "\"grader/grade/mistakes/" "\"grader/grade/submission/"
    "\"grader/grade/(results|rubric|cause_ids)\\.h\"" "\"clothref/(base|core|formula)/" "<Eigen/")
# the explanations of a student's numbers: the fits (the constants and stage forms that reproduce
# them), how evidence names causes, and the texts of a comparison; plain data, no child process
set(GRADER_explain_FILES "^grade/explain/")
set(GRADER_explain_MAY "\"grader/grade/explain/" "\"grader/grade/submission/" "\"grader/bridge/"
    "\"grader/grade/(results|text|cause_ids)\\.h\"" "<Eigen/" "<nlohmann/")
# the probes: run, submission, the mistake models, the explanations, and of the top level the results, rubric, text helpers,
# the catalogue and its generated cause-id constants (cause_ids.h, in the build tree);
# never the reports
set(GRADER_probes_FILES "^grade/probes/")
set(GRADER_probes_MAY "\"grader/bridge/" "\"grader/grade/run/" "\"grader/grade/submission/"
    "\"grader/grade/mistakes/" "\"grader/grade/explain/" "\"grader/grade/probes/"
    "\"grader/grade/(results|rubric|text|catalogue|cause_ids)\\.h\""
    "\"clothref/(base|core|io|scene|solver|trace|diff|record|verify|formula|analysis)/" "<Eigen/"
    "<nlohmann/")
# the writers: results and pages only. Of the top level the plain-data results, the text helpers
# and the generated cause ids; never the grading (grade.h), the batch (batch.h), run or probes
set(GRADER_report_FILES "^grade/report/")
set(GRADER_report_MAY "\"grader/grade/report/" "\"grader/grade/(results|text|cause_ids)\\.h\""
    "\"clothref/io/" "\"clothref/trace/" "\"pages/" "<nlohmann/" "<fmt/" "<stdlib\\.h>")
# the top level (grade, batch, rubric, text, results): of the probes only their table, probes.h
set(GRADER_grade_FILES "^grade/[^/]+$")
set(GRADER_grade_MAY "\"grader/grade/[^/]+$" "\"grader/grade/run/" "\"grader/grade/submission/"
    "\"grader/grade/probes/probes\\.h\"" "\"grader/grade/report/" "\"clothref/io/" "<nlohmann/"
    "<iconv\\.h>" "<unistd\\.h>" "<fcntl\\.h>" "<sys/")
set(GRADER_prebuild_FILES "^prebuild/")
set(GRADER_prebuild_MAY "\"grader/grade/run/")

if(NOT ROOT AND NOT GRADER)
  message(FATAL_ERROR "CheckIncludes.cmake: pass -DROOT=<path to lib/clothref> and/or "
                      "-DGRADER=<path to tools/grader>")
endif()
# Relative to the working directory: GLOB_RECURSE ... RELATIVE finds nothing under a relative
# path, so a check of no file would pass.
foreach(tree ROOT GRADER)
  if(${tree})
    get_filename_component(${tree} "${${tree}}" ABSOLUTE)
    if(NOT IS_DIRECTORY "${${tree}}")
      message(FATAL_ERROR "CheckIncludes.cmake: ${tree}=${${tree}} is not a folder")
    endif()
  endif()
endforeach()
set(violations 0)

# The include of `line` as written ("clothref/io/error.h" or <vector>, delimiters kept), or "".
function(include_of line out)
  set(${out} "" PARENT_SCOPE)
  if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*(\"[^\"]+\"|<[^>]+>)")
    set(${out} "${CMAKE_MATCH_1}" PARENT_SCOPE)
  endif()
endfunction()

if(GRADER)
  file(GLOB_RECURSE grader_files RELATIVE ${GRADER} ${GRADER}/*.h ${GRADER}/*.cpp)
  foreach(file ${grader_files})
    set(room "")
    foreach(candidate IN LISTS GRADER_ROOMS)
      if(NOT room AND file MATCHES "${GRADER_${candidate}_FILES}")
        set(room ${candidate})
      endif()
    endforeach()
    if(NOT room)
      message(SEND_ERROR "tools/grader/${file}: no room has include rules for it: add one to "
                         "cmake/CheckIncludes.cmake and docs/layout.md")
      math(EXPR violations "${violations} + 1")
      continue()
    endif()
    # UTF-8: a non-ASCII character would otherwise split its line in two (wrong line numbers)
    file(STRINGS ${GRADER}/${file} lines ENCODING UTF-8)
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      include_of("${line}" written)
      if(NOT written)
        continue()
      endif()
      set(allowed FALSE)
      if(written MATCHES "^<[^./]+>$")
        set(allowed TRUE)  # the C++ standard library
      endif()
      foreach(rule IN LISTS GRADER_${room}_MAY)
        if(written MATCHES "^${rule}")
          set(allowed TRUE)
        endif()
      endforeach()
      if(written MATCHES "\\.\\./")
        set(allowed FALSE)  # through the include path, never relative to this file
      endif()
      if(NOT allowed)
        string(REPLACE "\\." "." rule "${GRADER_${room}_MAY}")
        string(REPLACE ";" " " rule "${rule}")
        message(SEND_ERROR "tools/grader/${file}:${number}: #include ${written} breaks the include "
                           "rules (room '${room}' may include: the standard library ${rule}; "
                           "docs/layout.md)")
        math(EXPR violations "${violations} + 1")
      endif()
    endforeach()
  endforeach()
endif()

if(ROOT)
file(GLOB_RECURSE files RELATIVE ${ROOT} ${ROOT}/*.h ${ROOT}/*.cpp ${ROOT}/*.h.in)
foreach(file ${files})
  string(REGEX MATCH "^[^/]+" area "${file}")
  if(NOT DEFINED RULES_${area}_AREAS)
    message(SEND_ERROR "lib/clothref/${file}: area '${area}' has no include rules: add them to "
                       "cmake/CheckIncludes.cmake and docs/layout.md")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  file(STRINGS ${ROOT}/${file} lines ENCODING UTF-8)
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*([<\"])([^>\"]+)[>\"]")
      continue()
    endif()
    set(kind "${CMAKE_MATCH_1}")
    if(kind STREQUAL "<")
      set(close ">")
    else()
      set(close "\"")
    endif()
    set(header "${CMAKE_MATCH_2}")
    set(allowed FALSE)
    if(header MATCHES "^clothref/([^/]+)/")
      set(target "${CMAKE_MATCH_1}")
      if(target STREQUAL area)
        set(allowed TRUE)
      else()
        list(FIND RULES_${area}_AREAS "${target}" found)
        if(found GREATER -1)
          set(allowed TRUE)
        endif()
      endif()
      set(rule "area '${area}' may include: ${area} ${RULES_${area}_AREAS}")
    elseif(kind STREQUAL "\"")
      # a quoted include outside clothref/ is a file of the same folder
      set(allowed TRUE)
    elseif(NOT header MATCHES "[./]")
      set(allowed TRUE)  # the C++ standard library
    else()
      foreach(prefix IN LISTS RULES_${area}_EXTERNAL)
        string(FIND "${header}" "${prefix}" at)
        if(at EQUAL 0)
          set(allowed TRUE)
        endif()
      endforeach()
      set(rule "area '${area}' may use: the standard library ${RULES_${area}_EXTERNAL}")
    endif()
    if(NOT allowed)
      message(SEND_ERROR "lib/clothref/${file}:${number}: #include ${kind}${header}${close} breaks the "
                         "include rules (${rule}; docs/layout.md)")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()
endif()
if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include rule violation(s)")
endif()
