// Memory as a checked resource (DESIGN.md, "Faults become errors"): a command estimates every
// large buffer it will allocate and refuses to start when the total is over its limit
// (`--max-memory`, default kDefaultMaxMemory); a large allocation that fails anyway names what
// it was for and how much it asked for, instead of a bare std::bad_alloc.
#pragma once

#include <algorithm>
#include <cstddef>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/format.h"

namespace oceanref {

inline constexpr double kMebibyte = 1024.0 * 1024.0;
// The memory a command may plan to allocate unless told otherwise (bytes): 8 GiB.
inline constexpr double kDefaultMaxMemory = 8192.0 * kMebibyte;
// The range `--max-memory` accepts (bytes): 16 MiB to 1 PiB.
inline constexpr double kMinMaxMemory = 16.0 * kMebibyte;
inline constexpr double kMaxMaxMemory = 1024.0 * 1024.0 * 1024.0 * kMebibyte;

// A byte count in MiB for messages: "12.5 MiB" (one decimal; "0.1 MiB" at least).
inline std::string mebibytes(double bytes) {
  // Rounded to tenths by truncation (no libm), clamped below the range of long long.
  const double scaled = std::min(bytes / kMebibyte * 10.0 + 0.5, 9.0e18);
  const double tenths = static_cast<double>(static_cast<long long>(scaled));
  return shortest_number((tenths < 1.0 && bytes > 0.0 ? 1.0 : tenths) / 10.0) + " MiB";
}

// One buffer (or a group of buffers of one kind) of an estimate.
struct MemoryItem {
  std::string what;
  double bytes = 0.0;
};

// What a command will allocate, buffer by buffer.
struct MemoryEstimate {
  std::vector<MemoryItem> items;
  double total() const {
    double sum = 0.0;
    for (const MemoryItem& i : items) sum += i.bytes;
    return sum;
  }
};

// An estimate over the limit, refused before anything large is allocated.
class MemoryLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A large allocation that failed: what it was for and how many bytes it asked for.
class OutOfMemoryError : public std::runtime_error {
 public:
  OutOfMemoryError(const std::string& what, double bytes)
      : std::runtime_error("out of memory: could not allocate " + mebibytes(bytes) + " for " +
                           what + " (free memory, or lower the resolution or sample count)") {}
};

// Throws MemoryLimitError when `estimate` is over `limit` bytes, listing the three largest items
// and how to raise the limit (`how_to_raise`, e.g. "--max-memory").
inline void require_within(const MemoryEstimate& estimate, double limit,
                           const std::string& how_to_raise) {
  const double total = estimate.total();
  if (total <= limit) return;
  std::vector<MemoryItem> largest = estimate.items;
  std::stable_sort(largest.begin(), largest.end(),
                   [](const MemoryItem& a, const MemoryItem& b) { return a.bytes > b.bytes; });
  std::string parts;
  for (std::size_t i = 0; i < largest.size() && i < 3; ++i) {
    parts += (i == 0 ? "" : ", ") + largest[i].what + " " + mebibytes(largest[i].bytes);
  }
  throw MemoryLimitError("needs an estimated " + mebibytes(total) + " of memory (largest: " +
                         parts + "), over the limit of " + mebibytes(limit) + "; raise it with " +
                         how_to_raise + " or make the job smaller");
}

// `count` values of T, each `value`; an allocation failure becomes an OutOfMemoryError naming
// `what`. For the large buffers (wave grids, sample and pixel buffers, images read).
template <class T>
std::vector<T> allocate_buffer(std::size_t count, const std::string& what, const T& value = T{}) {
  try {
    return std::vector<T>(count, value);
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError(what, static_cast<double>(count) * static_cast<double>(sizeof(T)));
  } catch (const std::length_error&) {
    throw OutOfMemoryError(what, static_cast<double>(count) * static_cast<double>(sizeof(T)));
  }
}

}  // namespace oceanref
