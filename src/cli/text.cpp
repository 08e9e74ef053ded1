#include "cli/text.h"

#include "core/direction.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace oceanref::cli {

double parse_number(const std::string& flag, std::string_view text, bool allow_infinity) {
  const std::string s(text);
  if (allow_infinity && (s == "inf" || s == "infinity")) return HUGE_VAL;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  const bool whole = !s.empty() && end == s.c_str() + s.size();
  if (!whole || !std::isfinite(v) || errno == ERANGE) {
    throw UsageError(flag, "expected a finite number" +
                               std::string(allow_infinity ? " or inf" : "") + ", got '" + s + "'");
  }
  return v;
}

std::vector<double> parse_number_list(const std::string& flag, std::string_view text) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    values.push_back(parse_number(flag, text.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return values;
}

std::array<double, 3> parse_unit_vector(const std::string& flag, std::string_view text) {
  const std::vector<double> v = parse_number_list(flag, text);
  if (v.size() != 3) throw UsageError(flag, "expected x,y,z, got '" + std::string(text) + "'");
  const std::optional<std::array<double, 3>> d = unit_direction({v[0], v[1], v[2]});
  if (!d) throw UsageError(flag, "the vector must not be zero");
  return *d;
}

int resolve_threads(int requested) {
  if (requested < 0 || requested > 1024) {
    throw UsageError("--threads",
                     "must be in [0, 1024] (0: all cores), got " + std::to_string(requested));
  }
  return requested > 0 ? requested
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void progress(std::string_view who, const std::string& message) {
  if (isatty(STDERR_FILENO)) std::cerr << who << ": " << message << '\n';
}

}  // namespace oceanref::cli
