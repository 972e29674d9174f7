#include "render/preview.h"

#include "render/gpu_layout.h"
#include "resolve.h"

namespace octrace {

Preview::~Preview() {
  if (!ctx) return;
  // Errors are ignored here: after a lost device the handles are destroyed all the same.
  vkDeviceWaitIdle(ctx->device);
  if (fence) vkDestroyFence(ctx->device, fence, nullptr);
  if (acquired) vkDestroySemaphore(ctx->device, acquired, nullptr);
  if (cmd) vkFreeCommandBuffers(ctx->device, ctx->command_pool, 1, &cmd);
  destroy_swapchain(swapchain);
  if (surface) vkDestroySurfaceKHR(ctx->instance, surface, nullptr);
}

void create_preview(Preview& p, const VulkanContext& ctx, VkSurfaceKHR surface) {
  p.ctx = &ctx;
  p.surface = surface;
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx.command_pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &p.cmd));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx.device, &fence_info, nullptr, &p.fence));
  VkSemaphoreCreateInfo sem_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(ctx.device, &sem_info, nullptr, &p.acquired));
  create_timer(p.timer, ctx);
}

bool resize_preview(Preview& p, VkExtent2D extent) {
  VK_CHECK(vkDeviceWaitIdle(p.ctx->device));
  if (!create_swapchain(p.swapchain, *p.ctx, p.surface, extent)) return false;
  // The resolve writes bytes in the swapchain's order (a specialization constant).
  if (!p.resolve.pipeline || p.resolve_bgra != p.swapchain.bgra) {
    p.resolve_bgra = p.swapchain.bgra;
    create_compute_pipeline(p.resolve, *p.ctx, resolve_spv, sizeof(resolve_spv), gpu::RESOLVE_BINDING_COUNT,
                            sizeof(gpu::ResolveParams), {{gpu::RESOLVE_SPEC_SWAP_RB, p.resolve_bgra ? 1u : 0u}});
    p.width = p.height = 0;  // the tracer must be attached again
  }
  return true;
}

void attach_tracer(Preview& p, const PathTracer& tracer) {
  p.width = uint32_t(tracer.settings().width);
  p.height = uint32_t(tracer.settings().height);
  create_buffer(p.pixels, *p.ctx, uint64_t(p.width) * p.height * 4, false, "window pixel buffer");
  bind_buffers(p.resolve, {{gpu::RESOLVE_BINDING_ACCUM_SUM, &tracer.accum_sum()},
                           {gpu::RESOLVE_BINDING_ACCUM_COMP, &tracer.accum_comp()},
                           {gpu::RESOLVE_BINDING_PIXELS, &p.pixels}});
}

FrameStatus submit_frame(Preview& p, const PathTracer& tracer, const PassSettings& pass, uint32_t first_sample,
                         uint32_t passes) {
  uint32_t index = 0;
  if (!acquire_image(p.swapchain, p.acquired, &index)) return FrameStatus::Skipped;
  const gpu::ResolveParams size{p.width, p.height, 0, 0};
  VkCommandBuffer cmd = p.cmd;
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  // Earlier submissions (a restart's clear, the last frame) touched the accumulation.
  compute_barrier(cmd);
  p.passes_in_flight = passes;
  if (passes) {
    timer_begin(p.timer, cmd);
    tracer.record_passes(cmd, pass, first_sample, passes);
    timer_end(p.timer, cmd);
    compute_barrier(cmd);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.resolve.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.resolve.layout, 0, 1, &p.resolve.set, 0, nullptr);
  vkCmdPushConstants(cmd, p.resolve.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(size), &size);
  vkCmdDispatch(cmd, (p.width + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE,
                (p.height + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE, 1);
  compute_barrier(cmd);  // the resolve's writes before the copy reads them
  record_copy_to_image(cmd, p.pixels.buffer, p.swapchain.images[index], {p.width, p.height});
  VK_CHECK(vkEndCommandBuffer(cmd));
  submit_image_write(p.swapchain, cmd, p.acquired, index, p.fence);
  return present_image(p.swapchain, index) ? FrameStatus::Submitted : FrameStatus::SubmittedStale;
}

bool wait_frame(Preview& p, uint64_t timeout_ns) {
  VkResult r = vkWaitForFences(p.ctx->device, 1, &p.fence, VK_TRUE, timeout_ns);
  if (r == VK_TIMEOUT) return false;
  VK_CHECK(r);
  VK_CHECK(vkResetFences(p.ctx->device, 1, &p.fence));
  return true;
}

double frame_pass_ms(const Preview& p) { return p.passes_in_flight ? timer_ms(p.timer) : 0.0; }

Image read_preview_pixels(const Preview& p) {
  const size_t count = size_t(p.width) * size_t(p.height);
  std::vector<uint32_t> packed(count);
  download_buffer(*p.ctx, p.pixels, packed.data(), count * 4);
  Image image;
  image.width = int(p.width);
  image.height = int(p.height);
  image.rgb.resize(count * 3);
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      int shift = 8 * (p.resolve_bgra ? 2 - c : c);
      image.rgb[3 * i + c] = srgb_decode(float((packed[i] >> shift) & 0xff) / 255.0f);
    }
  return image;
}

}  // namespace octrace
