#include "vk/context.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

namespace octrace {

uint32_t mesa_release(std::string_view info) {
  const size_t at = info.find("Mesa ");
  if (at == std::string_view::npos) return 0;
  uint32_t major = 0, minor = 0;
  size_t i = at + 5;
  const auto number = [&](uint32_t& v) {
    const size_t start = i;
    while (i < info.size() && info[i] >= '0' && info[i] <= '9' && i - start < 4) v = v * 10 + uint32_t(info[i++] - '0');
    return i > start;
  };
  if (!number(major) || i >= info.size() || info[i++] != '.' || !number(minor)) return 0;
  return major * 100 + minor;
}

namespace {

std::atomic<uint32_t> g_validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void*) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  g_validation_messages++;
  std::fprintf(stderr, "octrace: validation: %s\n", data->pMessage);
  return VK_FALSE;
}

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

bool layer_available(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

VkInstance create_instance(bool validation, VkDebugUtilsMessengerEXT* messenger,
                           std::vector<const char*> extensions = {}) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "octrace";
  app.apiVersion = VK_API_VERSION_1_2;

  const char* layer = "VK_LAYER_KHRONOS_validation";
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = debug_callback;
  // Synchronization validation is off by default in the layer; the tests need it.
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &messenger_info;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (validation) {
    if (!layer_available(layer))
      throw RuntimeError("validation requested but VK_LAYER_KHRONOS_validation is not installed "
                         "(Debian: vulkan-validationlayers)");
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    info.pNext = &features;
  }
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&info, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    throw RuntimeError(std::string("no Vulkan driver found (") + vk_result_name(r) +
                       "); install mesa-vulkan-drivers for the CPU device or a GPU driver");
  VK_CHECK(r);
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(instance, &messenger_info, nullptr, messenger));
  }
  return instance;
}

void destroy_instance(VkInstance instance, VkDebugUtilsMessengerEXT messenger) {
  if (messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger, nullptr);
  }
  if (instance) vkDestroyInstance(instance, nullptr);
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

// The queue family we run on: one with compute (a pure compute family is as
// good as a graphics one for us; the first that fits is used), and for which
// `also` holds when given (a window's: it can present).
bool find_compute_queue(VkPhysicalDevice physical, uint32_t* family, uint32_t* timestamp_bits,
                        const std::function<bool(uint32_t)>& also = {}) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && (!also || also(i))) {
      *family = i;
      *timestamp_bits = families[i].timestampValidBits;
      return true;
    }
  }
  return false;
}

