// Specialisation of a SPIR-V module before the driver sees it: the
// specialisation constants are frozen to their values and the code they
// switch off is removed (SPIRV-Tools' optimizer), so the driver's compiler
// never translates it. Knows nothing of scenes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

struct SpecConstant;

// The module `spirv` with each constant of `spec` (SpecId -> value, as
// VkSpecializationInfo would give it: 32 bits, 0 or 1 for a bool) set and
// frozen, the branches, blocks and functions that became dead removed, and
// then SPIRV-Tools' performance recipe (the passes of `spirv-opt -O`) run
// over what is left, which shrinks the module another 6x (the driver's
// translation with it). The optimizer folds or reassociates float
// arithmetic only where it lacks NoContraction, and every float instruction
// of our modules carries it (vk/spirv_contraction.h): on lavapipe the
// images are bit-identical to the driver's specialisation (effects_test
// checks it). On the H200 the recipe's module was not (6 values of a 48x32
// image; the light passes alone were: optimisation log 36), so
// create_compute_pipeline runs the recipe on software devices only. Empty
// when the optimizer fails (the caller then passes the constants to the
// driver as usual).
// `optimize` false runs only the constant and dead-code passes: llvmpipe 22.3
// counts every loop iteration of an invocation against one limit of 65535
// and ends the loop there, and the performance recipe changes how a loop
// that reaches it is cut (brute force over 8,000 spheres at depth 50: 98%
// of pixels as the octree's with the light passes, 89% with the recipe;
// below the limit the images are identical; optimisation log 34).
std::vector<uint32_t> specialize_spirv(const uint32_t* spirv, size_t spirv_bytes,
                                       const std::vector<SpecConstant>& spec, bool optimize = true);

// Whether pipelines on a device are created from specialize_spirv's module
// (ahead-of-driver specialisation). On by default on software devices, where
// it was measured (lavapipe translates the whole module before it folds the
// constants: docs/optimisation-log.md); off on GPUs. OCTRACE_SPECIALIZE=0 / 1
// forces it off / on for every device.
bool specialize_spirv_enabled(bool software_device);

// The optimizer costs more than the driver's translation it saves (0.8 s
// against 0.6 s on the 2-core machine for the default scene's pipeline), so
// its result is kept on disk: specialize_spirv's module (optimize = true)
// for these inputs, read from `cache_dir` when an earlier run made it, else
// made and stored there. The key hashes the module, the constants and the SPIRV-Tools
// version; a file that does not hold a complete module of that key (torn,
// truncated, of another version) is ignored and replaced. A folder that
// cannot be created, read or written only costs the optimizer's time: it is
// never an error. An empty `cache_dir` means no cache.
std::vector<uint32_t> specialize_spirv_cached(const uint32_t* spirv, size_t spirv_bytes,
                                              const std::vector<SpecConstant>& spec, const std::string& cache_dir);

// Where the specialised modules are kept: OCTRACE_CACHE_DIR if it is set
// ("none": no cache), else $XDG_CACHE_HOME/octrace/spirv, else
// $HOME/.cache/octrace/spirv; empty when none of them is set.
std::string spirv_cache_dir();

}  // namespace octrace
