# Installs the library (each stage's static library and the public headers), the pcsketch CLI, a CMake package
# (find_package(pcsketch) gives pcsketch::pcsketch) and pkg-config's pcsketch.pc. tests/downstream/ builds against
# the installed tree (scripts/downstream.sh, run by CI).
include(CMakePackageConfigHelpers)

get_property(pcsketch_stages GLOBAL PROPERTY PCSKETCH_STAGES)
list(TRANSFORM pcsketch_stages PREPEND pcsketch_ OUTPUT_VARIABLE pcsketch_stage_targets)
install(TARGETS pcsketch ${pcsketch_stage_targets} EXPORT pcsketchTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS pcsketch_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/pcsketch DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(pcsketch_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/pcsketch)
install(EXPORT pcsketchTargets NAMESPACE pcsketch:: DESTINATION ${pcsketch_cmake_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/pcsketchConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/pcsketchConfig.cmake INSTALL_DESTINATION ${pcsketch_cmake_dir})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pcsketchConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pcsketchConfig.cmake ${PROJECT_BINARY_DIR}/pcsketchConfigVersion.cmake
        DESTINATION ${pcsketch_cmake_dir})

# pkg-config: the libraries in link order (pipeline first, core last), then the wrapped ones as plain linker
# arguments rather than Requires: pkg-config --cflags would put Requires' (and Requires.private's) include
# directories on the user's command line, and the libraries are static, so they are needed for any link.
set(pcsketch_pc_libs "")
foreach(stage IN LISTS pcsketch_stages)
  string(PREPEND pcsketch_pc_libs "-lpcsketch_${stage} ")
endforeach()
string(STRIP "-lpcsketch ${pcsketch_pc_libs}" pcsketch_pc_libs)
string(REPLACE ";" " " pcsketch_pc_cairo "${CAIRO_LDFLAGS};${PNG_LDFLAGS}")
# The prefix relative to the .pc file: the tree works wherever it is installed (cmake --install --prefix).
file(RELATIVE_PATH pcsketch_pc_up /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" pcsketch_pc_up "${pcsketch_pc_up}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/pcsketch.pc.in ${PROJECT_BINARY_DIR}/pcsketch.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/pcsketch.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
