#pragma once
// What a plugin was built for: sable's version and the build settings that change
// the layout or the inline code of the types the headers share. Every source that
// includes the registration header (style_registry.h) carries this tag in the ELF
// section .sable_plugin_abi, so that `plugin load` reads it from the file before
// dlopen runs any of the plugin's registrars (core/input/command_plugin.cpp).
#include <cstddef>  // defines _GLIBCXX_USE_CXX11_ABI (libstdc++)

#include "sable_plugin_version.h"  // generated from CMakeLists.txt's project VERSION (cmake/install.cmake)

#define SABLE_STR2(x) #x
#define SABLE_STR(x) SABLE_STR2(x)
#define SABLE_VERSION_STRING \
  SABLE_STR(SABLE_VERSION_MAJOR) "." SABLE_STR(SABLE_VERSION_MINOR) "." SABLE_STR(SABLE_VERSION_PATCH)
// OpenMP changes the inline thread helpers (core/engine/threads.h).
#ifdef _OPENMP
#define SABLE_ABI_THREADS "openmp"
#else
#define SABLE_ABI_THREADS "serial"
#endif
// A minor version may change the interface (0.x), a patch version does not. The C++
// standard and libstdc++'s string ABI change the shared types' layout. (Not
// __GXX_ABI_VERSION: GCC and Clang share the Itanium ABI but number it differently.)
#define SABLE_PLUGIN_ABI                                                                           \
  "sable " SABLE_STR(SABLE_VERSION_MAJOR) "." SABLE_STR(SABLE_VERSION_MINOR) ", C++ " SABLE_STR( \
      __cplusplus) ", cxx11-abi " SABLE_STR(_GLIBCXX_USE_CXX11_ABI) ", " SABLE_ABI_THREADS
// "sable-plugin 0.9.0; sable 0.9, C++ 202002L, cxx11-abi 1, openmp"
#define SABLE_PLUGIN_TAG "sable-plugin " SABLE_VERSION_STRING "; " SABLE_PLUGIN_ABI

#if defined(__has_attribute) && __has_attribute(retain)
#define SABLE_RETAIN [[gnu::retain]]  // kept by the linker's --gc-sections too
#else
#define SABLE_RETAIN
#endif

namespace sable::plugin_abi {
namespace {
// One copy per source file, so that a plugin mixing sources built for two versions is seen.
[[gnu::used, gnu::section(".sable_plugin_abi")]] SABLE_RETAIN const char kTag[] = SABLE_PLUGIN_TAG;
}  // namespace
}  // namespace sable::plugin_abi
