// Environment maps on the host (scene/envmap.h): the orientation convention,
// the importance-sampling tables and the host mirror of the shader's
// envmap_sample / envmap_pdf (the shader itself is held to this mirror by
// tests/render/envmap_render_test.cpp), the loader's errors and the JSON sky.
#include "scene/envmap.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "core/errors.h"
#include "io/image.h"
#include "shared/rng.h"
#include "test_util.h"

namespace octrace {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

std::string fresh_folder() {
  const auto* test = testing::UnitTest::GetInstance()->current_test_info();
  fs::path folder = fs::path(OCTRACE_TEST_TMP) / (std::string("envmap_test_") + test->name());
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol) {
  EXPECT_LT(glm::length(a - b), tol) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
                                     << ", " << b.z << ")";
}

// 32 x 16 texels: a smooth ramp of colours, a black row (y = 9), a bright
// top row (the pole) and a sun (texel (20, 4), 5000 x the rest).
EnvmapImage test_map() {
  EnvmapImage m{32, 16, std::vector<float>(32 * 16 * 3)};
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 32; ++x) {
      float* c = &m.rgb[3 * (y * 32 + x)];
      const float base = y == 9 ? 0.0f : y == 0 ? 50.0f : 0.1f + 0.05f * float(x) + 0.2f * float(y % 3);
      c[0] = base, c[1] = 0.5f * base, c[2] = 2.0f * base;
    }
  for (int k = 0; k < 3; ++k) m.rgb[3 * (4 * 32 + 20) + k] = 5000.0f;
  return m;
}

// A map that is black but for one texel.
EnvmapImage one_texel(uint32_t w, uint32_t h, uint32_t x, uint32_t y, float value) {
  EnvmapImage m{w, h, std::vector<float>(size_t(w) * h * 3, 0.0f)};
  for (int k = 0; k < 3; ++k) m.rgb[3 * (y * w + x) + k] = value;
  return m;
}

glm::vec2 uniform2(uint32_t i, uint32_t seed) {
  gpu::Rng rng = gpu::rng_init(seed, i, 0, 0);
  const float a = gpu::rng_next(rng);
  return {a, gpu::rng_next(rng)};
}

// ---------------------------------------------------------------------------
// The convention (scene/envmap.h): the image centre faces -z, u grows towards
// +x, v = 0 is +y, rotate turns counter-clockwise seen from above.

TEST(Envmap, ConventionNamesTheDirections) {
  expect_near(envmap_direction({0.5f, 0.5f}, 0.0f), {0, 0, -1}, 1e-6f);
  expect_near(envmap_direction({0.75f, 0.5f}, 0.0f), {1, 0, 0}, 1e-6f);
  expect_near(envmap_direction({0.25f, 0.5f}, 0.0f), {-1, 0, 0}, 1e-6f);
  expect_near(envmap_direction({0.0f, 0.5f}, 0.0f), {0, 0, 1}, 1e-6f);
  expect_near(envmap_direction({0.3f, 0.0f}, 0.0f), {0, 1, 0}, 1e-6f);
  expect_near(envmap_direction({0.3f, 1.0f}, 0.0f), {0, -1, 0}, 1e-6f);
  // rotate 90: the centre turns from -z to -x (counter-clockwise from above).
  expect_near(envmap_direction({0.5f, 0.5f}, 90.0f), {-1, 0, 0}, 1e-6f);
  expect_near(envmap_direction({0.5f, 0.5f}, -90.0f), {1, 0, 0}, 1e-6f);
}

TEST(Envmap, UvIsTheInverseOfDirection) {
  for (float rotate : {0.0f, 37.5f, -200.0f})
    for (uint32_t i = 0; i < 1000; ++i) {
      glm::vec2 uv = uniform2(i, 7);
      uv.y = 0.01f + 0.98f * uv.y;  // away from the poles, where u is undefined
      const glm::vec2 back = envmap_uv(envmap_direction(uv, rotate), rotate);
      const float du = std::abs(back.x - uv.x);
      EXPECT_LT(std::min(du, 1.0f - du), 2e-5f) << uv.x << " rotate " << rotate;
      EXPECT_NEAR(back.y, uv.y, 2e-5f);
    }
}

