# The package test (ctest label `package`): installs the build into WORK/prefix, builds the consumer
# project against it with find_package and with pkg-config, and checks that their traces equal the
# installed CLI's byte for byte and that the determinism options reached the consumer's compile
# line; then configures a parent project that adds clothref with add_subdirectory.
# Arguments: -DBUILD_DIR=<clothref build> -DSOURCE_DIR=<clothref source> -DWORK=<scratch directory>
#            -DCXX=<compiler> -DGENERATOR=<generator>
cmake_minimum_required(VERSION 3.22)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "package test: '${ARGN}' failed (${code}):\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(prefix ${WORK}/prefix)

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(installed bin/clothref include/clothref/record/record.h include/clothref/trace/build_info.h)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "package test: ${installed} was not installed")
  endif()
endforeach()
# Exactly the public headers (cmake/PublicHeaders.cmake) and the generated build_info.h: no
# *_impl.h or *_support.h.
include(${SOURCE_DIR}/cmake/PublicHeaders.cmake)
file(GLOB_RECURSE installed_headers RELATIVE ${prefix}/include/clothref ${prefix}/include/clothref/*)
set(expected_headers ${CLOTHREF_PUBLIC_HEADERS} trace/build_info.h)
list(SORT installed_headers)
list(SORT expected_headers)
if(NOT installed_headers STREQUAL expected_headers)
  set(extra ${installed_headers})
  list(REMOVE_ITEM extra ${expected_headers})
  set(missing ${expected_headers})
  list(REMOVE_ITEM missing ${installed_headers})
  message(FATAL_ERROR "package test: installed headers differ from the public list; "
                      "not public but installed: '${extra}'; public but not installed: '${missing}'")
endif()
run(${prefix}/bin/clothref --version)
if(NOT run_output MATCHES "^clothref [0-9]+\\.[0-9]+\\.[0-9]+ \\(git [^,]+, ")
  message(FATAL_ERROR "package test: unexpected --version output: ${run_output}")
endif()
run(${prefix}/bin/clothref trace --scene spring --steps 50 --stride 10 -o ${WORK}/cli.jsonl)

# find_package
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK}/consumer -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
run(${CMAKE_COMMAND} --build ${WORK}/consumer)
file(READ ${WORK}/consumer/compile_commands.json compile_commands)
foreach(flag -ffp-contract=off -fno-fast-math)
  string(FIND "${compile_commands}" "${flag}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "package test: ${flag} did not reach the consumer's compile line")
  endif()
endforeach()
run(${WORK}/consumer/consumer)
file(WRITE ${WORK}/consumer.jsonl "${run_output}")
file(READ ${WORK}/cli.jsonl cli_trace)
if(NOT run_output STREQUAL cli_trace)
  message(FATAL_ERROR "package test: the consumer's trace differs from the installed CLI's")
endif()

# pkg-config
find_program(PKG_CONFIG pkg-config REQUIRED)
file(GLOB pc_file ${prefix}/lib*/pkgconfig/clothref.pc ${prefix}/lib/*/pkgconfig/clothref.pc)
if(NOT pc_file)
  message(FATAL_ERROR "package test: clothref.pc was not installed")
endif()
list(GET pc_file 0 pc_file)
get_filename_component(pc_dir "${pc_file}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
run(${PKG_CONFIG} --static --cflags --libs clothref)
string(STRIP "${run_output}" pc_flags)
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
run(${CXX} -O2 ${SOURCE_DIR}/tests/package/consumer/consumer.cpp ${pc_flags} -o ${WORK}/pc-consumer)
run(${WORK}/pc-consumer)
if(NOT run_output STREQUAL cli_trace)
  message(FATAL_ERROR "package test: the pkg-config consumer's trace differs from the CLI's")
endif()
# Every installed header compiles against the install alone (no public header includes a
# private one), with the flags pkg-config gives.
run(${PKG_CONFIG} --cflags clothref)
string(STRIP "${run_output}" pc_cflags)
separate_arguments(pc_cflags UNIX_COMMAND "${pc_cflags}")
set(all_headers_source "")
foreach(header ${installed_headers})
  string(APPEND all_headers_source "#include \"clothref/${header}\"\n")
endforeach()
file(WRITE ${WORK}/all_headers.cpp "${all_headers_source}")
run(${CXX} -fsyntax-only ${pc_cflags} ${WORK}/all_headers.cpp)

# add_subdirectory and FetchContent from the local path (configure only: the checks are there)
foreach(fetch OFF ON)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/subproject -B ${WORK}/subproject-${fetch}
      -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCLOTHREF_SOURCE_DIR=${SOURCE_DIR}
      -DUSE_FETCHCONTENT=${fetch})
endforeach()

file(REMOVE_RECURSE ${WORK})
message(STATUS "package test: install, find_package, pkg-config, add_subdirectory and FetchContent all work")
