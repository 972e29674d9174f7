// Renders held against physics and against themselves.
#include <cmath>
#include <cstring>

#include "test_util.h"

namespace octrace {
namespace {

class RenderTest : public test::VulkanTest {};

RenderResult render_small(const Scene& scene, uint32_t spp, uint32_t depth = 50, uint32_t sample_seed = 1) {
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.spp = spp;
  s.bounce_limit = depth;
  s.sample_seed = sample_seed;
  return render(test::shared_context(), scene, s);
}

// White furnace: under a uniform sky of radiance 1, a lambertian sphere of
// albedo 1 and a perfect mirror absorb nothing, so every path carries exactly
// the sky's radiance and every pixel is 1 (here within 1e-4).
TEST_F(RenderTest, WhiteFurnaceLambertianAndMirrorIsOne) {
  Scene scene = test::furnace_scene();
  scene.materials = {{MaterialType::Lambertian, glm::vec3(1.0f)}, {MaterialType::Metal, glm::vec3(1.0f), 0.0f}};
  scene.spheres = {{{-1.1f, 0, 0}, 1.0f, 0}, {{1.1f, 0, 0}, 1.0f, 1}};
  RenderResult r = render_small(scene, 16);
  EXPECT_EQ(r.nonfinite_samples, 0u);
  float worst = 0;
  for (float v : r.mean.rgb) worst = std::max(worst, std::abs(v - 1.0f));
  EXPECT_LE(worst, 1e-4f) << "largest deviation from 1 in the furnace";
}

// The same settings give bit-identical images (counter-based RNG, no races).
TEST_F(RenderTest, SameSettingsGiveBitIdenticalImages) {
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderResult a = render_small(scene, 4);
  RenderResult b = render_small(scene, 4);
  ASSERT_EQ(a.mean.rgb.size(), b.mean.rgb.size());
  EXPECT_EQ(std::memcmp(a.mean.rgb.data(), b.mean.rgb.data(), a.mean.rgb.size() * sizeof(float)), 0);
}

// Another sample seed gives other noise (and the same scene).
TEST_F(RenderTest, SampleSeedChangesTheNoise) {
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderResult a = render_small(scene, 2, 50, 1);
  RenderResult b = render_small(scene, 2, 50, 2);
  EXPECT_NE(std::memcmp(a.mean.rgb.data(), b.mean.rgb.data(), a.mean.rgb.size() * sizeof(float)), 0);
}

// Every pixel gets exactly spp samples and none is NaN/Inf on the default scene.
TEST_F(RenderTest, RtiowSceneIsClean) {
  RenderResult r = render_small(make_rtiow_scene({}), 3);
  EXPECT_EQ(r.nonfinite_samples, 0u);
  EXPECT_EQ(r.min_samples, 3u);
  for (float v : r.mean.rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
}

// An emitter under a black sky: a pixel that sees the emitter directly has
// its radiance; one that sees the sky is black.
TEST_F(RenderTest, EmitterUnderBlackSky) {
  Scene scene = test::furnace_scene();
  scene.sky.type = SkyType::None;
  Material light;
  light.type = MaterialType::Emissive;
  light.radiance = glm::vec3(4.0f, 2.0f, 1.0f);
  scene.materials = {light};
  scene.spheres = {{{0, 0, 0}, 1.0f, 0}};
  RenderResult r = render_small(scene, 4);
  const float* centre = r.mean.pixel(24, 16);
  EXPECT_FLOAT_EQ(centre[0], 4.0f);
  EXPECT_FLOAT_EQ(centre[1], 2.0f);
  EXPECT_FLOAT_EQ(centre[2], 1.0f);
  const float* corner = r.mean.pixel(0, 0);
  EXPECT_EQ(corner[0] + corner[1] + corner[2], 0.0f);
}

// Depth 1 sees emitters and the sky directly, nothing that needs a bounce:
// a lambertian sphere under a uniform sky is black at depth 1.
TEST_F(RenderTest, DepthLimitCutsPaths) {
  Scene scene = test::furnace_scene();
  scene.materials = {{MaterialType::Lambertian, glm::vec3(1.0f)}};
  scene.spheres = {{{0, 0, 0}, 1.0f, 0}};
  RenderResult r = render_small(scene, 2, 1);
  EXPECT_EQ(r.mean.pixel(24, 16)[0], 0.0f);
  EXPECT_EQ(r.mean.pixel(0, 0)[0], 1.0f);
}

// Russian roulette changes the noise, not the expectation: in the furnace a
// path that survives the roulette (p = 0.95 at throughput 1) carries 1/p, so
// the image mean stays 1. Tolerance: 5 standard errors of the image mean
// (from the per-pixel variances the accumulation keeps), and the noise must
// actually grow (the roulette ran).
TEST_F(RenderTest, RussianRouletteKeepsTheExpectation) {
  Scene scene = test::furnace_scene();
  scene.materials = {{MaterialType::Lambertian, glm::vec3(1.0f)}, {MaterialType::Metal, glm::vec3(1.0f), 0.0f}};
  scene.spheres = {{{-1.1f, 0, 0}, 1.0f, 0}, {{1.1f, 0, 0}, 1.0f, 1}};
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.spp = 64;
  s.rr_depth = 1;
  RenderResult r = render(test::shared_context(), scene, s);
  ASSERT_EQ(r.nonfinite_samples, 0u);
  double sum = 0, var = 0;
  for (size_t i = 0; i < r.mean.rgb.size(); i += 3) {
    sum += r.mean.rgb[i];
    var += r.variance_of_mean.rgb[i];
  }
  const double n = double(r.mean.rgb.size() / 3);
  const double mean = sum / n, standard_error = std::sqrt(var) / n;
  EXPECT_GT(standard_error, 0.0) << "the roulette added no noise: it did not run";
  EXPECT_LE(std::abs(mean - 1.0), 5.0 * standard_error) << "image mean " << mean << ", standard error " << standard_error;
}

}  // namespace
}  // namespace octrace