// ---------------------------------------------------------------------------
// The density.

// The density integrates to 1 over the sphere: the midpoint rule in
// (theta, phi) with the solid-angle measure d omega = sin theta d theta d phi,
// which does not go through the (u, v) parametrisation that the functions
// use. 1024 x 1024 cells, 64 rows of cells per texel row: the integrand
// pdf x sin theta is constant within a texel (sin theta cancels), so the
// result is 1 to float rounding (bound 1e-4); a wrong Jacobian, a wrong scale
// or texels read from the wrong place are off by percents.
double integral_over_sphere(const EnvmapImage& map, const EnvmapTables& t, float rotate, double theta0,
                            double theta1, double phi0, double phi1, int n) {
  double sum = 0.0;
  const double dt = (theta1 - theta0) / n, dp = (phi1 - phi0) / n;
  for (int i = 0; i < n; ++i) {
    const double theta = theta0 + (i + 0.5) * dt;
    for (int j = 0; j < n; ++j) {
      const double phi = phi0 + (j + 0.5) * dp;
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      sum += envmap_pdf(map, t, rotate, d) * std::sin(theta) * dt * dp;
    }
  }
  return sum;
}

TEST(Envmap, PdfIntegratesToOneOverTheSphere) {
  for (float rotate : {0.0f, 100.0f}) {
    const EnvmapImage map = test_map();
    const EnvmapTables t = build_envmap_tables(map);
    EXPECT_NEAR(integral_over_sphere(map, t, rotate, 0.0, kPi, 0.0, 2.0 * kPi, 1024), 1.0, 1e-4) << "rotate " << rotate;
  }
}

