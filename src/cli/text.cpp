#include "cli/text.h"

#include <sys/resource.h>

#include "core/direction.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace oceanref::cli {

namespace {
std::string range_text(double lo, double hi, const std::string& unit) {
  return "[" + shortest_number(lo) + ", " + shortest_number(hi) + "]" + unit;
}
std::string quote_value(std::string_view text) {
  return "'" + escape_value(text) + "'";
}
}  // namespace

double parse_number(const std::string& flag, std::string_view text, bool allow_infinity,
                    const std::string& range) {
  const std::string s(text);
  if (allow_infinity && (s == "inf" || s == "infinity")) return HUGE_VAL;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  // The whole text (a NUL byte inside ends strtod early and is caught here), no leading space.
  const bool whole = !s.empty() && end == s.c_str() + s.size() &&
                     !std::isspace(static_cast<unsigned char>(s.front()));
  if (!whole || !std::isfinite(v) || errno == ERANGE) {
    throw UsageError(
        flag,
        "expected a finite number" + std::string(allow_infinity ? " or inf" : "") +
            (range.empty() ? "" : (range[0] == '[' || range[0] == '(' ? " in " : " ") + range) +
            ", got " + quote_value(s));
  }
  return v;
}

double parse_number_in(const std::string& flag, std::string_view text, double lo, double hi,
                       const std::string& unit) {
  const std::string range = range_text(lo, hi, unit);
  const double v = parse_number(flag, text, false, range);
  if (v < lo || v > hi)
    throw UsageError(flag, "must be in " + range + ", got " + quote_value(text));
  return v;
}

std::string duration_text(double seconds) {
  const long s = std::lround(seconds);
  return (s >= 60 ? std::to_string(s / 60) + " min " : std::string()) + std::to_string(s % 60) +
         " s";
}

std::string progress_line_text(double share, double elapsed) {
  std::string text =
      std::to_string(static_cast<int>(share * 100.0)) + "% after " + duration_text(elapsed);
  if (share > 0.0 && share < 1.0) text += ", ETA " + duration_text(elapsed * (1.0 - share) / share);
  return text;
}

std::string progress_estimate_text(double share, double elapsed) {
  return "estimated total " + duration_text(elapsed / share) + " (from the first " +
         std::to_string(std::lround(share * 100.0)) + "% of rows, spread over the image)";
}

std::string progress_bar_text(double share, double elapsed) {
  const int width = 40;
  const int filled = static_cast<int>(share * width);
  std::string eta;
  if (share > 0.0 && share < 1.0) {
    eta = "  ETA " + duration_text(elapsed * (1.0 - share) / share) + " ";
  } else if (share >= 1.0) {
    eta = "  " + std::to_string(std::lround(elapsed)) + " s\n";
  }
  return "\r  [" + std::string(static_cast<std::size_t>(filled), '#') +
         std::string(static_cast<std::size_t>(width - filled), ' ') + "] " +
         std::to_string(static_cast<int>(share * 100.0)) + "%" + eta;
}

double peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux: kibibytes
}

double max_memory_flag(const std::string& text) {
  return text.empty() ? kDefaultMaxMemory : parse_memory_size("--max-memory", text);
}

double parse_memory_size(const std::string& flag, std::string_view text) {
  std::string number(text);
  double unit = 1.0;
  if (!number.empty()) {
    const std::string suffixes = "KMGT";
    const std::size_t power = suffixes.find(number.back());
    if (power != std::string::npos) {
      number.pop_back();
      for (std::size_t i = 0; i <= power; ++i) unit *= 1024.0;
    }
  }
  const std::string range = "[16M, 1048576G] (bytes, or with a binary suffix K, M, G, T)";
  const double v = parse_number(flag, number, false, range) * unit;
  if (v < kMinMaxMemory || v > kMaxMaxMemory) {
    throw UsageError(flag, "must be in " + range + ", got " + quote_value(text));
  }
  return v;
}

long long parse_integer_in(const std::string& flag, std::string_view text, long long lo,
                           long long hi, const std::string& note) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]" + note;
  const std::string s(text);
  const std::size_t digits = !s.empty() && (s[0] == '-' || s[0] == '+') ? 1 : 0;
  const bool decimal =
      s.size() > digits && s.find_first_not_of("0123456789", digits) == std::string::npos;
  if (!decimal) {
    throw UsageError(flag, "expected an integer in " + range + ", got " + quote_value(text));
  }
  errno = 0;
  const long long v = std::strtoll(s.c_str(), nullptr, 10);
  if (errno == ERANGE || v < lo || v > hi) {
    throw UsageError(flag, "must be in " + range + ", got " + quote_value(text));
  }
  return v;
}

CLI::Validator integer_in(long long lo, long long hi, const std::string& note) {
  return CLI::Validator(
      [lo, hi, note](std::string& text) -> std::string {
        try {
          (void)parse_integer_in("", text, lo, hi, note);
        } catch (const UsageError& e) {
          return std::string(e.what()).substr(2);  // without the empty flag's ": "
        }
        return "";
      },
      "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", "integer_in");
}

CLI::Validator number_in(double lo, double hi, const std::string& unit) {
  return CLI::Validator(
      [lo, hi, unit](std::string& text) -> std::string {
        try {
          (void)parse_number_in("", text, lo, hi, unit);
        } catch (const UsageError& e) {
          return std::string(e.what()).substr(2);
        }
        return "";
      },
      "NUMBER in " + range_text(lo, hi, unit), "number_in");
}

std::vector<double> parse_number_list(const std::string& flag, std::string_view text,
                                      const std::string& range) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    values.push_back(parse_number(flag, text.substr(start, comma - start), false, range));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return values;
}

std::array<double, 3> parse_unit_vector(const std::string& flag, std::string_view text) {
  const std::vector<double> v = parse_number_list(flag, text);
  if (v.size() != 3) throw UsageError(flag, "expected x,y,z, got " + quote_value(text));
  const std::optional<std::array<double, 3>> d = unit_direction({v[0], v[1], v[2]});
  if (!d) throw UsageError(flag, "the vector must not be zero");
  return *d;
}

int resolve_threads(int requested) {
  return requested > 0 ? requested
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void progress(std::string_view who, const std::string& message) {
  if (isatty(STDERR_FILENO)) std::cerr << who << ": " << message << '\n';
}

void warn(std::string_view who, const std::string& message) {
  std::cerr << who << ": warning: " << message << '\n';
}

}  // namespace oceanref::cli
