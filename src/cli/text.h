// Strict number parsing and exact number printing for the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/format.h"
#include "core/memory.h"

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

// --threads (already checked in [0, 1024] by its option): 0 means all cores.
int resolve_threads(int requested);
// "<who>: <message>" on stderr, only when it is a terminal (pipes and CI logs stay clean).
void progress(std::string_view who, const std::string& message);
// A warning on stderr, "WHO: warning: MESSAGE", whether or not stderr is a terminal.
void warn(std::string_view who, const std::string& message);

// The whole text must be one finite number ("inf" accepted when allow_infinity). The message of a
// bad value quotes it escaped (escape_value) and, when `range` is given, states the accepted range
// ("[0, 180] degrees" or "(0, 1]" read "in [0, 180] degrees", "in (0, 1]"; other text, e.g.
// ">= 0 rad/s", follows as is).
double parse_number(const std::string& flag, std::string_view text, bool allow_infinity = false,
                    const std::string& range = "");
// One finite number in [lo, hi] (the message states the range, with `unit` after it).
double parse_number_in(const std::string& flag, std::string_view text, double lo, double hi,
                       const std::string& unit = "");
// The range of a number flag kept as text: checked when the command line is parsed (number_in,
// so that --help states it) and read with it (parse_number_in).
struct NumberRange {
  double lo = 0.0, hi = 0.0;
  const char* unit = "";
};
inline constexpr NumberRange kDegreesRange{-720.0, 720.0, " degrees"};  // a direction angle
inline double parse_number_in(const std::string& flag, std::string_view text,
                              const NumberRange& r) {
  return parse_number_in(flag, text, r.lo, r.hi, r.unit);
}
// --max-memory: bytes, or a number with a binary suffix K, M, G or T ("512M", "1.5G"), in
// [kMinMaxMemory, kMaxMaxMemory] (core/memory.h).
double parse_memory_size(const std::string& flag, std::string_view text);
// The value of a --max-memory option: kDefaultMaxMemory when not given ("").
double max_memory_flag(const std::string& text);
// The progress bar of a render at `share` of its work (in [0, 1]) after `elapsed` seconds, as
// written to a terminal: "\r  [####    ] 42%", then "  ETA 1 min 3 s " (the time left at the
// rate so far, rounded to a second) while 0 < share < 1, or "  12 s" and a newline at 1.
std::string progress_bar_text(double share, double elapsed);
// A duration rounded to a second: "42 s", "1 min 3 s", "67 min 30 s".
std::string duration_text(double seconds);
// The progress of a render off a terminal (a log, CI): "42% after 1 min 3 s, ETA 1 min 27 s",
// or at 1 "100% after 2 min 30 s".
std::string progress_line_text(double share, double elapsed);
// The estimated total of a render once `share` of it is done (its rows in spread order, a sample
// of the work): "estimated total 4 min 10 s (from the first 2% of rows, spread over the image)".
std::string progress_estimate_text(double share, double elapsed);
// Off a terminal, a progress line every this many seconds; the estimated total is printed for
// renders estimated at least this long.
inline constexpr double kProgressLineSeconds = 10.0;
// The share of a render's rows after which it prints its estimated total (the rows in spread
// order: a sample of the image, its costly sea rows and cheap sky rows alike).
inline constexpr double kProgressEstimateShare = 0.02;
// The process's peak resident memory so far (bytes; getrusage), for the render report.
double peak_memory_bytes();
// The help text of --max-memory.
inline constexpr const char* kMaxMemoryHelp =
    "refuse to start when the estimated memory (every large buffer) is over SIZE: bytes or "
    "K, M, G, T (binary), e.g. 20G; default 8G";
// One integer in [lo, hi] written in decimal (an optional sign, digits, nothing else).
long long parse_integer_in(const std::string& flag, std::string_view text, long long lo,
                           long long hi, const std::string& note = "");

// CLI11 checks for options that CLI11 converts itself (int and double variables): run on the text
// before the conversion, so that every bad value - not a number, trailing bytes, overflow,
// non-finite, out of range - fails with "--flag: expected an integer in [lo, hi]<note>, got
// '<escaped text>'" (CLI11 prefixes the flag) instead of CLI11's "Could not convert".
CLI::Validator integer_in(long long lo, long long hi, const std::string& note = "");
CLI::Validator number_in(double lo, double hi, const std::string& unit = "");
inline CLI::Validator number_in(const NumberRange& r) {
  return number_in(r.lo, r.hi, r.unit);
}
// Comma-separated finite numbers, at least one (`range`: stated in the message of a bad one).
std::vector<double> parse_number_list(const std::string& flag, std::string_view text,
                                      const std::string& range = "");
// Three comma-separated finite numbers, not all zero, normalized to unit length.
std::array<double, 3> parse_unit_vector(const std::string& flag, std::string_view text);

}  // namespace oceanref::cli