// The same for the sampling side, bin by bin: 200,000 directions from
// envmap_sample, in 16 x 8 equal-area bins of (phi, cos theta), against the
// probability envmap_pdf gives each bin (integral_over_sphere, 64 x 64 cells
// per bin). Pearson's chi-square with the bins of expected count < 5 merged;
// the bound is the 1 - 1e-4 quantile of chi-square with (bins - 1) degrees of
// freedom (Wilson-Hilferty approximation): a correct sampler fails it once in
// 10,000 seeds, and the seed is fixed. A sampler off by one texel, or whose
// pdf misses the sin theta, fails it by orders of magnitude.
TEST(Envmap, SampledDirectionsFollowThePdf) {
  const EnvmapImage map = test_map();
  const float rotate = 45.0f;
  const EnvmapTables t = build_envmap_tables(map);
  constexpr int kPhi = 16, kZ = 8, kSub = 64, kSamples = 200000;
  auto bin_of = [&](glm::vec3 d) {
    double phi = std::atan2(double(d.z), double(d.x));
    if (phi < 0) phi += 2.0 * kPi;
    const int b = std::min(int(phi / (2.0 * kPi) * kPhi), kPhi - 1);
    const int a = std::clamp(int((double(d.y) + 1.0) / 2.0 * kZ), 0, kZ - 1);
    return a * kPhi + b;
  };
  std::vector<double> expected(kPhi * kZ, 0.0), observed(kPhi * kZ, 0.0);
  for (int a = 0; a < kZ; ++a)
    for (int b = 0; b < kPhi; ++b)
      expected[a * kPhi + b] = kSamples * integral_over_sphere(map, t, rotate, std::acos(-1.0 + 2.0 * (a + 1) / kZ),
                                                                std::acos(-1.0 + 2.0 * a / kZ), 2.0 * kPi * b / kPhi,
                                                                2.0 * kPi * (b + 1) / kPhi, kSub);
  for (uint32_t i = 0; i < kSamples; ++i) {
    glm::vec3 dir;
    float pdf;
    ASSERT_TRUE(envmap_sample(map, t, rotate, uniform2(i, 3), dir, pdf));
    ASSERT_TRUE(std::isfinite(pdf) && pdf > 0.0f);
    observed[bin_of(dir)] += 1.0;
  }
  double chi2 = 0.0, rest_e = 0.0, rest_o = 0.0;
  int bins = 0;
  for (size_t k = 0; k < expected.size(); ++k) {
    if (expected[k] < 5.0) {
      rest_e += expected[k], rest_o += observed[k];
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++bins;
  }
  if (rest_e > 0.0) chi2 += (rest_o - rest_e) * (rest_o - rest_e) / rest_e, ++bins;
  const double df = bins - 1, z = 3.719;  // the standard normal's 1 - 1e-4 quantile
  const double bound = df * std::pow(1.0 - 2.0 / (9.0 * df) + z * std::sqrt(2.0 / (9.0 * df)), 3.0);
  EXPECT_LT(chi2, bound) << bins << " bins";
}

// envmap_sample's pdf is envmap_pdf of the direction it returns (the two
// functions are one density). Rounding can move a direction that lies on a
// texel's edge into the neighbour, so the comparison skips samples within
// 1e-3 texel of an edge; every other one agrees to float rounding (1e-4).
TEST(Envmap, SampleAndPdfAgree) {
  const EnvmapImage map = test_map();
  const EnvmapTables t = build_envmap_tables(map);
  int compared = 0;
  for (uint32_t i = 0; i < 20000; ++i) {
    glm::vec3 dir;
    float pdf;
    ASSERT_TRUE(envmap_sample(map, t, 30.0f, uniform2(i, 5), dir, pdf));
    const glm::vec2 uv = envmap_uv(dir, 30.0f);
    const float fx = uv.x * 32.0f - std::floor(uv.x * 32.0f), fy = uv.y * 16.0f - std::floor(uv.y * 16.0f);
    if (std::min({fx, 1.0f - fx, fy, 1.0f - fy}) < 1e-3f) continue;
    EXPECT_NEAR(envmap_pdf(map, t, 30.0f, dir) / pdf, 1.0f, 1e-4f);
    ++compared;
  }
  EXPECT_GT(compared, 19000);
}

// A black map has nothing to sample: no sample, pdf 0 everywhere, no NaN.
TEST(Envmap, BlackMapGivesNoSample) {
  const EnvmapImage map{8, 4, std::vector<float>(8 * 4 * 3, 0.0f)};
  const EnvmapTables t = build_envmap_tables(map);
  EXPECT_EQ(t.marginal[5], 0.0f);
  for (uint32_t i = 0; i < 100; ++i) {
    glm::vec3 dir;
    float pdf = -1.0f;
    EXPECT_FALSE(envmap_sample(map, t, 0.0f, uniform2(i, 1), dir, pdf));
    EXPECT_EQ(pdf, 0.0f);
    EXPECT_EQ(envmap_pdf(map, t, 0.0f, glm::normalize(glm::vec3(uniform2(i, 2), 0.3f))), 0.0f);
  }
}

// A sun: one bright texel in a black map. Every sample lands in it, and the
// mean of 1 / pdf estimates the texel's solid angle (2 pi / W)(cos theta0 -
// cos theta1): the density varies inside the texel only as sin(row centre) /
// sin theta, so 10,000 samples estimate it to ~1e-4; bound 1e-3.
TEST(Envmap, SunTexelIsFoundAndItsDensityIntegratesToOne) {
  const EnvmapImage map = one_texel(64, 32, 40, 9, 1e5f);
  const EnvmapTables t = build_envmap_tables(map);
  double inverse = 0.0;
  constexpr int kN = 10000;
  for (uint32_t i = 0; i < kN; ++i) {
    glm::vec3 dir;
    float pdf;
    ASSERT_TRUE(envmap_sample(map, t, 0.0f, uniform2(i, 9), dir, pdf));
    const glm::uvec2 texel = envmap_texel(envmap_uv(dir, 0.0f), 64, 32);
    // A sample on the texel's edge may round into the neighbour; none lands farther.
    EXPECT_LE(std::abs(int(texel.x) - 40), 1);
    EXPECT_LE(std::abs(int(texel.y) - 9), 1);
    inverse += 1.0 / pdf;
  }
  const double solid_angle = 2.0 * kPi / 64.0 * (std::cos(kPi * 9.0 / 32.0) - std::cos(kPi * 10.0 / 32.0));
  EXPECT_NEAR(inverse / kN / solid_angle, 1.0, 1e-3);
}

// Texels at the poles: sin theta -> 0. A map lit only in its top row is
// sampled there with finite densities; the pole itself (v = 0 exactly,
// sin theta = 0) is no sample, and its pdf is 0, not NaN or Inf.
TEST(Envmap, PoleTexelsGiveFiniteDensities) {
  EnvmapImage map{16, 8, std::vector<float>(16 * 8 * 3, 0.0f)};
  for (size_t i = 0; i < 16 * 3; ++i) map.rgb[i] = 3.0f;
  const EnvmapTables t = build_envmap_tables(map);
  for (uint32_t i = 0; i < 5000; ++i) {
    glm::vec3 dir;
    float pdf;
    if (!envmap_sample(map, t, 0.0f, uniform2(i, 4), dir, pdf)) continue;
    EXPECT_TRUE(std::isfinite(pdf) && pdf > 0.0f);
    EXPECT_GE(dir.y, std::cos(float(kPi) / 8.0f) - 1e-6f);
  }
  glm::vec3 dir;
  float pdf = -1.0f;
  EXPECT_FALSE(envmap_sample(map, t, 0.0f, {0.5f, 0.0f}, dir, pdf));
  EXPECT_EQ(pdf, 0.0f);
  EXPECT_EQ(envmap_pdf(map, t, 0.0f, {0, 1, 0}), 0.0f);
  EXPECT_EQ(envmap_uv({0, 1, 0}, 90.0f), glm::vec2(0.25f, 0.0f));  // u = rotate / 360 at a pole
  EXPECT_EQ(envmap_pdf(map, t, 0.0f, {0, -1, 0}), 0.0f);
}

// ---------------------------------------------------------------------------
// Loading.

Image to_image(const EnvmapImage& m) { return {int(m.width), int(m.height), m.rgb}; }

TEST(Envmap, LoadsExrAndHdr) {
  const std::string folder = fresh_folder();
  EnvmapImage m = test_map();
  write_image(to_image(m), folder + "/sky.exr");
  EXPECT_EQ(load_envmap(folder + "/sky.exr"), m);
  // Radiance RGBE keeps 8 bits of mantissa per channel (a shared exponent):
  // within 1/128 of the largest channel of each texel.
  const std::string hdr = folder + "/sky.hdr";
  ASSERT_TRUE(stbi_write_hdr(hdr.c_str(), 32, 16, 3, m.rgb.data()));
  const EnvmapImage back = load_envmap(hdr);
  ASSERT_EQ(back.width, 32u);
  ASSERT_EQ(back.height, 16u);
  for (size_t i = 0; i < m.rgb.size(); ++i) {
    const float* texel = &m.rgb[i / 3 * 3];
    EXPECT_NEAR(back.rgb[i], m.rgb[i], std::max({texel[0], texel[1], texel[2]}) / 128.0f) << i;
  }
}

TEST(Envmap, BadFilesAreOneLineErrorsNamingTheFile) {
  const std::string folder = fresh_folder();
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/missing.exr"); }).rfind(folder + "/missing.exr: ", 0), 0u);
  for (auto [value, what] : {std::pair{std::nanf(""), "NaN"}, std::pair{INFINITY, "infinite"}}) {
    EnvmapImage m = one_texel(4, 2, 1, 1, 1.0f);
    m.rgb[3 * 6 + 1] = value;  // texel (2, 1), green
    write_image(to_image(m), folder + "/bad.exr");
    EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/bad.exr"); }),
              folder + "/bad.exr: texel (2, 1) is " + what + " (an environment map needs finite radiance >= 0)");
  }
  EnvmapImage m = one_texel(4, 2, 1, 1, 1.0f);
  m.rgb[3 * 6 + 1] = -0.25f;  // texel (2, 1), green
  m.rgb[3 * 7 + 2] = -0.5f;   // texel (3, 1), blue
  write_image(to_image(m), folder + "/bad.exr");
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/bad.exr"); }),
            folder + "/bad.exr: 2 texel channels are negative, the first at texel (2, 1), the lowest -0.5 (an "
                     "environment map needs finite radiance >= 0)");
  // A truncated EXR and truncated or malformed .hdr files.
  write_image(to_image(test_map()), folder + "/whole.exr");
  std::string bytes;
  {
    std::ifstream in(folder + "/whole.exr", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(folder + "/cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/cut.exr"); }).rfind(folder + "/cut.exr: not a valid EXR file: ", 0), 0u);
  const std::string hdr = folder + "/sky.hdr";
  ASSERT_TRUE(stbi_write_hdr(hdr.c_str(), 32, 16, 3, test_map().rgb.data()));
  {
    std::ifstream in(hdr, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(folder + "/cut.hdr", std::ios::binary) << bytes.substr(0, bytes.size() - 20);
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/cut.hdr"); }),
            folder + "/cut.hdr: not a valid Radiance HDR file: truncated at scanline 15");
  std::ofstream(folder + "/zero.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 8\n";
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/zero.hdr"); }),
            folder + "/zero.hdr: not a valid Radiance HDR file: bad size 8x0");
  std::ofstream(folder + "/flat.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\nabcd";
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/flat.hdr"); }),
            folder + "/flat.hdr: not a valid Radiance HDR file: truncated pixel data (expected 32 bytes)");
  std::ofstream(folder + "/text.hdr", std::ios::binary) << "P3 1 1 255\n0 0 0\n";
  EXPECT_EQ(test::input_error([&] { load_envmap(folder + "/text.hdr"); }),
            folder + "/text.hdr: not a valid Radiance HDR file: does not start with \"#?RADIANCE\" or \"#?RGBE\"");
}

