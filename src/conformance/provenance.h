// What built this program: the version, the commit of the source tree at build time, the
// compiler, flags and math library (`oceanref --version`, and the provenance attributes of every
// EXR file oceanref writes).
#pragma once

#include <string>

namespace oceanref {

// "oceanref 0.1.0": the `oceanref.version` attribute of the EXR files.
std::string oceanref_version();
// The abbreviated commit (`git rev-parse --short HEAD`) at build time, with "-dirty" when
// tracked files differed from it; "unknown" outside a git tree.
std::string oceanref_commit();
// The whole `oceanref --version` text.
std::string version_text();

}  // namespace oceanref
