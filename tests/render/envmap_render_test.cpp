// The environment map on the device: the GLSL sampling functions agree with
// the host mirror (scene/envmap.h), the orientation convention holds in
// rendered images (a lone texel appears where the written convention says,
// up is up, rotate turns the stated way), and camera rays see exactly what
// the host's convention predicts.
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "envmap_probe.h"
#include "render/camera.h"
#include "render/gpu_scene.h"
#include "scene/envmap.h"
#include "shared/rng.h"
#include "test_util.h"
#include "vk/resources.h"

namespace octrace {
namespace {

class EnvmapRenderTest : public test::VulkanTest {};

constexpr double kPi = 3.14159265358979323846;

Scene sky_only(Sky sky, glm::vec3 look, float vfov) {
  Scene s;
  s.sky = std::move(sky);
  s.camera.lookfrom = {0, 0, 0};
  s.camera.lookat = look;
  s.camera.vup = {0, 1, 0};
  s.camera.vfov = vfov;
  s.camera.aperture = 0;
  s.camera.focus_dist = 1;
  return s;
}

RenderSettings small(int w, int h, uint32_t spp, uint32_t depth = 50) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.spp = spp;
  s.bounce_limit = depth;
  return s;
}

// The GLSL envmap_sample, envmap_pdf and envmap_radiance (through the probe
// shader and the scene's real upload) against the host mirror, on 4096 draws
// of the same random numbers. The sampled texel and its density are the same
// arithmetic on both sides (the CDFs are the same floats): directions agree
// to 1e-5 and densities to 1e-4 relative (the device's sin, cos and atan are
// not libm's, a few ulp); so do the map coordinates of the device's
// direction, to 1e-5. envmap_pdf and the radiance of the device's
// direction are compared away from texel edges (1e-3 texel), where such an
// ulp can pick the neighbour. The poles, where the azimuth is undefined,
// read a defined texel and have density 0.
TEST_F(EnvmapRenderTest, ShaderSamplingAgreesWithTheHost) {
  VulkanContext& ctx = test::shared_context();
  Scene scene;
  scene.sky = test::envmap_sky(test::test_envmap(48, 24, 2000.0f), 1.5f, 70.0f);
  // A black row and a bright pole row: zero-probability rows and sin theta -> 0.
  for (uint32_t x = 0; x < 48; ++x)
    for (int k = 0; k < 3; ++k) {
      scene.sky.image.rgb[3 * (10 * 48 + x) + k] = 0.0f;
      scene.sky.image.rgb[3 * x + k] = 40.0f;
    }
  GpuScene g;
  upload_scene(g, ctx, scene, Accel::Brute, {});
  constexpr uint32_t kN = 4096;
  Buffer out;
  create_buffer(out, ctx, (kN * 3 + 2) * sizeof(glm::vec4), false, "probe output");
  ComputePipeline p;
  create_compute_pipeline(p, ctx, envmap_probe_spv, sizeof(envmap_probe_spv), 5, 0);
  bind_buffers(p, {{0, &g.params}, {1, &g.envmap_texels}, {2, &g.envmap_marginal}, {3, &g.envmap_conditional}, {4, &out}});
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);
    vkCmdDispatch(cmd, kN / 64, 1, 1);
    compute_barrier(cmd);
  });
  std::vector<glm::vec4> gpu(kN * 3 + 2);
  download_buffer(ctx, out, gpu.data(), gpu.size() * sizeof(glm::vec4));

  const Sky& sky = scene.sky;
  const EnvmapTables tables = build_envmap_tables(sky.image);
  int away_from_edges = 0, sampled = 0;
  for (uint32_t i = 0; i < kN; ++i) {
    gpu::Rng rng = gpu::rng_init(11, i, 0, 0);
    const float u0 = gpu::rng_next(rng);
    const glm::vec2 u(u0, gpu::rng_next(rng));
    glm::vec3 dir;
    float pdf;
    const bool ok = envmap_sample(sky.image, tables, sky.rotate, u, dir, pdf);
    ASSERT_EQ(gpu[3 * i + 1].y == 1.0f, ok) << "draw " << i;
    if (!ok) continue;
    ++sampled;
    const glm::vec3 gdir(gpu[3 * i]);
    EXPECT_LT(glm::length(gdir - dir), 1e-5f) << "draw " << i;
    EXPECT_NEAR(gpu[3 * i].w / pdf, 1.0f, 1e-4f) << "draw " << i;
    // envmap_uv: within 1e-5 of the exact map coordinate of the device's
    // direction (measured: 5e-7 in u, 1e-6 in v; acos in place of atan was
    // 5e-5 in v).
    const glm::dvec3 d(gdir);
    double exact_u = std::atan2(-d.x, d.z) / (2.0 * kPi) + sky.rotate / 360.0;
    exact_u -= std::floor(exact_u);
    const double du = std::abs(exact_u - gpu[3 * i + 1].z);
    EXPECT_LT(std::min(du, 1.0 - du), 1e-5) << "draw " << i;
    EXPECT_NEAR(gpu[3 * i + 1].w, std::acos(d.y / glm::length(d)) / kPi, 1e-5) << "draw " << i;
    // envmap_pdf and the radiance of the device's direction, on both sides.
    const glm::vec2 uv = envmap_uv(gdir, sky.rotate);
    const float fx = uv.x * 48.0f - std::floor(uv.x * 48.0f), fy = uv.y * 24.0f - std::floor(uv.y * 24.0f);
    if (std::min({fx, 1.0f - fx, fy, 1.0f - fy}) < 1e-3f) continue;
    ++away_from_edges;
    EXPECT_NEAR(gpu[3 * i + 1].x / envmap_pdf(sky.image, tables, sky.rotate, gdir), 1.0f, 1e-4f) << "draw " << i;
    const glm::uvec2 t = envmap_texel(uv, 48, 24);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(gpu[3 * i + 2][k], sky.strength * sky.image.rgb[3 * (t.y * 48 + t.x) + k]) << "draw " << i;
  }
  EXPECT_EQ(sampled, int(kN));
  // The poles: u is 0 there (atan(0, 0) is undefined), the radiance that of
  // the top or bottom row's texel at u = rotate / 360, the pdf 0 (sin theta = 0).
  const uint32_t pole_x = uint32_t(sky.rotate / 360.0f * 48.0f);
  for (int j = 0; j < 2; ++j) {
    const glm::vec4 pole = gpu[3 * kN + j];
    const uint32_t row = j == 0 ? 0 : 23;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(pole[k], sky.strength * sky.image.rgb[3 * (row * 48 + pole_x) + k]) << "pole " << j;
    EXPECT_EQ(pole.w, 0.0f) << "pole " << j;
  }
  EXPECT_GT(away_from_edges, int(kN * 95 / 100));
}

