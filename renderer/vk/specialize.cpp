#include "vk/specialize.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include <spirv-tools/libspirv.h>
#include <spirv-tools/optimizer.hpp>

#include "core/hash.h"
#include "io/file.h"
#include "vk/resources.h"

namespace octrace {

std::vector<uint32_t> specialize_spirv(const uint32_t* spirv, size_t spirv_bytes,
                                       const std::vector<SpecConstant>& spec, bool optimize) {
  std::unordered_map<uint32_t, std::vector<uint32_t>> values;
  for (const SpecConstant& s : spec) values[s.id] = {s.value};
  spvtools::Optimizer opt(SPV_ENV_VULKAN_1_2);
  opt.SetMessageConsumer([](spv_message_level_t, const char*, const spv_position_t&, const char*) {});
  // Set and freeze the constants, fold the expressions over them (e.g.
  // `HAS_METAL && !HAS_FUZZ`), then drop the branches whose condition is now
  // a constant, the code nothing uses any more, and the functions no call
  // reaches. Merging blocks lets the second dead-code pass see through the
  // straight lines the first left. The performance recipe then inlines,
  // turns variables into SSA values and removes what became redundant
  // (190 KB -> 31 KB for the default scene; optimisation log 34).
  opt.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(values))
      .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
      .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
      .RegisterPass(spvtools::CreateDeadBranchElimPass())
      .RegisterPass(spvtools::CreateAggressiveDCEPass())
      .RegisterPass(spvtools::CreateBlockMergePass())
      .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
      .RegisterPass(spvtools::CreateAggressiveDCEPass());
  if (optimize) opt.RegisterPerformancePasses();
  spvtools::OptimizerOptions options;
  options.set_run_validator(false);  // our own modules, validated by the driver's layer in the tests
  std::vector<uint32_t> out;
  if (!opt.Run(spirv, spirv_bytes / sizeof(uint32_t), &out, options)) return {};
  return out;
}

bool specialize_spirv_enabled(bool software_device) {
  if (const char* e = std::getenv("OCTRACE_SPECIALIZE"); e && *e) return std::strcmp(e, "0") != 0;
  return software_device;
}

namespace {

// A cache file: this header, then the module's words.
struct CacheHeader {
  uint32_t magic;    // kCacheMagic
  uint32_t version;  // kCacheVersion
  uint64_t key;      // what the module was made from (cache_key)
  uint64_t words;    // the module's length in words
  uint64_t check;    // Hash64 of the module's words: a torn file is not taken
};
static_assert(sizeof(CacheHeader) == 32);

constexpr uint32_t kCacheMagic = 0x4f435356u;  // "VSCO"
constexpr uint32_t kCacheVersion = 1;          // the passes above and this layout
constexpr uint32_t kSpirvMagic = 0x07230203u;

uint64_t cache_key(const uint32_t* spirv, size_t spirv_bytes, const std::vector<SpecConstant>& spec) {
  Hash64 h;
  h.add(&kCacheVersion, sizeof kCacheVersion);
  const char* tools = spvSoftwareVersionDetailsString();
  h.add(tools, std::strlen(tools));
  h.add(spirv, spirv_bytes);
  for (const SpecConstant& s : spec) h.add(&s, sizeof s);
  return h.value();
}

uint64_t words_hash(const std::vector<uint32_t>& m) { return Hash64().add_vector(m).value(); }

// The cached module of `key` in `path`, or empty.
std::vector<uint32_t> read_cached(const std::string& path, uint64_t key) {
  std::string bytes;
  try {
    bytes = read_file(path);
  } catch (const std::exception&) {
    return {};
  }
  CacheHeader h{};
  if (bytes.size() < sizeof h) return {};
  std::memcpy(&h, bytes.data(), sizeof h);
  if (h.magic != kCacheMagic || h.version != kCacheVersion || h.key != key || h.words == 0 ||
      bytes.size() != sizeof h + h.words * sizeof(uint32_t))
    return {};
  std::vector<uint32_t> m(h.words);
  std::memcpy(m.data(), bytes.data() + sizeof h, h.words * sizeof(uint32_t));
  if (m[0] != kSpirvMagic || words_hash(m) != h.check) return {};
  return m;
}

void write_cached(const std::string& dir, const std::string& path, uint64_t key, const std::vector<uint32_t>& m) {
  std::string bytes(sizeof(CacheHeader) + m.size() * sizeof(uint32_t), '\0');
  const CacheHeader h{kCacheMagic, kCacheVersion, key, m.size(), words_hash(m)};
  std::memcpy(bytes.data(), &h, sizeof h);
  std::memcpy(bytes.data() + sizeof h, m.data(), m.size() * sizeof(uint32_t));
  try {
    std::error_code ec;  // a folder that cannot be made fails the write below
    std::filesystem::create_directories(dir, ec);
    write_file_atomically(path, bytes.data(), bytes.size(), "cannot write SPIR-V cache");
  } catch (const std::exception&) {
    // A cache that cannot be written costs the optimizer's time next run, nothing else.
  }
}

}  // namespace

std::vector<uint32_t> specialize_spirv_cached(const uint32_t* spirv, size_t spirv_bytes,
                                              const std::vector<SpecConstant>& spec, const std::string& cache_dir) {
  if (cache_dir.empty()) return specialize_spirv(spirv, spirv_bytes, spec);
  const uint64_t key = cache_key(spirv, spirv_bytes, spec);
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.spv", static_cast<unsigned long long>(key));
  const std::string path = (std::filesystem::path(cache_dir) / name).string();
  if (std::vector<uint32_t> m = read_cached(path, key); !m.empty()) return m;
  std::vector<uint32_t> m = specialize_spirv(spirv, spirv_bytes, spec);
  if (!m.empty()) write_cached(cache_dir, path, key, m);
  return m;
}

std::string spirv_cache_dir() {
  if (const char* e = std::getenv("OCTRACE_CACHE_DIR"); e && *e) return std::strcmp(e, "none") == 0 ? "" : e;
  if (const char* e = std::getenv("XDG_CACHE_HOME"); e && *e)
    return (std::filesystem::path(e) / "octrace" / "spirv").string();
  if (const char* e = std::getenv("HOME"); e && *e)
    return (std::filesystem::path(e) / ".cache" / "octrace" / "spirv").string();
  return "";
}

}  // namespace octrace
