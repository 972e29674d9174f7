// merge_accumulations and merge_accumulation_pixels (render/multi_device.h):
// what --device lists and the MPI front end merge states with. Parts that
// accumulated disjoint samples merge to the count, mean and M2 of all the
// samples; a merge in place or in slices (the MPI reduce) gives the same
// bits as a merge into a fresh state.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "render/multi_device.h"

namespace octrace {
namespace {

// The shader's add_sample (shaders/path_trace.comp) in fp32 on the CPU:
// Kahan sum with the count in .w, the compensation, Welford's M2 with the
// ray segments in sq.w.
void add_sample(const glm::vec3& value, uint32_t segments, glm::vec4& acc, glm::vec4& comp, glm::vec4& sq) {
  const glm::vec3 c = glm::vec3(comp);
  const glm::vec3 y = value - c;
  const glm::vec3 t = glm::vec3(acc) + y;
  const float n = acc.w;
  const glm::vec3 mean_old = n > 0 ? (glm::vec3(acc) - c) / n : glm::vec3(0);
  const glm::vec3 c_new = (t - glm::vec3(acc)) - y;
  const glm::vec3 mean_new = (t - c_new) / (n + 1);
  comp = glm::vec4(c_new, comp.w);
  acc = glm::vec4(t, n + 1);
  sq = glm::vec4(glm::vec3(sq) + (value - mean_old) * (value - mean_new),
                 std::bit_cast<float>(std::bit_cast<uint32_t>(sq.w) + segments));
}

Accumulation empty_state(int width, int height) {
  const size_t n = size_t(width) * size_t(height);
  return {width, height, std::vector<glm::vec4>(n), std::vector<glm::vec4>(n), std::vector<glm::vec4>(n)};
}

// Three parts of 7 x 5 pixels; part k adds counts[k] samples to each pixel
// (part 2 none to pixel 0: a part may miss a pixel). Also returns every
// pixel's samples for the exact statistics.
std::vector<Accumulation> three_parts(std::vector<std::vector<glm::vec3>>& samples) {
  constexpr int kW = 7, kH = 5;
  const int counts[3] = {40, 25, 90};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Accumulation> parts(3, empty_state(kW, kH));
  samples.assign(kW * kH, {});
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < size_t(kW * kH); ++i) {
      if (k == 2 && i == 0) continue;
      for (int s = 0; s < counts[k]; ++s) {
        // Bright outliers now and then: a heavy-tailed pixel, as renders have.
        const glm::vec3 v = glm::vec3(u(rng), u(rng), u(rng)) * (u(rng) < 0.05f ? 50.0f : 1.0f);
        add_sample(v, 3, parts[k].sum[i], parts[k].comp[i], parts[k].sq[i]);
        samples[i].push_back(v);
      }
    }
  return parts;
}

// Bounds: the merge computes in double from fp32 states, so the mean is
// within a few fp32 ulps of the exact one (1e-6 relative); each part's M2
// is an fp32 Welford sum over at most 90 samples, whose error grows like
// n * 2^-24 relative (< 1e-5), so M2 is held to 1e-4 relative.
TEST(MergeAccumulations, DisjointPartsGiveTheCountMeanAndM2OfAllSamples) {
  std::vector<std::vector<glm::vec3>> samples;
  const std::vector<Accumulation> parts = three_parts(samples);
  const Accumulation merged = merge_accumulations(parts);
  for (size_t i = 0; i < samples.size(); ++i) {
    const double n = double(samples[i].size());
    ASSERT_EQ(merged.sum[i].w, float(n)) << i;
    EXPECT_EQ(std::bit_cast<uint32_t>(merged.sq[i].w), uint32_t(3 * n)) << i;
    for (int c = 0; c < 3; ++c) {
      double total = 0;
      for (const glm::vec3& v : samples[i]) total += v[c];
      const double mean = total / n;
      double m2 = 0;
      for (const glm::vec3& v : samples[i]) m2 += (v[c] - mean) * (v[c] - mean);
      const double merged_mean = (double(merged.sum[i][c]) - double(merged.comp[i][c])) / n;
      EXPECT_NEAR(merged_mean, mean, 1e-6 * mean) << i << " " << c;
      EXPECT_NEAR(double(merged.sq[i][c]), m2, 1e-4 * m2) << i << " " << c;
    }
  }
}

bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0;
}

// The MPI reduce: the other parts arrive in slices (buffers of their own)
// and merge into the first part's own buffers.
TEST(MergeAccumulations, InPlaceAndInSlicesGiveTheSameBits) {
  std::vector<std::vector<glm::vec3>> samples;
  const std::vector<Accumulation> parts = three_parts(samples);
  const Accumulation expected = merge_accumulations(parts);
  Accumulation in_place = parts[0];
  const size_t pixels = in_place.sum.size();
  for (size_t begin = 0; begin < pixels; begin += 4) {  // slices of 4 pixels; the last one shorter
    const size_t count = std::min<size_t>(4, pixels - begin);
    std::vector<std::vector<glm::vec4>> slices;
    std::vector<AccumulationPixels> views = {
        {in_place.sum.data() + begin, in_place.comp.data() + begin, in_place.sq.data() + begin}};
    for (size_t k = 1; k < parts.size(); ++k) {
      for (const std::vector<glm::vec4>* v : {&parts[k].sum, &parts[k].comp, &parts[k].sq})
        slices.emplace_back(v->begin() + long(begin), v->begin() + long(begin + count));
      const size_t at = slices.size() - 3;
      views.push_back({slices[at].data(), slices[at + 1].data(), slices[at + 2].data()});
    }
    merge_accumulation_pixels(views, in_place.sum.data() + begin, in_place.comp.data() + begin,
                              in_place.sq.data() + begin, count);
  }
  EXPECT_TRUE(same_bits(in_place.sum, expected.sum));
  EXPECT_TRUE(same_bits(in_place.sq, expected.sq));
  // comp.w is not part of the state (the shader leaves it 0); .rgb must match.
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(std::bit_cast<uint32_t>(in_place.comp[i][c]), std::bit_cast<uint32_t>(expected.comp[i][c])) << i;
}

}  // namespace
}  // namespace octrace
