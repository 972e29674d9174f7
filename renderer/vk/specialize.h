// Specialisation of a SPIR-V module before the driver sees it: the
// specialisation constants are frozen to their values and the code they
// switch off is removed (SPIRV-Tools' optimizer), so the driver's compiler
// never translates it. Knows nothing of scenes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace octrace {

struct SpecConstant;

// The module `spirv` with each constant of `spec` (SpecId -> value, as
// VkSpecializationInfo would give it: 32 bits, 0 or 1 for a bool) set and
// frozen, then the branches,
// blocks and functions that became dead removed. Only passes that delete or
// fold constant control flow run: no arithmetic is rewritten, so the driver
// compiles the same instructions for the code that is kept (the images are
// bit-identical; effects_test checks it). Empty when the optimizer fails (the
// caller then passes the constants to the driver as usual).
std::vector<uint32_t> specialize_spirv(const uint32_t* spirv, size_t spirv_bytes,
                                       const std::vector<SpecConstant>& spec);

// Whether pipelines on a device are created from specialize_spirv's module
// (ahead-of-driver specialisation). On by default on software devices, where
// it was measured (lavapipe translates the whole module before it folds the
// constants: docs/optimisation-log.md); off on GPUs. OCTRACE_SPECIALIZE=0 / 1
// forces it off / on for every device.
bool specialize_spirv_enabled(bool software_device);

}  // namespace octrace
