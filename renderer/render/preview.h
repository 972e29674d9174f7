// The preview window's frames, on the device: passes into the tracer's
// accumulation, a resolve pass (resolve.comp: the mean as 8-bit sRGB) into a
// pixel buffer, a copy of that into the swapchain image, and the present. The
// image never leaves the device. Knows no windowing library: the caller makes
// the surface (e.g. glfwCreateWindowSurface) and hands it over.
#pragma once

#include <cstdint>

#include "io/image.h"
#include "render/path_tracer.h"
#include "vk/resources.h"
#include "vk/swapchain.h"
#include "vk/timer.h"

namespace octrace {

struct Preview {
  const VulkanContext* ctx = nullptr;
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // owned: destroyed with the preview
  Swapchain swapchain;
  ComputePipeline resolve;
  bool resolve_bgra = false;  // the byte order the resolve pipeline writes
  Buffer pixels;              // width * height packed 8-bit pixels in the swapchain's byte order
  uint32_t width = 0, height = 0;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkSemaphore acquired = VK_NULL_HANDLE;
  GpuTimer timer;
  uint32_t passes_in_flight = 0;

  Preview() = default;
  Preview(const Preview&) = delete;
  Preview& operator=(const Preview&) = delete;
  ~Preview();
};

// Takes `surface` (made on ctx.instance) and creates the per-frame objects.
void create_preview(Preview& p, const VulkanContext& ctx, VkSurfaceKHR surface);
// (Re)creates the swapchain at `extent` (the device must be idle). Returns
// false, with nothing to show, while the extent is zero (a minimised window).
bool resize_preview(Preview& p, VkExtent2D extent);
// Resolves from this tracer's accumulation from now on: after the tracer is
// made or resized (the device must be idle).
void attach_tracer(Preview& p, const PathTracer& tracer);

enum class FrameStatus {
  Skipped,         // the swapchain is out of date: nothing was submitted; recreate it
  Submitted,       // wait_frame, then the next frame
  SubmittedStale,  // as Submitted, and the swapchain should be recreated after it
};
// Records and submits one frame: `passes` passes from sample `first_sample`
// (none: only show the accumulation again), the resolve, the copy, the present.
FrameStatus submit_frame(Preview& p, const PathTracer& tracer, const PassSettings& pass, uint32_t first_sample,
                         uint32_t passes);
// Waits up to `timeout_ns` for the submitted frame; true once it is done.
bool wait_frame(Preview& p, uint64_t timeout_ns);
// Device time of the last frame's passes (0 when it ran none).
double frame_pass_ms(const Preview& p);
// The pixels the window shows, decoded back to linear, so that write_image
// encodes them to the same bytes again.
Image read_preview_pixels(const Preview& p);

}  // namespace octrace