// A black map but for one texel whose centre lies, by the written convention,
// towards +x and 45 degrees up: u = 0.75 (+x), v = 0.25. On a 30 x 30 map that
// is texel (22, 7). A camera at the origin looking that way sees it in the
// centre of the image; with rotate 90 the map turns counter-clockwise seen
// from above, +x to -z; with rotate -90 to +z. The brightness-weighted centroid
// of the image must be within 0.5 pixel of the centre: the texel spans about
// 8 x 12 pixels here, and a mirrored u or v, or the other rotation sense, puts
// it out of the picture (the centroid of a black image fails too: it is NaN).
TEST_F(EnvmapRenderTest, ALoneTexelAppearsWhereTheConventionSays) {
  EnvmapImage map{30, 30, std::vector<float>(30 * 30 * 3, 0.0f)};
  for (int k = 0; k < 3; ++k) map.rgb[3 * (7 * 30 + 22) + k] = 1.0f;
  const float s = std::sqrt(0.5f);
  for (auto [rotate, look] : {std::pair{0.0f, glm::vec3(s, s, 0)}, std::pair{90.0f, glm::vec3(0, s, -s)},
                              std::pair{-90.0f, glm::vec3(0, s, s)}}) {
    const RenderResult r = render(test::shared_context(), sky_only(test::envmap_sky(map, 1.0f, rotate), look, 40.0f),
                                  small(64, 64, 16, 1));
    double sum = 0, sx = 0, sy = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const double v = r.mean.pixel(x, y)[0];
        sum += v, sx += v * (x + 0.5), sy += v * (y + 0.5);
      }
    EXPECT_NEAR(sx / sum, 32.0, 0.5) << "rotate " << rotate;
    EXPECT_NEAR(sy / sum, 32.0, 0.5) << "rotate " << rotate;
  }
}

