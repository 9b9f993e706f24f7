# Install rules: the CLI with its data (cmake/InstallData.cmake), every library area (static), the
# public headers (cmake/PublicHeaders.cmake), a CMake package (find_package(clothref) ->
# clothref::clothref and clothref::<area>, carrying the determinism options) and a pkg-config file
# (clothref.pc). Included from the top-level CMakeLists.txt.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The areas in definition order: each after the areas it links, so the reverse is a valid static
# link order for pkg-config.
get_property(clothref_areas GLOBAL PROPERTY CLOTHREF_AREA_TARGETS)

install(TARGETS clothref_determinism clothref_base ${clothref_areas} clothref
        EXPORT clothrefTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(TARGET clothref-cli)
  install(TARGETS clothref-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  include(cmake/InstallData.cmake)
endif()

# Public headers: the explicit list of cmake/PublicHeaders.cmake, and the generated build
# information. A header of lib/clothref in neither that list nor the private one stops the
# configuration, so none is installed, or left out, by accident.
include(${PROJECT_SOURCE_DIR}/cmake/PublicHeaders.cmake)
file(GLOB_RECURSE clothref_all_headers RELATIVE ${PROJECT_SOURCE_DIR}/lib/clothref
     CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/lib/clothref/*.h)
foreach(header ${clothref_all_headers})
  if(NOT header IN_LIST CLOTHREF_PUBLIC_HEADERS AND NOT header IN_LIST CLOTHREF_PRIVATE_HEADERS)
    message(FATAL_ERROR "lib/clothref/${header} is in neither CLOTHREF_PUBLIC_HEADERS nor "
                        "CLOTHREF_PRIVATE_HEADERS (cmake/PublicHeaders.cmake): add it to one")
  endif()
endforeach()
foreach(header ${CLOTHREF_PUBLIC_HEADERS})
  get_filename_component(header_dir ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/lib/clothref/${header}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/clothref/${header_dir})
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/lib/clothref/trace/build_info.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/clothref/trace)

set(clothref_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/clothref)
install(EXPORT clothrefTargets NAMESPACE clothref:: DESTINATION ${clothref_cmake_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/clothrefConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/clothrefConfig.cmake
                              INSTALL_DESTINATION ${clothref_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/clothrefConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/clothrefConfig.cmake
              ${PROJECT_BINARY_DIR}/clothrefConfigVersion.cmake
        DESTINATION ${clothref_cmake_dir})

# pkg-config: link the areas dependents first (reverse definition order).
set(clothref_pc_libs "")
list(REVERSE clothref_areas)
foreach(area ${clothref_areas})
  string(APPEND clothref_pc_libs " -l${area}")
endforeach()
file(RELATIVE_PATH clothref_pc_to_prefix /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" clothref_pc_to_prefix "${clothref_pc_to_prefix}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/clothref.pc.in ${PROJECT_BINARY_DIR}/clothref.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/clothref.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
