#include "vk/timer.h"

namespace octrace {

void create_timer(GpuTimer& t, const VulkanContext& ctx) {
  t.ctx = &ctx;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2;
  VK_CHECK(vkCreateQueryPool(ctx.device, &info, nullptr, &t.pool));
}

GpuTimer::~GpuTimer() {
  if (pool) vkDestroyQueryPool(ctx->device, pool, nullptr);
}

void timer_begin(const GpuTimer& t, VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, t.pool, 0, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, t.pool, 0);
}

void timer_end(const GpuTimer& t, VkCommandBuffer cmd) {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t.pool, 1);
}

double timer_ms(const GpuTimer& t) {
  uint64_t stamps[2] = {0, 0};
  VK_CHECK(vkGetQueryPoolResults(t.ctx->device, t.pool, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return double(stamps[1] - stamps[0]) * double(t.ctx->limits.timestampPeriod) * 1e-6;
}

}  // namespace octrace