// ---------------------------------------------------------------------------
// The JSON sky: the file is found relative to the scene file, written back as
// given, and bad values name the field.

TEST(Envmap, JsonSkyLoadsTheFileRelativeToTheScene) {
  const std::string folder = fresh_folder();
  fs::create_directories(folder + "/maps");
  write_image(to_image(test_map()), folder + "/maps/sky.exr");
  const std::string json = R"({"sky": {"type": "envmap", "file": "maps/sky.exr", "strength": 2.5, "rotate": -30},
                               "materials": []})";
  const Scene s = parse_scene_json(json, folder + "/scene.json");
  EXPECT_EQ(s.sky.type, SkyType::Envmap);
  EXPECT_EQ(s.sky.file, "maps/sky.exr");
  EXPECT_EQ(s.sky.strength, 2.5f);
  EXPECT_EQ(s.sky.rotate, -30.0f);
  EXPECT_EQ(s.sky.image, test_map());
  const std::string written = scene_to_json(s);
  EXPECT_NE(written.find(R"("sky": {"type": "envmap", "file": "maps/sky.exr", "strength": 2.5, "rotate": -30})"),
            std::string::npos)
      << written;
  EXPECT_EQ(parse_scene_json(written, folder + "/again.json"), s);
  // Defaults: strength 1, rotate 0.
  const Scene d = parse_scene_json(R"({"sky": {"type": "envmap", "file": "maps/sky.exr"}, "materials": []})",
                                   folder + "/scene.json");
  EXPECT_EQ(d.sky.strength, 1.0f);
  EXPECT_EQ(d.sky.rotate, 0.0f);
}

TEST(Envmap, JsonSkyErrorsNameTheField) {
  const std::string folder = fresh_folder();
  write_image(to_image(test_map()), folder + "/sky.exr");
  const auto error = [&](const std::string& sky) {
    return test::input_error([&] { parse_scene_json(R"({"sky": )" + sky + R"(, "materials": []})", folder + "/s.json"); });
  };
  const std::string s = folder + "/s.json";
  EXPECT_EQ(error(R"({"type": "envmap"})"), s + ": sky.file: missing required field");
  EXPECT_EQ(error(R"({"type": "envmap", "file": 3})"), s + ": sky.file: expected a file name (a non-empty string), got 3");
  EXPECT_EQ(error(R"({"type": "envmap", "file": "sky.exr", "strength": -1})"),
            s + ": sky.strength: must be a finite number >= 0, got -1");
  EXPECT_EQ(error(R"({"type": "envmap", "file": "sky.exr", "radiance": [1, 1, 1]})").rfind(s + ": sky.radiance: unknown key", 0), 0u);
  EXPECT_EQ(error(R"({"type": "envmap", "file": "nope.exr"})").rfind(folder + "/nope.exr: ", 0), 0u);
}

}  // namespace
}  // namespace octrace
