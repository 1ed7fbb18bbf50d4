// frictal — version and build identification. The version number is defined once, in the
// top-level CMakeLists.txt (project(VERSION ...)); the CLI's --version, the Python package's
// __version__, study stores and written X3P files all read it from here.
#pragma once

#include <string>

namespace frictal {

/// The release number, e.g. "0.1.0" (from project(VERSION) in CMakeLists.txt).
const char* version();
/// The git commit the library was built from (short hash, "-dirty" when the work tree had
/// uncommitted changes), or "unknown" when built outside a git checkout.
const char* git_commit();
/// The CMake build type (Release, Debug, RelWithDebInfo, ...).
const char* build_type();
/// One line for --version: "frictal 0.1.0 (commit abc1234, Release build)".
std::string version_line();

}  // namespace frictal
