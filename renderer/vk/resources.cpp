#include "vk/resources.h"

#include <algorithm>
#include <cstring>

#include "core/text.h"
#include "vk/specialize.h"
#include "vk/spirv_contraction.h"

namespace octrace {

namespace {

uint32_t find_memory_type(const VulkanContext& ctx, uint32_t type_bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

}  // namespace

namespace {

// create_buffer with its memory type: the first of the device's types with
// every flag of `want`, else of `fallback` (0: any type; UINT32_MAX: none).
void create_buffer_in(Buffer& b, const VulkanContext& ctx, VkDeviceSize size, VkMemoryPropertyFlags want,
                      VkMemoryPropertyFlags fallback, const std::string& what, bool addressable) {
  const bool host = (want & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0;
  destroy_buffer(b);
  size = std::max<VkDeviceSize>(size, 16);
  b.ctx = &ctx;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  // Indirect: the tail queue's dispatch size is written by a pass (path_tracer.cpp).
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
               VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (addressable) info.usage |= VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkResult r = vkCreateBuffer(ctx.device, &info, nullptr, &b.buffer);
  if (r != VK_SUCCESS)
    throw RuntimeError("cannot create " + what + " of " + mib_string(size) + ": " + vk_result_name(r));

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
  uint32_t type = find_memory_type(ctx, req.memoryTypeBits, want);
  if (type == UINT32_MAX && fallback != UINT32_MAX) type = find_memory_type(ctx, req.memoryTypeBits, fallback);
  if (type == UINT32_MAX) throw RuntimeError("no memory type for " + what);

  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (addressable) alloc.pNext = &flags;
  r = vkAllocateMemory(ctx.device, &alloc, nullptr, &b.memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    throw RuntimeError("out of memory allocating " + mib_string(size) + " for the " + what);
  if (r != VK_SUCCESS) throw RuntimeError("cannot allocate the " + what + ": " + vk_result_name(r));
  VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
  if (host) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
}

constexpr VkMemoryPropertyFlags kHostCoherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

}  // namespace

// Host buffers are coherent so mapped writes need no flush; device buffers
// prefer device-local memory and fall back to any memory (lavapipe has one heap).
void create_buffer(Buffer& b, const VulkanContext& ctx, VkDeviceSize size, bool host, const std::string& what,
                   bool addressable) {
  if (host) create_buffer_in(b, ctx, size, kHostCoherent, UINT32_MAX, what, addressable);
  else create_buffer_in(b, ctx, size, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, what, addressable);
}

VkDeviceAddress buffer_address(const Buffer& b) {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = b.buffer;
  return vkGetBufferDeviceAddress(b.ctx->device, &info);
}

Buffer::~Buffer() { destroy_buffer(*this); }

void destroy_buffer(Buffer& b) {
  if (!b.ctx) return;
  if (b.buffer) vkDestroyBuffer(b.ctx->device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(b.ctx->device, b.memory, nullptr);
  b.buffer = VK_NULL_HANDLE;
  b.memory = VK_NULL_HANDLE;
  b.mapped = nullptr;
  b.ctx = nullptr;
}

void upload_buffer(const VulkanContext& ctx, Buffer& dst, const void* data, size_t bytes) {
  if (bytes == 0) return;
  Buffer staging;
  create_buffer(staging, ctx, bytes, true, "staging buffer");
  std::memcpy(staging.mapped, data, bytes);
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer, dst.buffer, 1, &region);
  });
}

void download_buffer(const VulkanContext& ctx, const Buffer& src, void* data, size_t bytes) {
  download_buffers(ctx, {{&src, data, bytes}});
}

void download_buffers(const VulkanContext& ctx, std::initializer_list<Download> downloads) {
  size_t largest = 0;
  for (const Download& d : downloads) largest = std::max(largest, d.bytes);
  if (largest == 0) return;
  // One staging buffer, the size of the largest, for every copy in turn:
  // allocating host memory and touching its pages for the first time were
  // most of a read-back (optimisation log 95), and one at a time the peak
  // memory is that of one download. Host-cached where the device has it:
  // the host reads this memory, and a GPU's uncached host memory is
  // write-combined, slow to read (log 94).
  Buffer staging;
  create_buffer_in(staging, ctx, largest, kHostCoherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, kHostCoherent,
                   "readback buffer", false);
  for (const Download& d : downloads) {
    if (d.bytes == 0) continue;
    submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
      VkBufferCopy region{0, 0, d.bytes};
      vkCmdCopyBuffer(cmd, d.src->buffer, staging.buffer, 1, &region);
      VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier,
                           0, nullptr, 0, nullptr);
    });
    if (d.take) d.take(staging.mapped);
    else std::memcpy(d.data, staging.mapped, d.bytes);
  }
}

