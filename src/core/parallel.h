// The deterministic parallel loop of every stage: independent outputs only (DESIGN.md,
// determinism contract), so which thread computes an index never changes its result.
#pragma once

#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace oceanref {

// Runs body(i) for i in [0, count) on up to `threads` threads, each taking the next index.
// If bodies throw, no further index is started, the running ones finish, and the exception of
// the smallest index that threw is rethrown on the caller — the same one a serial loop throws
// first, whatever the thread count (every smaller index was handed out before it, so ran to its
// end). A thread that cannot be started is such an error too.
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
  std::mutex failure_mutex;
  std::exception_ptr failure;
  int failed_index = count;
  const auto fail = [&](int index, std::exception_ptr e) {
    next = count;  // start no further index
    const std::lock_guard lock(failure_mutex);
    if (index < failed_index) {
      failed_index = index;
      failure = std::move(e);
    }
  };
  {
    std::vector<std::jthread> workers;
    try {
      workers.reserve(static_cast<std::size_t>(used));
      for (int t = 0; t < used; ++t) {
        workers.emplace_back([&body, &next, &fail, count] {
          for (int i = next++; i < count; i = next++) {
            try {
              body(i);
            } catch (...) {
              fail(i, std::current_exception());
            }
          }
        });
      }
    } catch (...) {
      fail(-1, std::current_exception());  // thread creation: before any index's error
    }
  }  // joins every worker
  if (failure) std::rethrow_exception(failure);
}

}  // namespace oceanref
