// Device time of recorded work, from timestamp queries. Knows nothing of
// what is timed.
#pragma once

#include <cstdint>
#include <vector>

#include "vk/context.h"

namespace octrace {

struct GpuTimer {
  const VulkanContext* ctx = nullptr;
  VkQueryPool pool = VK_NULL_HANDLE;
  uint32_t count = 0;  // timestamps in the pool

  GpuTimer() = default;
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;
  ~GpuTimer();
};

// A pool of `count` timestamps (at least 2), replacing the one `t` had.
void create_timer(GpuTimer& t, const VulkanContext& ctx, uint32_t count = 2);
// Records the reset of every timestamp and the first (top of pipe) ...
void timer_begin(const GpuTimer& t, VkCommandBuffer cmd);
// ... and the second (bottom of pipe), after the work to time.
void timer_end(const GpuTimer& t, VkCommandBuffer cmd);
// Milliseconds between the two, once the submission has completed (waits for it).
double timer_ms(const GpuTimer& t);
// Records timestamp i (bottom of pipe: once the work recorded before it is done).
void timer_mark(const GpuTimer& t, VkCommandBuffer cmd, uint32_t i);
// Milliseconds from each of timestamps 0 .. n - 2 to the next, once the
// submission has completed (waits for it).
std::vector<double> timer_intervals_ms(const GpuTimer& t, uint32_t n);

}  // namespace octrace
