// Work on the host split over its hardware threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace octrace {

// This host's hardware threads (at least 1, where the library cannot tell).
inline uint32_t host_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

// How many ranges to split n items into for parallel_ranges: one per
// hardware thread, each of at least min_items (at least 1 range).
inline size_t parallel_range_count(size_t n, size_t min_items) {
  return std::max<size_t>(1, std::min<size_t>(host_threads(), n / std::max<size_t>(1, min_items)));
}

// How many ranges parallel_ranges makes of n items when asked for `ranges`:
// at most n, at least 1 (a caller sizing an array per range uses it).
inline size_t clamp_ranges(size_t n, size_t ranges) { return std::clamp<size_t>(ranges, 1, std::max<size_t>(1, n)); }

// Calls f(k, begin, end) for clamp_ranges(n, ranges) contiguous ranges k of
// [0, n) (their sizes differ by at most 1), each on a thread of its own (the
// caller's takes range 0), and returns when every one is done. An exception
// thrown by f is rethrown here (the first of several), after all have
// finished.
template <class F>
void parallel_ranges(size_t n, size_t ranges, F&& f) {
  ranges = clamp_ranges(n, ranges);
  const auto begin_of = [&](size_t k) { return n / ranges * k + std::min(k, n % ranges); };
  if (ranges == 1) {
    f(size_t(0), size_t(0), n);
    return;
  }
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto run = [&](size_t k) {
    try {
      f(k, begin_of(k), begin_of(k + 1));
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> helpers;
    for (size_t k = 1; k < ranges; ++k) helpers.emplace_back(run, k);
    run(0);
  }
  if (error) std::rethrow_exception(error);
}

// Calls f(state, i) for every i in [0, n), on up to one thread per hardware
// thread (the caller's among them), each taking the next i when it is done
// with its last: for items of unequal cost (images to decode, the octree's
// subtrees). Each thread makes its own `state` once (make()) and hands it to
// every call it makes: buffers a thread reuses from item to item. Returns
// when all are done; an exception thrown by make or f is rethrown here (the
// first of several) after every thread has stopped taking items.
template <class Make, class F>
void parallel_items(size_t n, Make&& make, F&& f) {
  std::atomic<size_t> next{0};
  const size_t threads = parallel_range_count(n, 1);
  parallel_ranges(threads, threads, [&](size_t, size_t, size_t) {  // one "item" per thread: its loop
    auto state = make();
    for (size_t i = next++; i < n; i = next++) f(state, i);
  });
}

// parallel_items without a thread's state: f(i).
template <class F>
void parallel_items(size_t n, F&& f) {
  parallel_items(n, [] { return 0; }, [&](int, size_t i) { f(i); });
}

}  // namespace octrace
