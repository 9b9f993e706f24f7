# What an installed clothref needs besides its executable, so that it stands alone (no source or
# build tree): under <datadir>/clothref (found from the executable, CLOTHREF_DATA_FROM_BIN in
# tools/CMakeLists.txt) the Python package behind `clothref plot`, the golden set `clothref golden`
# checks, the grader's course side (stand-in headers, reference files, diagnoses, the driver
# libraries, the precompiled headers and reference objects built with clothref), and a man page
# per command generated from --help by help2man. Included from cmake/Install.cmake.
set(clothref_data ${CMAKE_INSTALL_DATADIR}/clothref)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/tools/python/clothref DESTINATION ${clothref_data}/python
        PATTERN __pycache__ EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/golden/ DESTINATION ${clothref_data}/golden)
set(clothref_grader_src ${PROJECT_SOURCE_DIR}/tools/grader)
install(DIRECTORY ${clothref_grader_src}/course ${clothref_grader_src}/reference
        DESTINATION ${clothref_data}/grader)
install(FILES ${clothref_grader_src}/diagnoses.json DESTINATION ${clothref_data}/grader)
install(TARGETS clothref_grader_course_2022 clothref_grader_course_2024
        ARCHIVE DESTINATION ${clothref_data}/grader/lib)
install(DIRECTORY ${PROJECT_BINARY_DIR}/grader-prebuilt/ DESTINATION ${clothref_data}/grader/prebuilt
        PATTERN stamp EXCLUDE)

# Man pages: clothref.1 and clothref-<command>.1, each from that command's --help, with the
# sections --help has not (EXAMPLES, EXIT STATUS) from cmake/man/<page>.h2m (help2man --include).
find_program(CLOTHREF_HELP2MAN help2man)
if(NOT CLOTHREF_HELP2MAN)
  message(STATUS "clothref: help2man not found, no man pages (tools/setup.sh installs it)")
  return()
endif()
# Every subcommand of `clothref --help`: the ctest man_pages (tests/docs/man_pages_test.sh) fails
# on a command without a page here, and renders each page's footer with `man -l`.
set(clothref_commands trace diff golden verify scenes bench stability sweep plot grade view
                      gradescope)
set(clothref_man_dir ${PROJECT_BINARY_DIR}/man)
set(clothref_man_pages ${clothref_man_dir}/clothref.1)
# The footer shows the source (left), the month (centre) and the title (right); help2man takes the
# source from the program's version line unless given one, and `clothref --version`'s line (git
# revision, compiler, build type, SIMD path) is too long for it: the month and the source then
# overprint. So each page is given the short "clothref[-<command>] <version>".
add_custom_command(OUTPUT ${clothref_man_dir}/clothref.1
  COMMAND ${CMAKE_COMMAND} -E make_directory ${clothref_man_dir}
  COMMAND ${CLOTHREF_HELP2MAN} --no-info --no-discard-stderr
          "--version-string=clothref ${PROJECT_VERSION}"
          "--name=reference and autograder for the cloth-and-spheres assignment"
          --include=${PROJECT_SOURCE_DIR}/cmake/man/clothref.h2m
          --output=${clothref_man_dir}/clothref.1 $<TARGET_FILE:clothref-cli>
  DEPENDS clothref-cli ${PROJECT_SOURCE_DIR}/cmake/man/clothref.h2m VERBATIM)
foreach(command ${clothref_commands})
  # help2man runs PROGRAM --help: a one-line wrapper gives it the command; the page is named
  # clothref-<command> (--version-string) and lists the command's options.
  set(wrapper ${clothref_man_dir}/clothref-${command})
  file(GENERATE OUTPUT ${wrapper}
       CONTENT "#!/bin/sh\nexec \"$<TARGET_FILE:clothref-cli>\" ${command} \"$@\"\n"
       FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
  add_custom_command(OUTPUT ${clothref_man_dir}/clothref-${command}.1
    COMMAND ${CLOTHREF_HELP2MAN} --no-info --no-discard-stderr
            "--version-string=clothref-${command} ${PROJECT_VERSION}"
            "--name=the clothref ${command} command (clothref(1))"
            --include=${PROJECT_SOURCE_DIR}/cmake/man/clothref-${command}.h2m
            --output=${clothref_man_dir}/clothref-${command}.1 ${wrapper}
    DEPENDS clothref-cli ${wrapper} ${PROJECT_SOURCE_DIR}/cmake/man/clothref-${command}.h2m VERBATIM)
  list(APPEND clothref_man_pages ${clothref_man_dir}/clothref-${command}.1)
endforeach()
add_custom_target(clothref_man_pages ALL DEPENDS ${clothref_man_pages})
install(FILES ${clothref_man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
