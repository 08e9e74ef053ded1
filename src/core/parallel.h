// The deterministic parallel loop of every stage: independent outputs only (DESIGN.md,
// determinism contract), so which thread computes an index never changes its result.
#pragma once

#include <atomic>
#include <thread>
#include <vector>

namespace oceanref {

// Runs body(i) for i in [0, count) on up to `threads` threads, each taking the next index.
template <class Body>
void parallel_for(int count, int threads, const Body& body) {
  if (threads <= 1 || count <= 1) {
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  // Indices are handed out one at a time (the cost of rows varies: sky rows are cheap, sea rows
  // with reference lighting are not); which thread runs an index never changes its result.
  const int used = threads < count ? threads : count;
  std::atomic<int> next{0};
  std::vector<std::jthread> workers;
  for (int t = 0; t < used; ++t) {
    workers.emplace_back([&body, &next, count] {
      for (int i = next++; i < count; i = next++) body(i);
    });
  }
}

}  // namespace oceanref
