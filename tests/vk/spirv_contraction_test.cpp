// without_contraction (vk/spirv_contraction.h): every float arithmetic result
// of a module gets NoContraction once, nothing else changes, and malformed
// modules are refused. The render tests create every pipeline from the
// processed modules with the validation layer on, which checks the result is
// valid SPIR-V.
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "path_trace_fp32.h"
#include "vk/spirv_contraction.h"

namespace {

using octrace::without_contraction;

constexpr uint32_t kOpDecorate = 71, kNoContraction = 42, kOpFAdd = 129, kOpFMul = 133, kOpDot = 148;

struct Instruction {
  uint32_t op;
  std::vector<uint32_t> words;
};

std::vector<Instruction> instructions(std::span<const uint32_t> m) {
  std::vector<Instruction> out;
  for (size_t i = 5; i < m.size(); i += m[i] >> 16)
    out.push_back({m[i] & 0xffffu, std::vector<uint32_t>(m.begin() + i, m.begin() + i + (m[i] >> 16))});
  return out;
}

std::map<uint32_t, int> no_contraction_counts(std::span<const uint32_t> m) {
  std::map<uint32_t, int> n;
  for (const auto& ins : instructions(m))
    if (ins.op == kOpDecorate && ins.words.size() == 3 && ins.words[2] == kNoContraction) ++n[ins.words[1]];
  return n;
}

TEST(SpirvContraction, EveryFloatArithmeticResultOfThePathTracerIsDecoratedOnce) {
  std::span<const uint32_t> in(path_trace_fp32_spv, sizeof(path_trace_fp32_spv) / 4);
  std::vector<uint32_t> out = without_contraction(in);
  std::set<uint32_t> arithmetic;
  for (const auto& ins : instructions(in))
    if (ins.op == kOpFAdd || ins.op == kOpFMul || ins.op == kOpDot) arithmetic.insert(ins.words[2]);
  ASSERT_GT(arithmetic.size(), 100u);  // the path tracer does arithmetic
  auto counts = no_contraction_counts(out);
  for (uint32_t id : arithmetic) EXPECT_EQ(counts[id], 1) << "id " << id;
  // Nothing but decorations is added; the rest keeps its order.
  std::vector<Instruction> a = instructions(in), b = instructions(out);
  std::erase_if(b, [](const Instruction& i) { return i.op == kOpDecorate && i.words[2] == kNoContraction; });
  std::erase_if(a, [](const Instruction& i) { return i.op == kOpDecorate && i.words[2] == kNoContraction; });
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i].words, b[i].words) << "instruction " << i;
  EXPECT_EQ(std::vector<uint32_t>(in.begin(), in.begin() + 5), std::vector<uint32_t>(out.begin(), out.begin() + 5));
}

TEST(SpirvContraction, IsIdempotentAndDecoratesBeforeTheFirstType) {
  // header; OpCapability Shader; OpMemoryModel; OpName %4 ""; OpTypeFloat %1 32;
  // OpFAdd %1 %4 %2 %3 (ids 2 and 3 need not exist for this pass).
  std::vector<uint32_t> m = {0x07230203u, 0x00010000u, 0u, 5u, 0u,
                             (2u << 16) | 17u, 1u,
                             (3u << 16) | 14u, 0u, 1u,
                             (3u << 16) | 5u, 4u, 0u,
                             (3u << 16) | 22u, 1u, 32u,
                             (5u << 16) | kOpFAdd, 1u, 4u, 2u, 3u};
  std::vector<uint32_t> once = without_contraction(m);
  ASSERT_EQ(once.size(), m.size() + 3);
  std::vector<uint32_t> expected(m.begin(), m.begin() + 13);
  expected.insert(expected.end(), {(3u << 16) | kOpDecorate, 4u, kNoContraction});
  expected.insert(expected.end(), m.begin() + 13, m.end());
  EXPECT_EQ(once, expected);
  EXPECT_EQ(without_contraction(once), once);
}

TEST(SpirvContraction, RefusesMalformedModules) {
  std::vector<uint32_t> good = {0x07230203u, 0x00010000u, 0u, 5u, 0u, (3u << 16) | 22u, 1u, 32u};
  EXPECT_NO_THROW(without_contraction(good));
  std::vector<uint32_t> bad_magic = good;
  bad_magic[0] = 0x03022307u;
  EXPECT_THROW(without_contraction(bad_magic), std::invalid_argument);
  std::vector<uint32_t> truncated = good;
  truncated.pop_back();
  EXPECT_THROW(without_contraction(truncated), std::invalid_argument);
  std::vector<uint32_t> zero_count = good;
  zero_count[5] = 22u;
  EXPECT_THROW(without_contraction(zero_count), std::invalid_argument);
  EXPECT_THROW(without_contraction(std::vector<uint32_t>(good.begin(), good.begin() + 3)), std::invalid_argument);
}

}  // namespace
