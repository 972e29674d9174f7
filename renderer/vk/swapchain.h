// Presentation over raw Vulkan: the swapchain of a window's surface. Knows
// nothing of scenes, and nothing of the windowing library (the caller creates
// the surface, e.g. with glfwCreateWindowSurface).
#pragma once

#include <cstdint>
#include <vector>

#include "vk/context.h"

namespace octrace {

// The swapchain images are written by a transfer (a copy from a buffer of
// 8-bit sRGB-encoded pixels), never rendered to, so the format is one of the
// four 8-bit RGBA/BGRA formats (UNORM or SRGB: a copy moves bytes, and both
// are shown as sRGB by the presentation engine in SRGB_NONLINEAR colour space).
struct Swapchain {
  const VulkanContext* ctx = nullptr;
  VkSurfaceKHR surface = VK_NULL_HANDLE;  // not owned
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  bool bgra = false;  // bytes in memory order B, G, R, A
  VkExtent2D extent{};
  std::vector<VkImage> images;
  // Per image: signalled by the submission that wrote it, waited on by its
  // present. One per image, not per frame, because a present may still hold
  // its semaphore when the next frame is submitted.
  std::vector<VkSemaphore> written;

  Swapchain() = default;
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;
  ~Swapchain();
};

// (Re)creates the swapchain of `surface`; `wanted` is used where the surface
// lets the application pick the extent (else the surface's own extent is).
// The device must be idle. Returns false, with no swapchain, while the extent
// is zero (a minimised window). Throws RuntimeError when the queue family
// cannot present to the surface or no usable format exists.
bool create_swapchain(Swapchain& sc, const VulkanContext& ctx, VkSurfaceKHR surface, VkExtent2D wanted);
void destroy_swapchain(Swapchain& sc);

// Acquires the next image, signalling `acquired`. Returns false when the
// swapchain is out of date (then nothing is signalled: recreate and retry).
bool acquire_image(const Swapchain& sc, VkSemaphore acquired, uint32_t* index);
// Records the copy of `pixels` (packed 8-bit, the swapchain's byte order)
// into a swapchain image, with its layout transitions for the present.
void record_copy_to_image(VkCommandBuffer cmd, VkBuffer pixels, VkImage image, VkExtent2D extent);
// Submits `cmd`, which writes image `index`, after `acquired` and signalling
// the image's `written` semaphore (and `fence`).
void submit_image_write(const Swapchain& sc, VkCommandBuffer cmd, VkSemaphore acquired, uint32_t index,
                        VkFence fence);
// Presents image `index` after its `written` semaphore. Returns false when the
// swapchain is out of date or suboptimal and should be recreated.
bool present_image(const Swapchain& sc, uint32_t index);

}  // namespace octrace