// Up is up for bounced rays too: a lambertian sphere under a map that is
// white above the horizon (v < 0.5) and black below is lit from above: its
// top row of pixels is bright, its bottom row nearly black. A point at the
// top of the sphere sees only the upper hemisphere (value = albedo 0.5); one
// at the bottom only the lower (0).
TEST_F(EnvmapRenderTest, UpIsUpForDiffuseLight) {
  EnvmapImage map{8, 4, std::vector<float>(8 * 4 * 3, 0.0f)};
  std::fill(map.rgb.begin(), map.rgb.begin() + 8 * 2 * 3, 1.0f);
  Scene s = sky_only(test::envmap_sky(map), {0, 0, -1}, 30.0f);
  s.camera.lookfrom = {0, 0, 5};
  s.camera.lookat = {0, 0, 0};
  s.materials = {test::lambertian(0.5f)};
  s.spheres = {{{0, 0, 0}, 1, 0}};
  const RenderResult r = render(test::shared_context(), s, small(32, 32, 64));
  // The sphere spans rows 3.9 to 28.1 at this field of view: rows 5 and 26
  // see its normal about 65 degrees above and below the horizon, where the
  // upper hemisphere gives (1 + sin 65) / 2 = 95% and 5% of the cosine-weighted
  // light: 0.48 and 0.02 (64 samples: a standard error below 0.02).
  double top = 0, bottom = 0;
  for (int x = 14; x < 18; ++x) top += r.mean.pixel(x, 5)[0] / 4, bottom += r.mean.pixel(x, 26)[0] / 4;
  EXPECT_GT(top, 0.4);
  EXPECT_LT(bottom, 0.1);
}

// Light from the map, against physics: a lambertian sphere (albedo 0.5)
// under test::test_envmap (turned by 30 degrees), at depth 2 (a path hits
// the convex sphere once and escapes), reflects albedo / pi x the irradiance
// E(n) = integral of L(w) max(0, n.w) dw. The host integrates E over the map
// (8 x 8 points per texel, dw = sin theta dtheta dphi) at 4 x 4 points of
// each pixel wholly on the sphere (the camera's jitter is uniform over the
// pixel); the image mean over those pixels must match within 5 standard
// errors of the render's mean (from its per-pixel variances) plus 2e-3 of
// the value for the quadrature. A mirrored or misplaced lookup of bounced
// rays, or a wrong strength, is off by percents (the map is brighter and
// bluer above, with a ripple in u).
TEST_F(EnvmapRenderTest, DiffuseSphereReflectsTheMapsIrradiance) {
  const Sky sky = test::envmap_sky(test::test_envmap(16, 8), 1.5f, 30.0f);
  Scene s = sky_only(sky, {0, 0, 0}, 14.0f);
  s.camera.lookfrom = {2, 3, 9};
  s.materials = {test::lambertian(0.5f)};
  s.spheres = {{{0, 0, 0}, 1, 0}};
  constexpr int kSize = 32, kSub = 4, kTexelSub = 8;
  const RenderResult r = render(test::shared_context(), s, small(kSize, kSize, 256, 2));
  // The map as directions with radiance x solid angle.
  std::vector<std::pair<glm::dvec3, glm::dvec3>> light;
  for (int y = 0; y < 8 * kTexelSub; ++y)
    for (int x = 0; x < 16 * kTexelSub; ++x) {
      const glm::vec2 uv((x + 0.5f) / (16 * kTexelSub), (y + 0.5f) / (8 * kTexelSub));
      const glm::dvec3 w(envmap_direction(uv, sky.rotate));
      const double dw = (2.0 * kPi / (16 * kTexelSub)) * (kPi / (8 * kTexelSub)) * std::sin(kPi * uv.y);
      const glm::uvec2 t = envmap_texel(uv, 16, 8);
      light.push_back({w, dw * double(sky.strength) * glm::dvec3(glm::make_vec3(&sky.image.rgb[3 * (t.y * 16 + t.x)]))});
    }
  const CameraFrame frame = camera_frame(s.camera, kSize, kSize);
  const glm::dvec3 o(s.camera.lookfrom);
  auto normal_at = [&](double x, double y, glm::dvec3& n) {
    const glm::dvec3 d = glm::normalize(frame.dir(x, y));
    const double t = test::ray_sphere(o, d, glm::dvec3(0.0), 1.0);
    if (!std::isfinite(t)) return false;
    n = glm::normalize(o + t * d);
    return true;
  };
  glm::dvec3 expected(0.0), measured(0.0), variance(0.0);
  int pixels = 0;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      glm::dvec3 n;
      bool inside = true;
      for (int corner = 0; corner < 4; ++corner) inside &= normal_at(px + (corner & 1), py + (corner >> 1), n);
      if (!inside) continue;
      ++pixels;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          normal_at(px + (i + 0.5) / kSub, py + (j + 0.5) / kSub, n);
          glm::dvec3 e(0.0);
          for (const auto& [w, l] : light) e += l * std::max(0.0, glm::dot(n, w));
          expected += 0.5 / kPi * e / double(kSub * kSub);
        }
      for (int c = 0; c < 3; ++c) {
        measured[c] += r.mean.pixel(px, py)[c];
        variance[c] += r.variance_of_mean.pixel(px, py)[c];
      }
    }
  ASSERT_GT(pixels, 300);
  for (int c = 0; c < 3; ++c) {
    const double e = expected[c] / pixels, m = measured[c] / pixels, sigma = std::sqrt(variance[c]) / pixels;
    EXPECT_LE(std::abs(m - e), 5.0 * sigma + 2e-3 * e) << "channel " << c << ": measured " << m << ", expected " << e
                                                       << ", sigma " << sigma;
  }
}

