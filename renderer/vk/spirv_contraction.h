// SPIR-V post-processing: forbid the driver to fuse a multiply and an add.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace octrace {

// A copy of `spirv` in which every floating-point arithmetic instruction
// (OpFAdd, OpFSub, OpFMul, OpFDiv, OpFNegate, OpFRem, OpFMod, OpDot and the
// vector/matrix products) carries the NoContraction decoration, as if each
// were declared `precise` in GLSL. Without it a driver may contract a*b + c
// into one fused multiply-add wherever it likes, and two pipelines built
// from the same source with different specialization constants may fuse
// differently and round differently (SPIR-V 1.6, 3.20 "Decoration":
// NoContraction). Explicit fma() calls are not affected. Throws
// std::invalid_argument on a malformed module.
std::vector<uint32_t> without_contraction(std::span<const uint32_t> spirv);

}  // namespace octrace
