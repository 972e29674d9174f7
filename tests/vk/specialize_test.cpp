// Ahead-of-driver specialisation (vk/specialize.h): the module it returns has
// the constants frozen, is valid SPIR-V, and is smaller; a module the
// optimizer cannot read gives an empty result (the caller falls back to the
// driver's specialisation); the on-disk cache gives back what the optimizer
// made and never a damaged file. That images do not change is effects_test's.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <unistd.h>

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

#include "path_trace_fp32.h"
#include "core/hash.h"
#include "io/file.h"
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

// The one file a cache folder holds after one module was made.
std::filesystem::path only_file(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  EXPECT_EQ(files.size(), 1u);
  return files.empty() ? std::filesystem::path() : files[0];
}

TEST(Specialize, CacheHoldsTheOptimizersModuleAndReplacesADamagedOne) {
  const auto dir = std::filesystem::path(OCTRACE_TEST_TMP) / ("spirv-cache-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::vector<uint32_t> fresh = specialize_spirv(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW);
  ASSERT_FALSE(fresh.empty());
  EXPECT_EQ(specialize_spirv_cached(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW, dir.string()), fresh);
  const std::filesystem::path entry = only_file(dir);
  const std::string stored = read_file(entry.string());
  ASSERT_EQ(stored.size(), 32 + fresh.size() * 4);

  // The next call takes the module from the file: one word changed there,
  // with the file's check value made to match, comes back.
  std::vector<uint32_t> edited = fresh;
  edited.back() ^= 1u;
  std::string altered = stored;
  std::memcpy(altered.data() + 32, edited.data(), edited.size() * 4);
  const uint64_t check = Hash64().add_vector(edited).value();
  std::memcpy(altered.data() + 24, &check, 8);
  write_file_atomically(entry.string(), altered.data(), altered.size());
  EXPECT_EQ(specialize_spirv_cached(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW, dir.string()), edited);

  // A torn file (cut short, or a word changed without its check value) is
  // not used: the module is made again and the file replaced.
  for (std::string damaged : {stored.substr(0, stored.size() / 2), stored}) {
    if (damaged.size() == stored.size()) damaged[40] ^= 1;
    write_file_atomically(entry.string(), damaged.data(), damaged.size());
    EXPECT_EQ(specialize_spirv_cached(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW, dir.string()), fresh);
    EXPECT_EQ(read_file(entry.string()), stored);
  }

  // Other constants are another entry.
  std::vector<SpecConstant> other = RTIOW;
  other[0].value = gpu::ACCEL_BRUTE;
  EXPECT_EQ(specialize_spirv_cached(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), other, dir.string()),
            specialize_spirv(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), other));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 2);
  std::filesystem::remove_all(dir);
}

TEST(Specialize, ACacheFolderThatCannotBeMadeIsNoError) {
  // A regular file where the folder should be: nothing can be stored, the
  // module is still made.
  const auto blocker = std::filesystem::path(OCTRACE_TEST_TMP) / ("spirv-cache-file-" + std::to_string(::getpid()));
  write_file_atomically(blocker.string(), "x", 1);
  EXPECT_EQ(specialize_spirv_cached(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW, (blocker / "sub").string()),
            specialize_spirv(path_trace_fp32_spv, sizeof(path_trace_fp32_spv), RTIOW));
  std::filesystem::remove(blocker);
}

TEST(Specialize, CacheFolderFromTheEnvironment) {
  const char* names[] = {"OCTRACE_CACHE_DIR", "XDG_CACHE_HOME", "HOME"};
  std::vector<std::pair<std::string, bool>> saved;
  for (const char* n : names) {
    const char* v = std::getenv(n);
    saved.push_back({v ? v : "", v != nullptr});
    unsetenv(n);
  }
  EXPECT_EQ(spirv_cache_dir(), "");
  setenv("HOME", "/home/u", 1);
  EXPECT_EQ(spirv_cache_dir(), "/home/u/.cache/octrace/spirv");
  setenv("XDG_CACHE_HOME", "/c", 1);
  EXPECT_EQ(spirv_cache_dir(), "/c/octrace/spirv");
  setenv("OCTRACE_CACHE_DIR", "/tmp/x", 1);
  EXPECT_EQ(spirv_cache_dir(), "/tmp/x");
  setenv("OCTRACE_CACHE_DIR", "none", 1);
  EXPECT_EQ(spirv_cache_dir(), "");
  for (size_t i = 0; i < saved.size(); ++i)
    if (saved[i].second) setenv(names[i], saved[i].first.c_str(), 1); else unsetenv(names[i]);
}

}  // namespace
}  // namespace octrace
