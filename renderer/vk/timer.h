// Device time of recorded work, from two timestamp queries. Knows nothing of
// what is timed.
#pragma once

#include "vk/context.h"

namespace octrace {

struct GpuTimer {
  const VulkanContext* ctx = nullptr;
  VkQueryPool pool = VK_NULL_HANDLE;

  GpuTimer() = default;
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;
  ~GpuTimer();
};

void create_timer(GpuTimer& t, const VulkanContext& ctx);
// Records the reset and the first timestamp (top of pipe) ...
void timer_begin(const GpuTimer& t, VkCommandBuffer cmd);
// ... and the second (bottom of pipe), after the work to time.
void timer_end(const GpuTimer& t, VkCommandBuffer cmd);
// Milliseconds between the two, once the submission has completed (waits for it).
double timer_ms(const GpuTimer& t);

}  // namespace octrace
