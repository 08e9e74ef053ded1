#include "conformance/provenance.h"

#include <cfloat>
#include <sstream>

#include "conformance/build_commit.h"
#include "conformance/build_info.h"

namespace oceanref {

std::string oceanref_version() {
  return std::string("oceanref ") + OCEANREF_VERSION;
}

std::string oceanref_commit() {
  return OCEANREF_COMMIT;
}

std::string version_text() {
  std::ostringstream s;
  s << oceanref_version() << " (commit " << oceanref_commit() << ")\n"
    << "compiler: "
#if defined(__clang__)
    << "clang "
#else
    << "gcc "
#endif
    << __VERSION__ << ", " << OCEANREF_BUILD_TYPE << ", " << OCEANREF_ARCH << "\n"
    << "flags: " << OCEANREF_BUILD_FLAGS << "\n"
    << "math: " << OCEANREF_MATH_LIBRARY << "\n"
    << "floating point: IEEE-754 binary64, FLT_EVAL_METHOD " << FLT_EVAL_METHOD
    << ", no contraction; round-to-nearest with FTZ and DAZ off enforced while computing";
  return s.str();
}

}  // namespace oceanref
