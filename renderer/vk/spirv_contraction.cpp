#include "vk/spirv_contraction.h"

#include <algorithm>
#include <stdexcept>

namespace octrace {

namespace {

// Opcodes, from the SPIR-V 1.6 specification, section 3.52 (Instructions).
constexpr uint32_t kOpDecorate = 71;
constexpr uint32_t kDecorationNoContraction = 42;
constexpr uint32_t kMagic = 0x07230203u;
constexpr size_t kHeaderWords = 5;

bool is_float_arithmetic(uint32_t op) {
  switch (op) {
    case 127:  // OpFNegate
    case 129:  // OpFAdd
    case 131:  // OpFSub
    case 133:  // OpFMul
    case 136:  // OpFDiv
    case 140:  // OpFRem
    case 141:  // OpFMod
    case 142:  // OpVectorTimesScalar
    case 143:  // OpMatrixTimesScalar
    case 144:  // OpVectorTimesMatrix
    case 145:  // OpMatrixTimesVector
    case 146:  // OpMatrixTimesMatrix
    case 147:  // OpOuterProduct
    case 148:  // OpDot
      return true;
    default:
      return false;
  }
}

// The logical layout (SPIR-V 1.6, 2.4): annotations end where the first
// type, constant, global variable or function is declared; the new
// decorations go there.
bool ends_annotations(uint32_t op) {
  return (op >= 19 && op <= 39) ||  // OpTypeVoid .. OpTypeForwardPointer
         (op >= 41 && op <= 52) ||  // OpConstantTrue .. OpSpecConstantOp
         op == 54 || op == 59;      // OpFunction, OpVariable
}

}  // namespace

std::vector<uint32_t> without_contraction(std::span<const uint32_t> spirv) {
  if (spirv.size() < kHeaderWords || spirv[0] != kMagic) throw std::invalid_argument("not a SPIR-V module");
  std::vector<uint32_t> decorated;  // result ids to decorate
  std::vector<uint32_t> precise;    // ids the module decorates already (GLSL `precise`)
  size_t insert_at = 0;             // word index of the first declaration
  for (size_t i = kHeaderWords; i < spirv.size();) {
    const uint32_t count = spirv[i] >> 16;
    const uint32_t op = spirv[i] & 0xffffu;
    if (count == 0 || i + count > spirv.size()) throw std::invalid_argument("malformed SPIR-V instruction");
    if (insert_at == 0 && ends_annotations(op)) insert_at = i;
    if (is_float_arithmetic(op) && count >= 3) decorated.push_back(spirv[i + 2]);
    if (op == kOpDecorate && count == 3 && spirv[i + 2] == kDecorationNoContraction) precise.push_back(spirv[i + 1]);
    i += count;
  }
  if (insert_at == 0) throw std::invalid_argument("SPIR-V module without declarations");
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + insert_at);
  out.reserve(spirv.size() + 3 * decorated.size());
  std::sort(precise.begin(), precise.end());
  for (uint32_t id : decorated) {
    if (std::binary_search(precise.begin(), precise.end(), id)) continue;
    out.push_back((3u << 16) | kOpDecorate);
    out.push_back(id);
    out.push_back(kDecorationNoContraction);
  }
  out.insert(out.end(), spirv.begin() + insert_at, spirv.end());
  return out;
}

}  // namespace octrace