// Camera rays see exactly the host's prediction: the shader's camera jitter
// is replayed on the host (shared/rng.h, render/camera.h), each ray's
// direction looked up in the map by the host's convention (scene/envmap.h),
// and the mean of 4 samples compared with the rendered pixel. Every pixel
// agrees to 1e-5 relative but those with a sample within float rounding of a
// texel edge (the host's direction is double, the device's float), at most
// 1% of the pixels.
TEST_F(EnvmapRenderTest, CameraRaysSeeTheHostsPrediction) {
  const Sky sky = test::envmap_sky(test::test_envmap(48, 24, 100.0f), 2.0f, 30.0f);
  const Scene s = sky_only(sky, {-0.3f, 0.4f, -1.0f}, 70.0f);
  constexpr int kW = 64, kH = 48;
  constexpr uint32_t kSpp = 4;
  const RenderResult r = render(test::shared_context(), s, small(kW, kH, kSpp, 1));
  const CameraFrame frame = camera_frame(s.camera, kW, kH);
  int differing = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      glm::dvec3 sum(0.0);
      for (uint32_t k = 0; k < kSpp; ++k) {
        gpu::Rng rng = gpu::rng_init(1, uint32_t(y * kW + x), k, gpu::CAMERA_BOUNCE);
        const float jx = gpu::rng_next(rng);
        const float jy = gpu::rng_next(rng);
        const glm::vec3 d(glm::normalize(frame.dir(x + jx, y + jy)));
        const glm::uvec2 t = envmap_texel(envmap_uv(d, sky.rotate), 48, 24);
        sum += glm::dvec3(sky.strength * glm::make_vec3(&sky.image.rgb[3 * (t.y * 48 + t.x)]));
      }
      const glm::dvec3 expected = sum / double(kSpp);
      for (int c = 0; c < 3; ++c)
        if (std::abs(r.mean.pixel(x, y)[c] - expected[c]) > 1e-5 * expected[c]) {
          ++differing;
          break;
        }
    }
  EXPECT_LE(differing, kW * kH / 100);
}

// A map whose texels do not fit one storage buffer is an input error naming
// the file and the sizes, raised before anything is rendered (the CLI prints
// it as one line and exits 2). lavapipe allows 128 MiB: 4800 x 2400 texels of
// 12 bytes are 132 MiB. Devices with a larger limit would need a map of
// gigabytes: skipped there.
TEST_F(EnvmapRenderTest, AMapLargerThanAStorageBufferIsAnInputError) {
  VulkanContext& ctx = test::shared_context();
  if (ctx.limits.maxStorageBufferRange > (256u << 20)) GTEST_SKIP() << "the device allows more than 256 MiB per buffer";
  const uint32_t w = 4800, h = 2400;
  ASSERT_GT(uint64_t(w) * h * 12, ctx.limits.maxStorageBufferRange);
  Scene s;
  s.sky = test::envmap_sky(EnvmapImage{w, h, std::vector<float>(size_t(w) * h * 3, 0.5f)});
  GpuScene g;
  EXPECT_EQ(test::input_error([&] { upload_scene(g, ctx, s, Accel::Brute, {}); }),
            "test.exr: the environment map's 4800x2400 texels need 132 MiB, the device allows 128 MiB per buffer");
}

// The fp16 variants carry the sky's radiance in half: a map whose strength x
// brightest texel exceeds 65504 is refused for them, by name; fp32 takes it.
TEST(Envmap, Fp16RefusesAMapBeyondHalf) {
  Scene s;
  s.sky = test::envmap_sky(test::test_envmap(8, 4, 40000.0f), 2.0f);
  EXPECT_EQ(test::input_error([&] { check_precision(s, Precision::FP16); }),
            "precision fp16: sky: test.exr: strength x brightest texel = 80000 is above 65504 and does not fit half "
            "(use --precision fp32)");
  EXPECT_NO_THROW(check_precision(s, Precision::FP32));
  s.sky.strength = 1.0f;
  EXPECT_NO_THROW(check_precision(s, Precision::FP16All));
}

}  // namespace
}  // namespace octrace