bool has_device_extension(VkPhysicalDevice physical, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
  for (const auto& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// The threads llvmpipe runs a dispatch on, as Mesa 22.3 sets them: LP_NUM_THREADS
// where given (0 runs it in the submitting thread: one), else the online CPUs;
// at most LP_MAX_THREADS (32).
uint32_t llvmpipe_threads() {
  long threads = sysconf(_SC_NPROCESSORS_ONLN);
  if (const char* env = std::getenv("LP_NUM_THREADS")) threads = std::strtol(env, nullptr, 10);
  return uint32_t(std::clamp<long>(threads, 1, 32));
}

// Threads resident at once, from the vendor's properties (0: unknown).
uint64_t resident_threads(VkPhysicalDevice physical) {
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  if (has_device_extension(physical, VK_NV_SHADER_SM_BUILTINS_EXTENSION_NAME)) {
    VkPhysicalDeviceShaderSMBuiltinsPropertiesNV sm{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SM_BUILTINS_PROPERTIES_NV};
    props2.pNext = &sm;
    vkGetPhysicalDeviceProperties2(physical, &props2);
    return uint64_t(sm.shaderSMCount) * sm.shaderWarpsPerSM * 32;
  }
  if (has_device_extension(physical, VK_AMD_SHADER_CORE_PROPERTIES_EXTENSION_NAME)) {
    VkPhysicalDeviceShaderCorePropertiesAMD core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CORE_PROPERTIES_AMD};
    props2.pNext = &core;
    vkGetPhysicalDeviceProperties2(physical, &props2);
    return uint64_t(core.shaderEngineCount) * core.shaderArraysPerEngineCount * core.computeUnitsPerShaderArray *
           core.simdPerComputeUnit * core.wavefrontsPerSimd * core.wavefrontSize;
  }
  return 0;
}

// `presents` (a window's test of a queue family), when given, fills info.presents.
DeviceInfo describe(VkPhysicalDevice physical, uint32_t index, const std::function<bool(uint32_t)>& presents) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical, &props);
  DeviceInfo info;
  info.index = index;
  info.name = props.deviceName;
  info.type = device_type_name(props.deviceType);
  info.software = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  if (info.software) info.cpu_threads = llvmpipe_threads();
  info.api_version = std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
                     std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + "." +
                     std::to_string(VK_API_VERSION_PATCH(props.apiVersion));
  info.vulkan12 = props.apiVersion >= VK_API_VERSION_1_2;

  if (info.vulkan12) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    driver.pNext = &id;
    id.pNext = &subgroup;
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(physical, &props2);
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    if (driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE)
      info.llvmpipe_release = mesa_release(driver.driverInfo);
    info.nvidia = driver.driverID == VK_DRIVER_ID_NVIDIA_PROPRIETARY;
    info.subgroup_size = subgroup.subgroupSize;
    info.subgroup_stages = subgroup.supportedStages;
    info.subgroup_features = subgroup.supportedOperations;
    static const char kHex[] = "0123456789abcdef";
    for (uint8_t byte : id.deviceUUID) {
      info.uuid += kHex[byte >> 4];
      info.uuid += kHex[byte & 15];
    }

    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f11.pNext = &f12;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &f11;
    VkPhysicalDevicePipelineRobustnessFeaturesEXT robustness{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_ROBUSTNESS_FEATURES_EXT};
    const bool has_robustness = has_device_extension(physical, VK_EXT_PIPELINE_ROBUSTNESS_EXTENSION_NAME);
    if (has_robustness) f12.pNext = &robustness;
    vkGetPhysicalDeviceFeatures2(physical, &features);
    info.shader_float16 = f12.shaderFloat16;
    info.storage_16bit = f11.storageBuffer16BitAccess;
    info.pipeline_robustness = has_robustness && robustness.pipelineRobustness;
    info.resident_threads = resident_threads(physical);
  }

  uint32_t family = 0, timestamp_bits = 0;
  info.compute = find_compute_queue(physical, &family, &timestamp_bits);
  info.timestamps = timestamp_bits > 0 && props.limits.timestampPeriod > 0;
  info.swapchain = has_device_extension(physical, VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  info.presents = presents && find_compute_queue(physical, &family, &timestamp_bits, presents);
  return info;
}

int auto_rank(const DeviceInfo& d) {
  if (d.type == "discrete GPU") return 0;
  if (d.type == "integrated GPU") return 1;
  if (d.type == "virtual GPU") return 2;
  if (d.type == "CPU") return 4;
  return 3;
}

}  // namespace

const char* vk_result_name(VkResult result) {
  switch (result) {
#define OCT_CASE(x) case x: return #x;
    OCT_CASE(VK_SUCCESS)
    OCT_CASE(VK_NOT_READY)
    OCT_CASE(VK_TIMEOUT)
    OCT_CASE(VK_INCOMPLETE)
    OCT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    OCT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    OCT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    OCT_CASE(VK_ERROR_DEVICE_LOST)
    OCT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    OCT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    OCT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    OCT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    OCT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    OCT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    OCT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    OCT_CASE(VK_ERROR_FRAGMENTED_POOL)
    OCT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    OCT_CASE(VK_ERROR_SURFACE_LOST_KHR)
    OCT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    OCT_CASE(VK_SUBOPTIMAL_KHR)
#undef OCT_CASE
    default: return "VK_ERROR_UNKNOWN";
  }
}

void throw_vk_error(VkResult result, const char* what) {
  std::string where = what;
  if (auto paren = where.find('('); paren != std::string::npos) where.resize(paren);
  switch (result) {
    case VK_ERROR_DEVICE_LOST:
      throw RuntimeError("Vulkan device lost during " + where +
                         " (the driver reset the device: a pass took too long or the GPU faulted)");
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      throw RuntimeError("out of device memory in " + where + " (try a smaller image or scene)");
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      throw RuntimeError("out of host memory in " + where);
    default:
      throw RuntimeError(where + " failed: " + vk_result_name(result));
  }
}

