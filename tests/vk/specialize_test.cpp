// Ahead-of-driver specialisation (vk/specialize.h): the module it returns has
// the constants frozen, is valid SPIR-V, and is smaller; a module the
// optimizer cannot read gives an empty result (the caller falls back to the
// driver's specialisation). That images do not change is effects_test's.
#include <cstdlib>

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

#include "path_trace_fp32.h"
#include "render/gpu_layout.h"
#include "vk/resources.h"
#include "vk/specialize.h"

namespace octrace {
namespace {

// The SpecId decorations of a module (OpDecorate %x SpecId N: opcode 71,
// decoration 1).
std::vector<uint32_t> spec_ids(const std::vector<uint32_t>& m) {
  std::vector<uint32_t> ids;
  for (size_t i = 5; i < m.size();) {
    const uint32_t words = m[i] >> 16, opcode = m[i] & 0xffffu;
    if (words == 0) break;
    if (opcode == 71 && words == 4 && m[i + 2] == 1) ids.push_back(m[i + 3]);
    i += words;
  }
  return ids;
}

// The default scene's features: spheres only, the four RTIOW materials, a
// thin lens, the gradient sky.
const std::vector<SpecConstant> RTIOW = {
    {gpu::SPEC_ACCEL, gpu::ACCEL_OCTREE}, {gpu::SPEC_LAMBERTIAN, 1}, {gpu::SPEC_METAL, 1},
    {gpu::SPEC_FUZZ, 1}, {gpu::SPEC_DIELECTRIC, 1}, {gpu::SPEC_EMISSIVE, 0}, {gpu::SPEC_PBR, 0},
    {gpu::SPEC_DEFOCUS, 1}, {gpu::SPEC_SAMPLE_LANES, 0}, {gpu::SPEC_SKY, gpu::SKY_GRADIENT},
    {gpu::SPEC_ANY_LIGHT, 1}, {gpu::SPEC_SPHERES, 1}, {gpu::SPEC_TRIANGLES, 0},
    {gpu::SPEC_VERTEX_NORMALS, 0}, {gpu::SPEC_TEXTURES, 0}, {gpu::SPEC_SURFACE_EMISSION, 0},
    {gpu::SPEC_NORMAL_MAPS, 0}, {gpu::SPEC_ALPHA, 0}, {gpu::SPEC_SINGLE_SIDED, 0},
    {gpu::SPEC_TRANSMISSION, 0}, {gpu::SPEC_NEE, 0}, {gpu::SPEC_PUNCTUAL, 0}};

TEST(Specialize, FreezesTheConstantsAndDropsDeadCode) {
  const std::vector<uint32_t> original(path_trace_fp32_spv,
                                       path_trace_fp32_spv + sizeof(path_trace_fp32_spv) / sizeof(uint32_t));
  ASSERT_FALSE(spec_ids(original).empty());
  const std::vector<uint32_t> m = specialize_spirv(original.data(), sizeof(path_trace_fp32_spv), RTIOW);
  ASSERT_FALSE(m.empty());
  EXPECT_TRUE(spec_ids(m).empty()) << "a specialisation constant is left";
  EXPECT_LT(m.size(), original.size() * 9 / 10) << "the code of absent effects is still there";
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
  std::string errors;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* msg) {
    errors += msg;
    errors += '\n';
  });
  EXPECT_TRUE(tools.Validate(m)) << errors;
}

TEST(Specialize, ConstantsNotGivenKeepTheirDefaultsAndAreFrozen) {
  // Only the accel is given: every other constant takes its default (the
  // general pipeline's) and is frozen too.
  const std::vector<uint32_t> m =
      specialize_spirv(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), {{gpu::SPEC_ACCEL, gpu::ACCEL_BRUTE}});
  ASSERT_FALSE(m.empty());
  EXPECT_TRUE(spec_ids(m).empty());
}

TEST(Specialize, UnreadableModuleGivesNothing) {
  const std::vector<uint32_t> garbage(64, 0xdeadbeefu);
  EXPECT_TRUE(specialize_spirv(garbage.data(), garbage.size() * sizeof(uint32_t), RTIOW).empty());
  EXPECT_TRUE(specialize_spirv(path_trace_fp32_spv, 12, RTIOW).empty());  // a cut header
}

TEST(Specialize, OnForSoftwareDevicesUnlessTheEnvironmentSays) {
  const char* saved = std::getenv("OCTRACE_SPECIALIZE");
  const std::string keep = saved ? saved : "";
  unsetenv("OCTRACE_SPECIALIZE");
  EXPECT_TRUE(specialize_spirv_enabled(true));
  EXPECT_FALSE(specialize_spirv_enabled(false));
  setenv("OCTRACE_SPECIALIZE", "0", 1);
  EXPECT_FALSE(specialize_spirv_enabled(true));
  setenv("OCTRACE_SPECIALIZE", "1", 1);
  EXPECT_TRUE(specialize_spirv_enabled(false));
  if (saved) setenv("OCTRACE_SPECIALIZE", keep.c_str(), 1); else unsetenv("OCTRACE_SPECIALIZE");
}

}  // namespace
}  // namespace octrace