namespace {

// VK_KHR_pipeline_executable_properties: every statistic of every executable
// of the pipeline, as text ("Register Count" = "64"); the names and what they
// mean are the driver's.
std::vector<std::pair<std::string, std::string>> pipeline_statistics(const VulkanContext& ctx, VkPipeline pipeline) {
  auto get_executables = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(ctx.device, "vkGetPipelineExecutablePropertiesKHR"));
  auto get_statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(ctx.device, "vkGetPipelineExecutableStatisticsKHR"));
  std::vector<std::pair<std::string, std::string>> out;
  if (!get_executables || !get_statistics) return out;
  VkPipelineInfoKHR pipeline_info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  pipeline_info.pipeline = pipeline;
  uint32_t count = 0;
  VK_CHECK(get_executables(ctx.device, &pipeline_info, &count, nullptr));
  std::vector<VkPipelineExecutablePropertiesKHR> executables(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
  VK_CHECK(get_executables(ctx.device, &pipeline_info, &count, executables.data()));
  for (uint32_t e = 0; e < count; ++e) {
    VkPipelineExecutableInfoKHR exec{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    exec.pipeline = pipeline;
    exec.executableIndex = e;
    uint32_t n = 0;
    VK_CHECK(get_statistics(ctx.device, &exec, &n, nullptr));
    std::vector<VkPipelineExecutableStatisticKHR> stats(n, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    VK_CHECK(get_statistics(ctx.device, &exec, &n, stats.data()));
    std::string prefix = count > 1 ? std::string(executables[e].name) + ": " : "";
    for (const auto& st : stats) {
      std::string value;
      switch (st.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: value = st.value.b32 ? "true" : "false"; break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: value = std::to_string(st.value.i64); break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: value = std::to_string(st.value.u64); break;
        default: value = std::to_string(st.value.f64); break;
      }
      out.emplace_back(prefix + st.name, value);
    }
  }
  return out;
}

}  // namespace

void create_compute_pipeline(ComputePipeline& p, const VulkanContext& ctx, const uint32_t* spirv,
                             size_t spirv_bytes, uint32_t binding_count, uint32_t push_bytes,
                             const std::vector<SpecConstant>& spec, bool optimize) {
  destroy_compute_pipeline(p);
  p.ctx = &ctx;
  std::vector<VkDescriptorSetLayoutBinding> bindings(binding_count);
  for (uint32_t i = 0; i < binding_count; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = binding_count;
  set_info.pBindings = bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &set_info, nullptr, &p.set_layout));

  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &p.set_layout;
  layout_info.pushConstantRangeCount = push_bytes ? 1 : 0;
  layout_info.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &layout_info, nullptr, &p.layout));

  // No implicit fused multiply-adds: a driver could otherwise fuse the same
  // source differently in two specialisations of it, and `--effects auto`
  // would not render bit-identically to `all` (optimisation log 18: 3 of 40
  // scenes differed on the H100 without this; 0 with it, for 1-4% of time).
  const std::vector<uint32_t> exact = without_contraction({spirv, spirv_bytes / 4});
  // On software devices the constants are applied before the driver sees the
  // module (vk/specialize.h): lavapipe then translates only the code the
  // pipeline runs. The driver gets no specialisation info for such a module.
  // The optimized module is kept on disk for the next run (spirv_cache_dir);
  // the light one costs less to make than to read.
  // The performance passes only where they were measured and checked: on
  // the H200 (OCTRACE_SPECIALIZE=1) their module rendered 6 values of a
  // 48x32 image differently from the driver's own specialisation, though
  // the decorations were kept (optimisation log 36); the light passes alone
  // render it bit for bit there.
  std::vector<uint32_t> specialized;
  if (!spec.empty() && specialize_spirv_enabled(ctx.info.software))
    specialized = optimize && ctx.info.software
                      ? specialize_spirv_cached(exact.data(), exact.size() * sizeof(uint32_t), spec, spirv_cache_dir())
                      : specialize_spirv(exact.data(), exact.size() * sizeof(uint32_t), spec, false);
  const std::vector<uint32_t>& code = specialized.empty() ? exact : specialized;
  VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  module_info.codeSize = code.size() * sizeof(uint32_t);
  module_info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device, &module_info, nullptr, &module));

  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (const auto& s : spec) {
    entries.push_back({s.id, uint32_t(values.size() * 4), 4});
    values.push_back(s.value);
  }
  VkSpecializationInfo spec_info{uint32_t(entries.size()), entries.data(), values.size() * 4, values.data()};

  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = spec.empty() || !specialized.empty() ? nullptr : &spec_info;
  info.layout = p.layout;
  if (ctx.pipeline_statistics) info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  // No bounds checks on buffer loads and stores (ContextOptions::robust_buffers).
  VkPipelineRobustnessCreateInfoEXT robustness{VK_STRUCTURE_TYPE_PIPELINE_ROBUSTNESS_CREATE_INFO_EXT};
  robustness.storageBuffers = VK_PIPELINE_ROBUSTNESS_BUFFER_BEHAVIOR_DISABLED_EXT;
  robustness.uniformBuffers = VK_PIPELINE_ROBUSTNESS_BUFFER_BEHAVIOR_DISABLED_EXT;
  robustness.vertexInputs = VK_PIPELINE_ROBUSTNESS_BUFFER_BEHAVIOR_DEVICE_DEFAULT_EXT;
  robustness.images = VK_PIPELINE_ROBUSTNESS_IMAGE_BEHAVIOR_DEVICE_DEFAULT_EXT;
  if (!ctx.robust_buffers) info.pNext = &robustness;
  VkResult r = vkCreateComputePipelines(ctx.device, ctx.pipeline_cache, 1, &info, nullptr, &p.pipeline);
  vkDestroyShaderModule(ctx.device, module, nullptr);
  VK_CHECK(r);
  p.statistics.clear();
  if (ctx.pipeline_statistics) p.statistics = pipeline_statistics(ctx, p.pipeline);

  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, binding_count};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pool_info, nullptr, &p.pool));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = p.pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &p.set_layout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &alloc, &p.set));
}

