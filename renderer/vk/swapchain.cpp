#include "vk/swapchain.h"

#include <algorithm>

namespace octrace {

namespace {

// The first of our byte formats the surface offers in sRGB colour space.
VkSurfaceFormatKHR pick_format(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()));
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                        VK_FORMAT_R8G8B8A8_SRGB})
    for (const auto& f : formats)
      if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  throw RuntimeError("the window surface offers no 8-bit RGBA or BGRA format in sRGB colour space");
}

// Mailbox never blocks a frame on the display; FIFO is always there.
VkPresentModeKHR pick_present_mode(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data()));
  return std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end()
             ? VK_PRESENT_MODE_MAILBOX_KHR
             : VK_PRESENT_MODE_FIFO_KHR;
}

void destroy_semaphores(Swapchain& sc) {
  for (VkSemaphore s : sc.written) vkDestroySemaphore(sc.ctx->device, s, nullptr);
  sc.written.clear();
}

}  // namespace

bool create_swapchain(Swapchain& sc, const VulkanContext& ctx, VkSurfaceKHR surface, VkExtent2D wanted) {
  VkBool32 supported = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical, ctx.queue_family, surface, &supported));
  if (!supported) throw RuntimeError("the device's compute queue cannot present to this window");

  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physical, surface, &caps));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {  // the surface size follows the swapchain's
    extent.width = std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  VkSwapchainKHR old = sc.swapchain;
  if (sc.ctx) destroy_semaphores(sc);
  sc.ctx = &ctx;
  sc.surface = surface;
  sc.images.clear();
  if (extent.width == 0 || extent.height == 0) {
    destroy_swapchain(sc);
    return false;
  }
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw RuntimeError("the window surface does not accept transfer writes to its images");

  VkSurfaceFormatKHR format = pick_format(ctx.physical, surface);
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface;
  info.minImageCount = caps.minImageCount + 1;
  if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (auto alpha : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                     VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
    if (caps.supportedCompositeAlpha & alpha) {
      info.compositeAlpha = alpha;
      break;
    }
  info.presentMode = pick_present_mode(ctx.physical, surface);
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  VkResult r = vkCreateSwapchainKHR(ctx.device, &info, nullptr, &sc.swapchain);
  if (old) vkDestroySwapchainKHR(ctx.device, old, nullptr);
  if (r != VK_SUCCESS) {
    sc.swapchain = VK_NULL_HANDLE;
    throw_vk_error(r, "vkCreateSwapchainKHR");
  }
  sc.bgra = format.format == VK_FORMAT_B8G8R8A8_UNORM || format.format == VK_FORMAT_B8G8R8A8_SRGB;
  sc.extent = extent;

  uint32_t count = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, sc.swapchain, &count, nullptr));
  sc.images.resize(count);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, sc.swapchain, &count, sc.images.data()));
  for (uint32_t i = 0; i < count; ++i) {
    VkSemaphoreCreateInfo sem_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    sc.written.push_back(VK_NULL_HANDLE);
    VK_CHECK(vkCreateSemaphore(ctx.device, &sem_info, nullptr, &sc.written.back()));
  }
  return true;
}

void destroy_swapchain(Swapchain& sc) {
  if (!sc.ctx) return;
  destroy_semaphores(sc);
  if (sc.swapchain) vkDestroySwapchainKHR(sc.ctx->device, sc.swapchain, nullptr);
  sc.swapchain = VK_NULL_HANDLE;
  sc.images.clear();
  sc.extent = {};
}

Swapchain::~Swapchain() { destroy_swapchain(*this); }

bool acquire_image(const Swapchain& sc, VkSemaphore acquired, uint32_t* index) {
  VkResult r = vkAcquireNextImageKHR(sc.ctx->device, sc.swapchain, UINT64_MAX, acquired, VK_NULL_HANDLE, index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) VK_CHECK(r);  // suboptimal still signals: present, then recreate
  return true;
}

bool present_image(const Swapchain& sc, uint32_t index) {
  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &sc.written[index];
  info.swapchainCount = 1;
  info.pSwapchains = &sc.swapchain;
  info.pImageIndices = &index;
  VkResult r = vkQueuePresentKHR(sc.ctx->queue, &info);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  VK_CHECK(r);
  return true;
}

void record_copy_to_image(VkCommandBuffer cmd, VkBuffer pixels, VkImage image, VkExtent2D extent) {
  // The image's old contents are not needed. Its transition waits at the
  // transfer stage, the stage the submission waits on the acquire semaphore.
  VkImageMemoryBarrier to_dst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_dst.srcAccessMask = 0;
  to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_dst.srcQueueFamilyIndex = to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.image = image;
  to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_dst);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyBufferToImage(cmd, pixels, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  VkImageMemoryBarrier to_present = to_dst;
  to_present.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_present.dstAccessMask = 0;
  to_present.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr,
                       0, nullptr, 1, &to_present);
}

void submit_image_write(const Swapchain& sc, VkCommandBuffer cmd, VkSemaphore acquired, uint32_t index,
                        VkFence fence) {
  VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &acquired;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &sc.written[index];
  VK_CHECK(vkQueueSubmit(sc.ctx->queue, 1, &submit, fence));
}

}  // namespace octrace
