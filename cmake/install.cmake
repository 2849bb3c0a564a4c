# Install (cmake --install build --prefix P): P/bin/sable and sable-analyze, the headers a
# contact-model plugin includes (P/include/sable/...) and the CMake package
# P/lib/cmake/sable, whose target sable::plugin compiles a plugin as the engine is compiled.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(SABLE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/sable)

# The version a plugin is built for (core/input/plugin_abi.h); configure_file rewrites it
# only when the project VERSION changes.
configure_file(${CMAKE_SOURCE_DIR}/cmake/sable_plugin_version.h.in
               ${CMAKE_BINARY_DIR}/generated/sable_plugin_version.h @ONLY)

# What a plugin shares with the engine: its headers, C++20 (the layout of the shared
# types), the floating-point flags (the same bits on every SIMD width, see
# CMakeLists.txt) and OpenMP (the inline thread helpers, core/engine/threads.h).
add_library(sable_plugin INTERFACE)
target_include_directories(sable_plugin INTERFACE
  $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}> $<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/generated>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/sable>)
target_compile_features(sable_plugin INTERFACE cxx_std_${CMAKE_CXX_STANDARD})
target_compile_options(sable_plugin INTERFACE ${SABLE_FP_FLAGS})
if(SABLE_OPENMP)
  target_link_libraries(sable_plugin INTERFACE OpenMP::OpenMP_CXX)
endif()
set_target_properties(sable_plugin PROPERTIES EXPORT_NAME plugin)

# The headers a plugin includes: contact_models/registry.h and every header it
# includes, followed through the sources and the generated folder; OUT: paths
# relative to the include root, and DIR_<path>: the folder each lies in.
function(sable_plugin_headers out)
  set(todo contact_models/registry.h)
  set(seen)
  while(todo)
    list(POP_FRONT todo h)
    if(h IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${h})
    set(dir ${CMAKE_SOURCE_DIR})
    if(NOT EXISTS ${dir}/${h})
      set(dir ${CMAKE_BINARY_DIR}/generated)
    endif()
    set(DIR_${h} ${dir} PARENT_SCOPE)
    file(STRINGS ${dir}/${h} includes REGEX "^#include \"")
    list(TRANSFORM includes REPLACE "^#include \"([^\"]+)\".*$" "\\1")
    list(APPEND todo ${includes})
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()
sable_plugin_headers(SABLE_PLUGIN_HEADERS)
foreach(h ${SABLE_PLUGIN_HEADERS})
  get_filename_component(sub ${h} DIRECTORY)
  install(FILES ${DIR_${h}}/${h} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sable/${sub})
endforeach()

# Libraries found outside the system's folders (an HDF5 or GSL of one's own) stay found.
set_target_properties(sable sable-analyze PROPERTIES INSTALL_RPATH_USE_LINK_PATH ON)
install(TARGETS sable EXPORT sableTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS sable-analyze RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS sable_plugin EXPORT sableTargets)
install(EXPORT sableTargets NAMESPACE sable:: DESTINATION ${SABLE_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/sableConfig.cmake.in
  ${CMAKE_BINARY_DIR}/sableConfig.cmake INSTALL_DESTINATION ${SABLE_CMAKE_DIR})
# find_package(sable 0.9) accepts 0.9.x: a patch release keeps the plugin interface (plugin_abi.h).
write_basic_package_version_file(${CMAKE_BINARY_DIR}/sableConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/sableConfig.cmake ${CMAKE_BINARY_DIR}/sableConfigVersion.cmake
        DESTINATION ${SABLE_CMAKE_DIR})
