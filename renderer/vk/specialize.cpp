#include "vk/specialize.h"

#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include <spirv-tools/optimizer.hpp>

#include "vk/resources.h"

namespace octrace {

std::vector<uint32_t> specialize_spirv(const uint32_t* spirv, size_t spirv_bytes,
                                       const std::vector<SpecConstant>& spec) {
  std::unordered_map<uint32_t, std::vector<uint32_t>> values;
  for (const SpecConstant& s : spec) values[s.id] = {s.value};
  spvtools::Optimizer opt(SPV_ENV_VULKAN_1_2);
  opt.SetMessageConsumer([](spv_message_level_t, const char*, const spv_position_t&, const char*) {});
  // Set and freeze the constants, fold the expressions over them (e.g.
  // `HAS_METAL && !HAS_FUZZ`), then drop the branches whose condition is now
  // a constant, the code nothing uses any more, and the functions no call
  // reaches. Merging blocks lets the second dead-code pass see through the
  // straight lines the first left.
  opt.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(values))
      .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
      .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
      .RegisterPass(spvtools::CreateDeadBranchElimPass())
      .RegisterPass(spvtools::CreateAggressiveDCEPass())
      .RegisterPass(spvtools::CreateBlockMergePass())
      .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
      .RegisterPass(spvtools::CreateAggressiveDCEPass());
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

}  // namespace octrace
