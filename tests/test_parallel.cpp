// The parallel loop (core/parallel.h): every index once, and a worker's exception — an
// allocation failure included — reaches the caller as the one a serial loop would throw first.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.h"

using namespace oceanref;

TEST_CASE("parallel_for: every index exactly once, for any thread count") {
  for (const int threads : {1, 2, 3, 8}) {
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(1000, threads, [&](int i) { ++runs[static_cast<std::size_t>(i)]; });
    int wrong = 0;
    for (const auto& r : runs) wrong += r.load() == 1 ? 0 : 1;
    CAPTURE(threads);
    CHECK(wrong == 0);
  }
}

TEST_CASE("parallel_for: the smallest throwing index's exception reaches the caller") {
  // Indices 37 and 80 throw; whatever the thread count and timing, the caller sees index 37's
  // exception, as in a serial loop (repeated to give the threads many interleavings).
  for (const int threads : {1, 2, 3, 8}) {
    for (int repeat = 0; repeat < 20; ++repeat) {
      std::string caught;
      try {
        parallel_for(200, threads, [](int i) {
          if (i == 37 || i == 80) throw std::runtime_error("index " + std::to_string(i));
        });
      } catch (const std::runtime_error& e) {
        caught = e.what();
      }
      CAPTURE(threads);
      CHECK(caught == "index 37");
    }
  }
  // An allocation failure in a worker is an exception on the caller, not an abort.
  CHECK_THROWS_AS(parallel_for(64, 4,
                               [](int i) {
                                 if (i == 5) throw std::bad_alloc();
                               }),
                  std::bad_alloc);
}

TEST_CASE("parallel_for: after a failure no further index starts") {
  // Index 0 fails at once; the other worker may finish the index it is running, and take a few
  // more until the failing worker has recorded the failure (microseconds). Each other index
  // takes a millisecond, so the loop's 4000 indices would take 2 s on two threads without the
  // stop: only a failing worker kept off the CPU for a second lets 2000 of them run. (With bodies
  // of a few nanoseconds, a loaded machine ran them all before the first throw had unwound.)
  std::atomic<int> ran{0};
  CHECK_THROWS_AS(parallel_for(4000, 2,
                               [&](int i) {
                                 if (i == 0) throw std::runtime_error("first");
                                 ++ran;
                                 std::this_thread::sleep_for(std::chrono::milliseconds(1));
                               }),
                  std::runtime_error);
  CHECK(ran.load() < 2000);
}
