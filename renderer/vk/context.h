// Vulkan instance, device selection and the logical device. Knows nothing of
// scenes or spheres.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/errors.h"

namespace octrace {

// Throws RuntimeError naming the call and the VkResult.
#define VK_CHECK(call)                                              \
  do {                                                              \
    VkResult vk_check_result_ = (call);                             \
    if (vk_check_result_ != VK_SUCCESS)                             \
      ::octrace::throw_vk_error(vk_check_result_, #call);           \
  } while (0)

[[noreturn]] void throw_vk_error(VkResult result, const char* what);
const char* vk_result_name(VkResult result);

struct DeviceInfo {
  uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
  std::string name;
  std::string type;    // "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other"
  std::string driver;  // driver name and info, e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
  std::string api_version;
  // VkPhysicalDeviceIDProperties::deviceUUID in hex (Vulkan 1.2 devices): the
  // same for every process that opens the same physical device on a host (the
  // MPI front end lets such ranks take turns, docs/multi_gpu.md).
  std::string uuid;
  bool software = false;         // a CPU implementation (lavapipe, SwiftShader)
  // Lavapipe's Mesa release as major * 100 + minor (driverID MESA_LLVMPIPE;
  // read from its driverInfo, "Mesa 25.0.7 ...", as lavapipe's driverVersion
  // is 0.0.1), e.g. 2203 for 22.3.6 (Debian 12) and 2500 for 25.0.7; 0 for
  // every other driver.
  uint32_t llvmpipe_release = 0;
  // NVIDIA's own driver (driverID NVIDIA_PROPRIETARY), whose shader compiler
  // some per-device rules are measured against (render/path_tracer.h).
  bool nvidia = false;
  bool vulkan12 = false;         // device API >= 1.2 (we need it)
  bool compute = false;          // a queue family with compute
  bool timestamps = false;       // timestamps on the compute queue
  // Queried through the Vulkan 1.1/1.2 feature structs, so only on 1.2 devices.
  bool shader_float16 = false;   // VkPhysicalDeviceVulkan12Features::shaderFloat16
  bool storage_16bit = false;    // VkPhysicalDeviceVulkan11Features::storageBuffer16BitAccess
  bool swapchain = false;        // VK_KHR_swapchain
  // VK_EXT_pipeline_robustness with its pipelineRobustness feature: buffer
  // bounds checks can be turned off per pipeline (ContextOptions::robust_buffers).
  bool pipeline_robustness = false;
  // Threads the device holds resident at once (its multiprocessors times
  // their warps or wavefronts), where the driver says (VK_NV_shader_sm_builtins,
  // VK_AMD_shader_core_properties); 0 when unknown.
  uint64_t resident_threads = 0;
  // Lanes of a compute subgroup (VkPhysicalDeviceSubgroupProperties; 0 below
  // Vulkan 1.2): a warp on NVIDIA, the vector width on llvmpipe.
  uint32_t subgroup_size = 0;
  // The stages and operations subgroups support
  // (VkPhysicalDeviceSubgroupProperties: VkShaderStageFlags and
  // VkSubgroupFeatureFlags; 0 below Vulkan 1.2). The path tracer's subgroup
  // stage needs arithmetic, ballot and shuffle in compute shaders
  // (missing_subgroup_operations; a device without them is not selected:
  // unmet_requirements).
  uint32_t subgroup_stages = 0;
  uint32_t subgroup_features = 0;
  // A CPU device's worker threads (0 on a GPU), as llvmpipe counts them:
  // LP_NUM_THREADS, else the online CPUs, at most 32. llvmpipe gives each
  // thread one contiguous block of a dispatch's workgroups, so a dispatch of
  // whole images per thread keeps them all busy to its end (PathTracer::
  // batch_granule; optimisation log 85).
  uint32_t cpu_threads = 0;
  bool presents = false;         // a compute queue family presents to the window; known only when
                                 // selecting for a window (ContextOptions::can_present)

  bool supports_fp16() const { return shader_float16 && storage_16bit; }
};

// The Mesa release a driverInfo string names ("Mesa 25.0.7-2~bpo12+1 (LLVM
// 15.0.6)": 2500) as major * 100 + minor; 0 where it names none.
uint32_t mesa_release(std::string_view driver_info);

// What a run needs of a device beyond Vulkan 1.2, a compute queue and timestamps.
struct DeviceRequirements {
  bool fp16 = false;     // shaderFloat16 + storageBuffer16BitAccess (the fp16 and fp16-all variants)
  bool present = false;  // a window: VK_KHR_swapchain and a compute queue family that presents
};

// Every requirement `d` fails, in words ("no shaderFloat16"); empty when it
// fits. Below Vulkan 1.2 the 16-bit features are unknown, so the version is
// then the only reason given for them.
std::vector<std::string> unmet_requirements(const DeviceInfo& d, const DeviceRequirements& req);

// What `d` lacks of the subgroup operations every path-tracing pipeline
// declares, in words ("shuffle", "ballot and shuffle"; "operations" where
// its subgroups have none in compute shaders), or "" where it has them all.
std::string missing_subgroup_operations(const DeviceInfo& d);

// The device that `selection` (auto | cpu | gpu | INDEX) picks: an index
// picks that device; auto, cpu and gpu the first that fits among their
// candidates, GPUs (discrete, integrated, virtual, other) before CPU devices.
// Throws SettingError "device" for a selection that names no device,
// SettingError "precision" when only the 16-bit features are missing, and
// RuntimeError otherwise; both list each candidate with every unmet requirement.
uint32_t select_device(const std::vector<DeviceInfo>& devices, const std::string& selection,
                       const DeviceRequirements& req);

struct ContextOptions {
  std::string device = "auto";  // auto | cpu | gpu | INDEX
  bool need_fp16 = false;       // enable shaderFloat16 + 16-bit storage (fails without)
  bool validation = false;      // Khronos validation + synchronization validation
  // For a window (octrace view): the instance extensions the surface needs
  // (glfwGetRequiredInstanceExtensions), and a test whether a queue family of
  // a device can present. When `can_present` is set, the device must have
  // VK_KHR_swapchain (it is enabled) and a queue family with compute that can
  // present; headless runs leave both empty.
  std::vector<const char*> instance_extensions;
  std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> can_present;
  // Ask the driver for what it compiled each pipeline into (registers,
  // spills, ...) through VK_KHR_pipeline_executable_properties, where the
  // device has it (VulkanContext::pipeline_statistics says whether it did).
  bool pipeline_statistics = false;
  // Keep the driver's default robustness for storage and uniform buffers.
  // Otherwise, where the device has VK_EXT_pipeline_robustness, every
  // pipeline is created with it disabled: the shaders index within their
  // buffers by construction, and NVIDIA's driver checks every storage-buffer
  // load against its descriptor's range unless told not to (optimisation log
  // 58: 8-12% of a GPU render). VulkanContext::robust_buffers says which.
  bool robust_buffers = false;
};

// One line for a render on a software device, so that its timings are not
// mistaken for a GPU's ("rendering on llvmpipe (...), a CPU (software) ...").
std::string software_device_note(const DeviceInfo& d);

// The validation layer is on when asked for or when OCTRACE_VALIDATION=1.
bool validation_requested_by_env();

struct VulkanContext {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  // Every pipeline is created through this cache, so a specialisation that a
  // run (a benchmark, the preview window) creates again costs a cache hit.
  VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  VkPhysicalDeviceLimits limits{};
  DeviceInfo info;
  bool fp16_enabled = false;
  bool pipeline_statistics = false;  // VK_KHR_pipeline_executable_properties enabled
  // Whether pipelines keep the driver's default robustness for storage and
  // uniform buffers (ContextOptions::robust_buffers); false: created with it
  // disabled (VK_EXT_pipeline_robustness).
  bool robust_buffers = true;
  // bufferDeviceAddress (Vulkan 1.2) enabled, where the device has it: a
  // scene larger than one storage buffer is read through addresses.
  bool buffer_device_address = false;
  bool memory_budget = false;             // VK_EXT_memory_budget enabled
  uint64_t max_allocation_bytes = 0;      // maxMemoryAllocationSize (Vulkan 1.1)

  VulkanContext() = default;
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;
  ~VulkanContext();
};

// The memory a render can have on `ctx`'s device: the largest device-local
// heap, or its budget where VK_EXT_memory_budget offers one (what is left to
// this process now). A software device's memory is the host's, so there the
// host's physical memory counts when it is larger (lavapipe 22.3 reports a
// fixed 2 GiB heap whatever the machine has). `source` says which, for
// messages. Test hook: OCTRACE_TEST_DEVICE_MEMORY_BYTES=N pretends N bytes.
struct DeviceMemory {
  uint64_t bytes = 0;
  std::string source;  // "heap 0", "heap 0 budget", "host memory", "OCTRACE_TEST_DEVICE_MEMORY_BYTES"
};
DeviceMemory device_memory(const VulkanContext& ctx);

// The largest buffer a shader may read through one descriptor (and allocate
// at once): maxStorageBufferRange and maxMemoryAllocationSize, whichever is
// smaller. Test hook: OCTRACE_TEST_MAX_BUFFER_BYTES=N lowers it to N.
uint64_t max_buffer_bytes(const VulkanContext& ctx);

// Every device the loader reports, with what octrace needs to know about it.
std::vector<DeviceInfo> list_devices();

// Picks a device per options.device (select_device) and creates it. Throws
// RuntimeError when Vulkan itself fails.
void create_context(VulkanContext& ctx, const ContextOptions& options);

// Messages the validation layer reported so far in this process (warnings and
// errors). The front end fails the run if this is not zero.
uint32_t validation_message_count();

// One-shot command buffer: record with `record`, submit, wait.
template <typename F>
void submit_and_wait(const VulkanContext& ctx, F&& record);
void submit_and_wait_raw(const VulkanContext& ctx, void (*record)(VkCommandBuffer, void*), void* user);

template <typename F>
void submit_and_wait(const VulkanContext& ctx, F&& record) {
  submit_and_wait_raw(
      ctx, [](VkCommandBuffer cmd, void* user) { (*static_cast<F*>(user))(cmd); }, &record);
}

}  // namespace octrace
