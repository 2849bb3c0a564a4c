#pragma once
// sable's version (CMakeLists.txt's project VERSION) and the git commit it was built
// from (`git describe --always --dirty`, "unknown" without git). Defined in a file
// generated at build time (cmake/sable_version.cmake), so a new commit recompiles one file.
#include <string>

namespace sable {

const char* version();  // "0.9.0"
const char* commit();   // "ea9ccef", "ea9ccef-dirty" or "unknown"
// "sable 0.9.0 (commit ea9ccef)": what --version prints and the banner's first line.
inline std::string version_line() { return std::string("sable ") + version() + " (commit " + commit() + ")"; }

}  // namespace sable
