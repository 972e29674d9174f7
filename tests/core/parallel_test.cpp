// core/parallel.h: parallel_items calls f once per item, a thread's state is
// made once and kept for every item that thread takes, and an exception in f
// comes back to the caller.
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace octrace {
namespace {

TEST(ParallelItems, EveryItemOnce) {
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1000)}) {
    std::vector<std::atomic<int>> calls(n);
    parallel_items(n, [&](size_t i) { ++calls[i]; });
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(calls[i].load(), 1) << "item " << i << " of " << n;
  }
}

// A thread's state: made once by that thread, handed to each of its items.
struct Counter {
  std::thread::id owner = std::this_thread::get_id();
  size_t items = 0;
};

TEST(ParallelItems, StatePerThreadKeptAcrossItems) {
  constexpr size_t kItems = 1000;
  std::mutex m;
  std::vector<Counter*> made;
  std::vector<std::atomic<int>> calls(kItems);
  std::atomic<size_t> total{0};
  std::atomic<bool> foreign{false};
  parallel_items(
      kItems,
      [] { return Counter{}; },
      [&](Counter& c, size_t i) {
        if (c.items == 0) {
          std::lock_guard<std::mutex> lock(m);
          made.push_back(&c);
        }
        foreign = foreign || c.owner != std::this_thread::get_id();
        ++c.items;
        ++total;
        ++calls[i];
      });
  EXPECT_FALSE(foreign) << "a state was used by another thread than the one that made it";
  EXPECT_EQ(total.load(), kItems);
  for (size_t i = 0; i < kItems; ++i) ASSERT_EQ(calls[i].load(), 1) << "item " << i;
  // One state per thread at most, each made once: as many as threads took items.
  EXPECT_GE(made.size(), 1u);
  EXPECT_LE(made.size(), parallel_range_count(kItems, 1));
}

TEST(ParallelItems, ExceptionReachesTheCaller) {
  std::atomic<size_t> done{0};
  EXPECT_THROW(parallel_items(100,
                              [&](size_t i) {
                                if (i == 7) throw std::runtime_error("item 7");
                                ++done;
                              }),
               std::runtime_error);
  EXPECT_LE(done.load(), 99u);
}

}  // namespace
}  // namespace octrace