std::string missing_subgroup_operations(const DeviceInfo& d) {
  if ((d.subgroup_stages & VK_SHADER_STAGE_COMPUTE_BIT) == 0) return "operations";
  std::vector<std::string> missing;
  for (auto [bit, name] : {std::pair{VK_SUBGROUP_FEATURE_ARITHMETIC_BIT, "arithmetic"},
                           std::pair{VK_SUBGROUP_FEATURE_BALLOT_BIT, "ballot"},
                           std::pair{VK_SUBGROUP_FEATURE_SHUFFLE_BIT, "shuffle"}})
    if ((d.subgroup_features & bit) == 0) missing.push_back(name);
  std::string words;
  for (size_t i = 0; i < missing.size(); ++i)
    words += (i == 0 ? "" : i + 1 == missing.size() ? " and " : ", ") + missing[i];
  return words;
}

std::vector<std::string> unmet_requirements(const DeviceInfo& d, const DeviceRequirements& req) {
  std::vector<std::string> unmet;
  if (!d.vulkan12) unmet.push_back("Vulkan " + d.api_version + " < 1.2");
  if (!d.compute) unmet.push_back("no compute queue");
  else if (!d.timestamps) unmet.push_back("no timestamp queries on its compute queue");
  // The path tracer's subgroup stage (every pipeline compiled from it declares it).
  if (const std::string missing = missing_subgroup_operations(d); d.vulkan12 && !missing.empty())
    unmet.push_back("no subgroup " + missing + " in compute shaders");
  if (req.fp16 && d.vulkan12 && !d.shader_float16) unmet.push_back("no shaderFloat16");
  if (req.fp16 && d.vulkan12 && !d.storage_16bit) unmet.push_back("no storageBuffer16BitAccess");
  if (req.present && !d.swapchain) unmet.push_back("no VK_KHR_swapchain");
  if (req.present && d.compute && !d.presents)
    unmet.push_back("no queue family with compute that can present to the window");
  return unmet;
}

uint32_t select_device(const std::vector<DeviceInfo>& devices, const std::string& selection,
                       const DeviceRequirements& req) {
  if (devices.empty())
    throw RuntimeError("no Vulkan device found; install mesa-vulkan-drivers for the CPU device (lavapipe)");
  std::vector<uint32_t> candidates;
  if (selection == "auto" || selection == "cpu" || selection == "gpu") {
    for (uint32_t i = 0; i < devices.size(); ++i)
      if (selection == "auto" || (selection == "cpu") == devices[i].software) candidates.push_back(i);
    std::stable_sort(candidates.begin(), candidates.end(),
                     [&](uint32_t a, uint32_t b) { return auto_rank(devices[a]) < auto_rank(devices[b]); });
    if (candidates.empty())
      throw SettingError("device", " " + selection + ": no " + (selection == "cpu" ? "CPU (software)" : "GPU") +
                                       " device found");
  } else {
    char* end = nullptr;
    unsigned long idx = std::strtoul(selection.c_str(), &end, 10);
    if (selection.empty() || *end != '\0')
      throw SettingError("device", ": expected auto, cpu, gpu or a device index, got \"" + selection + "\"");
    if (idx >= devices.size())
      throw SettingError("device", ": index " + selection + " out of range (" + std::to_string(devices.size()) +
                                       (devices.size() == 1 ? " device)" : " devices)"));
    candidates.push_back(uint32_t(idx));
  }

  // The first candidate that fits; else every candidate with every reason.
  std::string reasons;
  bool fits_without_fp16 = false;
  for (uint32_t i : candidates) {
    auto unmet = unmet_requirements(devices[i], req);
    if (unmet.empty()) return i;
    fits_without_fp16 |= unmet_requirements(devices[i], {false, req.present}).empty();
    reasons += (reasons.empty() ? "" : "; ") + std::to_string(i) + " " + devices[i].name + ": ";
    for (size_t k = 0; k < unmet.size(); ++k) reasons += (k ? ", " : "") + unmet[k];
  }
  // Only the 16-bit features missing: the choice of precision is what failed.
  if (fits_without_fp16) throw SettingError("precision", " fp16: no suitable device: " + reasons);
  throw RuntimeError("no suitable Vulkan device: " + reasons);
}