void bind_buffers(ComputePipeline& p, std::initializer_list<BufferBinding> buffers) {
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  size_t i = 0;
  for (const BufferBinding& b : buffers) {
    infos[i] = {b.buffer->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = p.set;
    writes[i].dstBinding = b.binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
    ++i;
  }
  vkUpdateDescriptorSets(p.ctx->device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

ComputePipeline::~ComputePipeline() { destroy_compute_pipeline(*this); }

void destroy_compute_pipeline(ComputePipeline& p) {
  if (!p.ctx) return;
  VkDevice d = p.ctx->device;
  if (p.pool) vkDestroyDescriptorPool(d, p.pool, nullptr);
  if (p.pipeline) vkDestroyPipeline(d, p.pipeline, nullptr);
  if (p.layout) vkDestroyPipelineLayout(d, p.layout, nullptr);
  if (p.set_layout) vkDestroyDescriptorSetLayout(d, p.set_layout, nullptr);
  p.pool = VK_NULL_HANDLE;
  p.pipeline = VK_NULL_HANDLE;
  p.layout = VK_NULL_HANDLE;
  p.set_layout = VK_NULL_HANDLE;
  p.set = VK_NULL_HANDLE;
  p.ctx = nullptr;
}

void compute_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                          VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                           VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace octrace
