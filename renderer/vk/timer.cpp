#include "vk/timer.h"

namespace octrace {

void create_timer(GpuTimer& t, const VulkanContext& ctx, uint32_t count) {
  if (t.pool) vkDestroyQueryPool(ctx.device, t.pool, nullptr);
  t.pool = VK_NULL_HANDLE;
  t.ctx = &ctx;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count < 2 ? 2 : count;
  VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &t.pool));
  t.count = info.queryCount;
}

GpuTimer::~GpuTimer() {
  if (pool) vkDestroyQueryPool(ctx->device, pool, nullptr);
}

void timer_begin(const GpuTimer& t, VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, t.pool, 0, t.count);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, t.pool, 0);
}

void timer_end(const GpuTimer& t, VkCommandBuffer cmd) { timer_mark(t, cmd, 1); }

double timer_ms(const GpuTimer& t) { return timer_intervals_ms(t, 2)[0]; }

void timer_mark(const GpuTimer& t, VkCommandBuffer cmd, uint32_t i) {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t.pool, i);
}

std::vector<double> timer_intervals_ms(const GpuTimer& t, uint32_t n) {
  std::vector<uint64_t> stamps(n, 0);
  VK_CHECK(vkGetQueryPoolResults(t.ctx->device, t.pool, 0, n, n * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  std::vector<double> ms(n > 0 ? n - 1 : 0);
  for (uint32_t i = 0; i + 1 < n; ++i)
    ms[i] = double(stamps[i + 1] - stamps[i]) * double(t.ctx->limits.timestampPeriod) * 1e-6;
  return ms;
}

}  // namespace octrace
