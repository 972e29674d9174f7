// Buffers and compute pipelines over raw Vulkan: plain structs and free
// functions. Knows nothing of scenes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "vk/context.h"

namespace octrace {

// A storage buffer. Device-local, or host-visible when `host` (staging,
// readback). Frees itself, so an exception half-way through set-up leaks nothing.
struct Buffer {
  const VulkanContext* ctx = nullptr;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers only

  Buffer() = default;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer();
};

// `what` names the buffer in error messages ("accumulation buffer").
// Zero-sized requests get a 16-byte buffer so an empty scene still binds.
// `addressable`: a shader may read it through its device address
// (buffer_address; needs ctx.buffer_device_address).
void create_buffer(Buffer& b, const VulkanContext& ctx, VkDeviceSize size, bool host, const std::string& what,
                   bool addressable = false);
VkDeviceAddress buffer_address(const Buffer& b);
void destroy_buffer(Buffer& b);

// Copies host data into a device buffer through a staging buffer, and back.
void upload_buffer(const VulkanContext& ctx, Buffer& dst, const void* data, size_t bytes);
void download_buffer(const VulkanContext& ctx, const Buffer& src, void* data, size_t bytes);
// Several buffers back in one call, one after another through one staging
// buffer the size of the largest (renderer/vk/resources.cpp says why). Each
// is copied to `data`, or, where `take` is set (and `data` null), handed to
// it in the staging memory, valid during the call: a caller that only
// reduces what it reads needs no array of its own (optimisation log 97).
struct Download {
  const Buffer* src;
  void* data;
  size_t bytes;
  std::function<void(const void* mapped)> take = {};
};
void download_buffers(const VulkanContext& ctx, std::initializer_list<Download> downloads);

struct SpecConstant {
  uint32_t id;
  uint32_t value;
};

// A compute pipeline whose set 0 has `binding_count` storage buffers at
// bindings 0..n-1, with `push_bytes` of push constants.
struct ComputePipeline {
  const VulkanContext* ctx = nullptr;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  // What the driver reports of the compiled pipeline (name, value), e.g.
  // register counts and spills; empty unless ctx.pipeline_statistics.
  std::vector<std::pair<std::string, std::string>> statistics;

  ComputePipeline() = default;
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;
  ~ComputePipeline();
};

// (Re)creates `p` (what it held before is destroyed first). `optimize`: where
// the constants are applied ahead of the driver (vk/specialize.h), also run
// the optimizer's performance passes (cached on disk), on software devices
// only; false for a pipeline whose loops may reach llvmpipe's iteration
// limit (specialize_spirv).
void create_compute_pipeline(ComputePipeline& p, const VulkanContext& ctx, const uint32_t* spirv,
                             size_t spirv_bytes, uint32_t binding_count, uint32_t push_bytes,
                             const std::vector<SpecConstant>& spec = {}, bool optimize = true);
void destroy_compute_pipeline(ComputePipeline& p);

// Binds each buffer at its binding number (the BINDING_* constants of
// shaders/shared/shared.h name them).
struct BufferBinding {
  uint32_t binding;
  const Buffer* buffer;
};
void bind_buffers(ComputePipeline& p, std::initializer_list<BufferBinding> buffers);

// Full-pipeline compute->compute/transfer/indirect barrier on all memory:
// passes are read-modify-write on the accumulation buffers, and a pass may
// write the next one's indirect dispatch size.
void compute_barrier(VkCommandBuffer cmd);

}  // namespace octrace
