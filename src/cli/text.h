// Strict number parsing and exact number printing for the command line.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/format.h"

namespace oceanref::cli {

// A bad command-line value: `flag` is the flag as typed (e.g. "--wind-speed").
class UsageError : public std::invalid_argument {
 public:
  UsageError(std::string flag, const std::string& message)
      : std::invalid_argument(flag + ": " + message), flag_(std::move(flag)) {}
  const std::string& flag() const { return flag_; }

 private:
  std::string flag_;
};

// A check that ran and failed (compare, golden verify): the command's output is still printed,
// and the exit status is 1.
struct CheckFailed {};

// --threads: 0 means all cores; throws UsageError outside [0, 1024].
int resolve_threads(int requested);
// "<who>: <message>" on stderr, only when it is a terminal (pipes and CI logs stay clean).
void progress(std::string_view who, const std::string& message);

// The whole text must be one finite number ("inf" accepted when allow_infinity).
double parse_number(const std::string& flag, std::string_view text, bool allow_infinity = false);
// Comma-separated finite numbers, at least one.
std::vector<double> parse_number_list(const std::string& flag, std::string_view text);
// Three comma-separated finite numbers, not all zero, normalized to unit length.
std::array<double, 3> parse_unit_vector(const std::string& flag, std::string_view text);

}  // namespace oceanref::cli
