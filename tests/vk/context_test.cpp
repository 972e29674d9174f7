// Device selection explains itself: every candidate is listed with every
// requirement it fails, and the messages name the library's settings, never a
// CLI flag. Runs on fabricated devices, so no GPU (or driver) is needed.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vk/context.h"

namespace {

using octrace::DeviceInfo;
using octrace::DeviceRequirements;
using octrace::mesa_release;
using octrace::RuntimeError;
using octrace::select_device;
using octrace::SettingError;
using octrace::unmet_requirements;
using Reasons = std::vector<std::string>;

// A device with everything octrace uses, window included.
DeviceInfo capable(uint32_t index, const std::string& name, const std::string& type) {
  DeviceInfo d;
  d.index = index;
  d.name = name;
  d.type = type;
  d.api_version = "1.3.230";
  d.software = type == "CPU";
  d.vulkan12 = d.compute = d.timestamps = d.shader_float16 = d.storage_16bit = d.swapchain = d.presents = true;
  d.subgroup_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  d.subgroup_features = VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT |
                        VK_SUBGROUP_FEATURE_SHUFFLE_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT;
  return d;
}

DeviceInfo lavapipe(uint32_t index) { return capable(index, "llvmpipe (LLVM 15.0.6, 256 bits)", "CPU"); }
DeviceInfo discrete(uint32_t index) { return capable(index, "NVIDIA GeForce RTX 4090", "discrete GPU"); }

DeviceInfo without_fp16(DeviceInfo d) {
  d.shader_float16 = d.storage_16bit = false;
  return d;
}

DeviceInfo vulkan11(DeviceInfo d) {
  d.api_version = "1.1.0";
  d.vulkan12 = d.shader_float16 = d.storage_16bit = false;  // unknown below 1.2: never queried
  d.subgroup_stages = d.subgroup_features = 0;
  return d;
}

// The message a selection throws, checked to be of type E.
template <typename E>
std::string error_of(const std::vector<DeviceInfo>& devices, const std::string& selection,
                     const DeviceRequirements& req) {
  try {
    uint32_t i = select_device(devices, selection, req);
    ADD_FAILURE() << "selected device " << i;
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

TEST(MesaRelease, ReadFromTheDriverInfo) {
  EXPECT_EQ(mesa_release("Mesa 22.3.6 (LLVM 15.0.6)"), 2203u);
  EXPECT_EQ(mesa_release("Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)"), 2500u);
  EXPECT_EQ(mesa_release("Mesa 24.10.1"), 2410u);
  EXPECT_EQ(mesa_release("580.159.04"), 0u);  // NVIDIA's
  EXPECT_EQ(mesa_release("Mesa 25"), 0u);
  EXPECT_EQ(mesa_release("Mesa .1"), 0u);
  EXPECT_EQ(mesa_release(""), 0u);
}

TEST(DeviceRequirements, ACapableDeviceMeetsAll) {
  EXPECT_EQ(unmet_requirements(lavapipe(0), {true, true}), Reasons{});
}

TEST(DeviceRequirements, EveryUnmetRequirementIsListedNotOnlyTheFirst) {
  DeviceInfo d = without_fp16(lavapipe(0));
  d.timestamps = d.swapchain = d.presents = false;
  d.subgroup_features = 0;
  EXPECT_EQ(unmet_requirements(d, {true, true}),
            (Reasons{"no timestamp queries on its compute queue", "no subgroup arithmetic, ballot and shuffle in compute shaders",
                     "no shaderFloat16", "no storageBuffer16BitAccess", "no VK_KHR_swapchain",
                     "no queue family with compute that can present to the window"}));
  // What a run does not ask for is not held against the device.
  EXPECT_EQ(unmet_requirements(d, {false, false}),
            (Reasons{"no timestamp queries on its compute queue", "no subgroup arithmetic, ballot and shuffle in compute shaders"}));
}

// The subgroup operations every path-tracing pipeline declares, each one
// missing named (a device may have arithmetic and ballot without shuffle).
TEST(DeviceRequirements, MissingSubgroupOperationsAreNamed) {
  DeviceInfo d = lavapipe(0);
  EXPECT_EQ(missing_subgroup_operations(d), "");
  d.subgroup_features &= ~uint32_t(VK_SUBGROUP_FEATURE_SHUFFLE_BIT);
  EXPECT_EQ(missing_subgroup_operations(d), "shuffle");
  EXPECT_EQ(unmet_requirements(d, {false, false}), Reasons{"no subgroup shuffle in compute shaders"});
  d.subgroup_features &= ~uint32_t(VK_SUBGROUP_FEATURE_BALLOT_BIT);
  EXPECT_EQ(missing_subgroup_operations(d), "ballot and shuffle");
  d.subgroup_features = VK_SUBGROUP_FEATURE_BALLOT_BIT;
  EXPECT_EQ(missing_subgroup_operations(d), "arithmetic and shuffle");
  d = lavapipe(0);
  d.subgroup_stages = VK_SHADER_STAGE_FRAGMENT_BIT;  // subgroups, but not in compute shaders
  EXPECT_EQ(unmet_requirements(d, {false, false}), Reasons{"no subgroup operations in compute shaders"});
}

TEST(DeviceRequirements, BelowVulkan12TheVersionIsTheReasonForTheUnqueriedFeatures) {
  EXPECT_EQ(unmet_requirements(vulkan11(discrete(0)), {true, false}), Reasons{"Vulkan 1.1.0 < 1.2"});
}

TEST(DeviceRequirements, NoComputeQueueIsSaidOnce) {
  DeviceInfo d = lavapipe(0);
  d.compute = d.timestamps = d.presents = false;
  EXPECT_EQ(unmet_requirements(d, {false, true}), Reasons{"no compute queue"});
}

TEST(SelectDevice, AutoPrefersAGpuThatFitsAndFallsBackToTheCpu) {
  EXPECT_EQ(select_device({lavapipe(0), discrete(1)}, "auto", {}), 1u);
  EXPECT_EQ(select_device({lavapipe(0), without_fp16(discrete(1))}, "auto", {true, false}), 0u);
  EXPECT_EQ(select_device({lavapipe(0), discrete(1)}, "cpu", {}), 0u);
  EXPECT_EQ(select_device({lavapipe(0), discrete(1)}, "gpu", {}), 1u);
  EXPECT_EQ(select_device({lavapipe(0), discrete(1)}, "0", {}), 0u);
}

TEST(SelectDevice, NoFitListsEveryCandidateWithEveryReason) {
  DeviceInfo cpu = without_fp16(lavapipe(0));
  cpu.swapchain = false;
  DeviceInfo gpu = vulkan11(discrete(1));
  EXPECT_EQ(error_of<RuntimeError>({cpu, gpu}, "auto", {true, true}),
            "no suitable Vulkan device: 1 NVIDIA GeForce RTX 4090: Vulkan 1.1.0 < 1.2; "
            "0 llvmpipe (LLVM 15.0.6, 256 bits): no shaderFloat16, no storageBuffer16BitAccess, no VK_KHR_swapchain");
  // Only the candidates of the selection are listed.
  EXPECT_EQ(error_of<RuntimeError>({cpu, gpu}, "gpu", {}),
            "no suitable Vulkan device: 1 NVIDIA GeForce RTX 4090: Vulkan 1.1.0 < 1.2");
}

TEST(SelectDevice, MissingOnlyThe16BitFeaturesIsAPrecisionError) {
  std::vector<DeviceInfo> devices{without_fp16(lavapipe(0)), vulkan11(discrete(1))};
  try {
    select_device(devices, "auto", {true, false});
    FAIL() << "selected a device";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.setting, "precision");
    EXPECT_STREQ(e.what(),
                 "precision fp16: no suitable device: 1 NVIDIA GeForce RTX 4090: Vulkan 1.1.0 < 1.2; "
                 "0 llvmpipe (LLVM 15.0.6, 256 bits): no shaderFloat16, no storageBuffer16BitAccess");
  }
}

TEST(SelectDevice, ASelectionThatNamesNoDeviceIsADeviceSettingError) {
  std::vector<DeviceInfo> devices{lavapipe(0), discrete(1)};
  struct Case {
    std::vector<DeviceInfo> devices;
    std::string selection, message;
  } cases[] = {
      {devices, "banana", "device: expected auto, cpu, gpu or a device index, got \"banana\""},
      {devices, "", "device: expected auto, cpu, gpu or a device index, got \"\""},
      {devices, "99", "device: index 99 out of range (2 devices)"},
      {{lavapipe(0)}, "1", "device: index 1 out of range (1 device)"},
      {{lavapipe(0)}, "gpu", "device gpu: no GPU device found"},
      {{discrete(0)}, "cpu", "device cpu: no CPU (software) device found"},
  };
  for (const auto& c : cases) {
    try {
      select_device(c.devices, c.selection, {});
      ADD_FAILURE() << c.selection << " selected a device";
    } catch (const SettingError& e) {
      EXPECT_EQ(e.setting, "device");
      EXPECT_EQ(std::string(e.what()), c.message);
    }
  }
}

TEST(SelectDevice, NoDeviceAtAllIsARuntimeError) {
  EXPECT_NE(error_of<RuntimeError>({}, "auto", {}).find("no Vulkan device found"), std::string::npos);
}

}  // namespace