std::string software_device_note(const DeviceInfo& d) {
  return "rendering on " + d.name + ", a CPU (software) Vulkan device: its timings are not a GPU's";
}

bool validation_requested_by_env() {
  const char* v = std::getenv("OCTRACE_VALIDATION");
  return v && std::strcmp(v, "0") != 0 && *v;
}

uint32_t validation_message_count() { return g_validation_messages.load(); }

std::vector<DeviceInfo> list_devices() {
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkInstance instance = create_instance(validation_requested_by_env(), &messenger);
  std::vector<DeviceInfo> result;
  try {
    auto devices = physical_devices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe(devices[i], i, {}));
  } catch (...) {
    destroy_instance(instance, messenger);
    throw;
  }
  destroy_instance(instance, messenger);
  return result;
}

void create_context(VulkanContext& ctx, const ContextOptions& options) {
  ctx.instance = create_instance(options.validation || validation_requested_by_env(), &ctx.messenger,
                                 options.instance_extensions);
  auto devices = physical_devices(ctx.instance);

  // A window needs the swapchain extension and a compute family that presents.
  auto presents = [&](VkPhysicalDevice physical) -> std::function<bool(uint32_t)> {
    if (!options.can_present) return {};
    return [&, physical](uint32_t family) { return options.can_present(ctx.instance, physical, family); };
  };
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i, presents(devices[i])));
  uint32_t chosen = select_device(infos, options.device, {options.need_fp16, bool(options.can_present)});

  ctx.physical = devices[chosen];
  ctx.info = infos[chosen];
  uint32_t timestamp_bits = 0;
  find_compute_queue(ctx.physical, &ctx.queue_family, &timestamp_bits, presents(ctx.physical));
  vkGetPhysicalDeviceMemoryProperties(ctx.physical, &ctx.memory);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx.physical, &props);
  ctx.limits = props.limits;

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = ctx.queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  // 16-bit features are enabled only when asked for, so an fp32 run works on
  // devices without them.
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f11.pNext = &f12;
  ctx.fp16_enabled = options.need_fp16 || ctx.info.supports_fp16();
  f11.storageBuffer16BitAccess = ctx.fp16_enabled;
  f12.shaderFloat16 = ctx.fp16_enabled;
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR exec_props{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  std::vector<const char*> extensions;
  if (options.can_present) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  ctx.pipeline_statistics = options.pipeline_statistics &&
                            has_device_extension(ctx.physical, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
  if (ctx.pipeline_statistics) {
    extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    exec_props.pipelineExecutableInfo = VK_TRUE;
    f12.pNext = &exec_props;
  }
  // Buffer device addresses wherever the device has them: only the split
  // pipeline (scenes larger than one storage buffer) uses them.
  {
    VkPhysicalDeviceVulkan12Features have{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    query.pNext = &have;
    if (ctx.info.vulkan12) vkGetPhysicalDeviceFeatures2(ctx.physical, &query);
    ctx.buffer_device_address = have.bufferDeviceAddress;
    f12.bufferDeviceAddress = have.bufferDeviceAddress;
  }
  ctx.memory_budget = has_device_extension(ctx.physical, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  if (ctx.memory_budget) extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  {
    VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props2.pNext = &m3;
    vkGetPhysicalDeviceProperties2(ctx.physical, &props2);
    ctx.max_allocation_bytes = m3.maxMemoryAllocationSize;
  }
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f11;
  // Buffer robustness off per pipeline where the device lets us
  // (ContextOptions::robust_buffers).
  VkPhysicalDevicePipelineRobustnessFeaturesEXT robustness{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_ROBUSTNESS_FEATURES_EXT};
  ctx.robust_buffers = options.robust_buffers || !ctx.info.pipeline_robustness;
  if (!ctx.robust_buffers) {
    extensions.push_back(VK_EXT_PIPELINE_ROBUSTNESS_EXTENSION_NAME);
    robustness.pipelineRobustness = VK_TRUE;
    robustness.pNext = features.pNext;
    features.pNext = &robustness;
  }

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &features;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VK_CHECK(vkCreateDevice(ctx.physical, &info, nullptr, &ctx.device));
  vkGetDeviceQueue(ctx.device, ctx.queue_family, 0, &ctx.queue);

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = ctx.queue_family;
  VK_CHECK(vkCreateCommandPool(ctx.device, &pool_info, nullptr, &ctx.command_pool));
  VkPipelineCacheCreateInfo cache_info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  VK_CHECK(vkCreatePipelineCache(ctx.device, &cache_info, nullptr, &ctx.pipeline_cache));
}

namespace {

// A test hook's value (a byte count), or 0 when it is not set.
uint64_t test_bytes(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::strtoull(v, nullptr, 10) : 0;
}

}  // namespace

DeviceMemory device_memory(const VulkanContext& ctx) {
  if (const uint64_t fake = test_bytes("OCTRACE_TEST_DEVICE_MEMORY_BYTES")) return {fake, "OCTRACE_TEST_DEVICE_MEMORY_BYTES"};
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
  if (ctx.memory_budget) props.pNext = &budget;
  vkGetPhysicalDeviceMemoryProperties2(ctx.physical, &props);
  const VkPhysicalDeviceMemoryProperties& m = props.memoryProperties;
  DeviceMemory best;
  for (uint32_t h = 0; h < m.memoryHeapCount; ++h) {
    if (!(m.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
    const uint64_t bytes = ctx.memory_budget ? budget.heapBudget[h] : m.memoryHeaps[h].size;
    if (bytes > best.bytes) best = {bytes, "heap " + std::to_string(h) + (ctx.memory_budget ? " budget" : "")};
  }
  if (ctx.info.software) {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    const uint64_t host = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
    if (host > best.bytes) best = {host, "host memory"};
  }
  return best;
}

uint64_t max_buffer_bytes(const VulkanContext& ctx) {
  if (const uint64_t fake = test_bytes("OCTRACE_TEST_MAX_BUFFER_BYTES")) return fake;
  uint64_t limit = ctx.limits.maxStorageBufferRange;
  if (ctx.max_allocation_bytes) limit = std::min(limit, ctx.max_allocation_bytes);
  return limit;
}

namespace {

// OCTRACE_DUMP_PIPELINE_CACHE=FILE: the pipeline cache's data
// (vkGetPipelineCacheData) written to FILE when the context ends, i.e. every
// pipeline the run built, as the driver compiled it; a diagnostic for
// tools/nvidia_sass.py, which reads the machine code out of NVIDIA's.
void dump_pipeline_cache(VkDevice device, VkPipelineCache cache) {
  const char* path = std::getenv("OCTRACE_DUMP_PIPELINE_CACHE");
  if (!path || !*path) return;
  size_t n = 0;
  if (vkGetPipelineCacheData(device, cache, &n, nullptr) != VK_SUCCESS) return;
  std::vector<char> data(n);
  if (vkGetPipelineCacheData(device, cache, &n, data.data()) != VK_SUCCESS) return;
  if (FILE* f = std::fopen(path, "wb")) {
    std::fwrite(data.data(), 1, n, f);
    std::fclose(f);
  }
}

}  // namespace

VulkanContext::~VulkanContext() {
  if (device) {
    vkDeviceWaitIdle(device);
    if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
    if (pipeline_cache) {
      dump_pipeline_cache(device, pipeline_cache);
      vkDestroyPipelineCache(device, pipeline_cache, nullptr);
    }
    vkDestroyDevice(device, nullptr);
  }
  destroy_instance(instance, messenger);
}

void submit_and_wait_raw(const VulkanContext& ctx, void (*record)(VkCommandBuffer, void*), void* user) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx.command_pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd));
  VkFence fence = VK_NULL_HANDLE;
  try {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd, user);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &fence_info, nullptr, &fence));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(ctx.queue, 1, &submit, fence));
    VK_CHECK(vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, UINT64_MAX));
  } catch (...) {
    if (fence) vkDestroyFence(ctx.device, fence, nullptr);
    vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &cmd);
    throw;
  }
  vkDestroyFence(ctx.device, fence, nullptr);
  vkFreeCommandBuffers(ctx.device, ctx.command_pool, 1, &cmd);
}

}  // namespace octrace
