// Preconditions of library functions, checked in every build type.
//
// OCEANREF_EXPECTS(condition, message) states what a caller inside the library must guarantee
// (array sizes that match, N a power of two, an index in range, a positive variance, a unit
// vector where one is assumed): conditions that only wrong code, never a user's input, can
// break — input is validated at the boundary (scene parsing, the CLI's flags) with an error
// that names the key and its range. Unlike assert() it does not depend on NDEBUG: the checks
// stay in Release, so they must be cheap (a comparison or two, outside inner loops). They read
// values and change none, so they cannot change an output bit. A failed check throws
// PreconditionError (a std::logic_error: a bug) whose what() names the file, line, condition
// and message; the CLI reports it like any other error, on stderr with a nonzero exit code.
// `message` is evaluated only when the check fails, so it may build a string.
#pragma once

#include <stdexcept>
#include <string>

namespace oceanref {

class PreconditionError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
// The path from the last "src/" on (so messages do not depend on where the tree is checked out).
constexpr const char* source_relative(const char* path) {
  const char* start = path;
  for (const char* p = path; *p != '\0'; ++p) {
    if (p[0] == 's' && p[1] == 'r' && p[2] == 'c' && p[3] == '/') start = p;
  }
  return start;
}

[[noreturn, gnu::cold, gnu::noinline]] inline void precondition_failed(const char* file, int line,
                                                                       const char* condition,
                                                                       const std::string& message) {
  throw PreconditionError("internal error: precondition failed at " +
                          std::string(source_relative(file)) + ":" + std::to_string(line) + ": " +
                          condition + " (" + message + ")");
}
}  // namespace detail

}  // namespace oceanref

#define OCEANREF_EXPECTS(condition, message) \
  ((condition) ? static_cast<void>(0)        \
               : ::oceanref::detail::precondition_failed(__FILE__, __LINE__, #condition, message))
