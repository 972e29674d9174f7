// Renders held against physics and against themselves.
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "accel/bvh.h"
#include "render/camera.h"
#include "render/gpu_scene.h"
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

// A field of pbr spheres (tools/scenes/pbr_field.json, also the scene of the
// pbr accuracy report) gives no NaN or Inf sample in any precision: the fp16
// variants once overflowed an intermediate factor of the sample weight.
TEST_F(RenderTest, PbrFieldHasNoNonFiniteSamplesInAnyPrecision) {
  const Scene scene = load_scene_json(std::string(OCTRACE_SOURCE_DIR) + "/tools/scenes/pbr_field.json");
  for (Precision p : {Precision::FP32, Precision::FP16, Precision::FP16All}) {
    RenderSettings s;
    s.width = 200;
    s.height = 112;
    s.spp = 256;
    s.precision = p;
    const RenderResult r = render(test::shared_context(), scene, s);
    EXPECT_EQ(r.nonfinite_samples, 0u) << precision_name(p);
  }
}

// Another sample seed gives other noise (and the same scene).
TEST_F(RenderTest, SampleSeedChangesTheNoise) {
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderResult a = render_small(scene, 2, 50, 1);
  RenderResult b = render_small(scene, 2, 50, 2);
  EXPECT_NE(std::memcmp(a.mean.rgb.data(), b.mean.rgb.data(), a.mean.rgb.size() * sizeof(float)), 0);
}

bool same_bits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

// 40 spheres of the book's scene, and an icosphere among them where `mesh`.
Scene spheres_and_icosphere(bool mesh = true) {
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  if (mesh) test::place(scene, test::icosphere(2, 1, true), glm::translate(glm::mat4(1.0f), glm::vec3(2, 1, 2)));
  return scene;
}

// Every bit of a render's result as another's: mean, variance, sample and
// ray counts, and the NaN/Inf samples rejected.
void expect_same_result(const RenderResult& got, const RenderResult& want) {
  EXPECT_TRUE(same_bits(got.mean, want.mean));
  EXPECT_TRUE(same_bits(got.variance_of_mean, want.variance_of_mean));
  EXPECT_EQ(got.count, want.count);
  EXPECT_EQ(got.rays, want.rays);
  EXPECT_EQ(got.nonfinite_samples, want.nonfinite_samples);
}

// read_result() resolves each buffer in the staging memory as it arrives
// (optimisation log 97): every bit as resolve_accumulation's of the
// buffers read back, including min_samples (a pixel below the others: a
// second batch over part of the samples is not possible, so the counts are
// set through write_accumulation).
TEST_F(RenderTest, ResultResolvedAsItArrivesIsTheAccumulationsResolved) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 37;
  s.height = 23;
  PathTracer tracer(ctx, scene, s);
  tracer.run_passes(pass_settings(scene, s), 0, 5);
  Accumulation acc = tracer.read_accumulation();
  acc.sum[100].w = 2.0f;  // fewer samples in one pixel, and one with none
  acc.sum[101].w = 0.0f;
  tracer.write_accumulation(acc);
  RenderResult want;
  resolve_accumulation(tracer.read_accumulation(), want);
  const RenderResult got = tracer.read_result();
  expect_same_result(got, want);
  EXPECT_EQ(got.min_samples, 0u);
  EXPECT_EQ(want.min_samples, 0u);
  EXPECT_GT(got.rays, 0u);
  EXPECT_EQ(got.variance_of_mean.rgb[3 * 101], 0.0f);
}

// How samples are split into dispatches and shared among invocations does
// not change a bit of the result: mean, variance, sample and ray counts
// (shaders/path_trace.comp main()). The image size is not a multiple of the
// workgroup's tile; one scene has spheres and a mesh, one spheres only (whose
// dispatches take whole rounds of lanes and the rest in fewer lanes:
// PathTracer::record_passes). `render` too, whose first batch has every lane.
TEST_F(RenderTest, BatchingAndSampleLanesDoNotChangeTheResult) {
  for (bool mesh : {true, false}) {
    Scene scene = spheres_and_icosphere(mesh);
    RenderSettings s;
    s.width = 45;
    s.height = 29;
    s.spp = 7;
    // The reference: one dispatch per sample, one invocation per pixel.
    s.samples_per_dispatch = 1;
    s.sample_lanes = 1;
    const RenderResult want = render(test::shared_context(), scene, s);
    const auto check = [&](const RenderResult& got, const std::string& what) {
      SCOPED_TRACE(std::string(mesh ? "spheres and a mesh, " : "spheres only, ") + what);
      expect_same_result(got, want);
      EXPECT_EQ(got.min_samples, 7u);
    };
    for (auto [per_dispatch, lanes] : {std::pair{0u, 0u}, {0u, 8u}, {0u, 4u}, {0u, 2u}, {3u, 4u}, {5u, 8u}, {2u, 1u}}) {
      s.samples_per_dispatch = per_dispatch;
      s.sample_lanes = lanes;
      PathTracer tracer(test::shared_context(), scene, s);
      tracer.run_passes(pass_settings(scene, s), 0, s.spp);  // all 7 in one batch
      check(tracer.read_result(), "samples per dispatch " + std::to_string(per_dispatch) + ", lanes " +
                                      std::to_string(lanes));
    }
    for (uint32_t lanes : {4u, 8u}) {
      s.samples_per_dispatch = 0;
      s.sample_lanes = lanes;
      check(render(test::shared_context(), scene, s), "render, lanes " + std::to_string(lanes));
    }
  }
}

// The tail queue (RenderSettings::tail_depth) splits a dispatch into head,
// tail and sum; the paths' arithmetic and the sum's order are those of the
// whole paths: every bit of the result is the same, whatever bounce the
// queue takes paths at, however the samples are batched, in fp32 and fp16,
// with roulette, with a queue too small for the paths (the head then
// finishes the rest itself), and with tail levels (RenderSettings::tail_step:
// a level's survivors queued again for the next, the last finishing them;
// at the bounce limit of 50 the levels stay below MAX_TAIL_LEVELS), and
// with a fill (RenderSettings::tail_fill) that has a level of few paths
// finish them.
TEST_F(RenderTest, TailQueueDoesNotChangeTheResult) {
  // RenderSettings::tail_subgroup's auto with the octree over triangles
  // (and the fill's), for the device the tests run on.
  const auto subgroup_auto = [] { return default_tail_subgroup(test::shared_context().info, true); };
  Scene scene = spheres_and_icosphere();
  Material light;
  light.type = MaterialType::Emissive;
  light.radiance = glm::vec3(6.0f, 5.0f, 4.0f);
  scene.materials.push_back(light);
  scene.spheres.push_back({{-1, 3, 1}, 0.5f, uint32_t(scene.materials.size() - 1)});
  for (Precision precision : {Precision::FP32, Precision::FP16}) {
    for (uint32_t rr : {0u, 2u}) {
      RenderSettings s;
      s.width = 37;
      s.height = 23;
      s.spp = 6;
      s.precision = precision;
      s.rr_depth = rr;
      s.tail_depth = 0;
      const RenderResult want = render(test::shared_context(), scene, s);
      ASSERT_EQ(want.tail_depth, 0u);
      // A fill of 300 paths finishes them in the level where fewer
      // than 300 are left (with 37 x 23 pixels, some levels on); 10^9 in
      // the first level. The subgroup stage (the last column; auto: the
      // device's resident subgroups times kTailSubgroupPaths where its
      // driver says, 0 on lavapipe) takes every level at 10^9, a level of
      // fewer than 100 or 50 paths, or the one tail.
      constexpr uint32_t kAuto = RenderSettings::kTailAuto;
      for (auto [depth, per_dispatch, lanes, entries, step, fill, subgroup] :
           {std::tuple{1u, 0u, 0u, 0u, 0u, 0u, kAuto}, {2u, 0u, 0u, 0u, 0u, 0u, kAuto}, {5u, 3u, 4u, 0u, 0u, 0u, kAuto},
            {2u, 5u, 8u, 0u, 0u, 0u, kAuto}, {1u, 0u, 2u, 64u, 0u, 0u, kAuto}, {3u, 0u, 0u, 1u, 0u, 0u, kAuto},
            {60u, 0u, 0u, 0u, 0u, 0u, kAuto}, {1u, 0u, 0u, 0u, 1u, 0u, kAuto}, {2u, 5u, 4u, 0u, 2u, 0u, kAuto},
            {1u, 0u, 2u, 64u, 1u, 0u, kAuto}, {2u, 0u, 0u, 1u, 3u, 0u, kAuto}, {1u, 0u, 0u, 0u, 1u, 300u, kAuto},
            {2u, 5u, 4u, 0u, 1u, 1000000000u, kAuto}, {1u, 0u, 2u, 64u, 1u, 40u, kAuto},
            {1u, 0u, 0u, 0u, 1u, 300u, 1000000000u}, {2u, 5u, 4u, 0u, 1u, 0u, 100u}, {2u, 0u, 2u, 64u, 1u, 300u, 50u},
            {3u, 0u, 0u, 0u, 0u, 0u, 1000000000u}, {1u, 0u, 0u, 0u, 1u, 300u, 0u}}) {
        s.tail_depth = depth;
        s.samples_per_dispatch = per_dispatch;
        s.sample_lanes = lanes;
        s.tail_queue_entries = entries;
        s.tail_step = step;
        s.tail_fill = fill;
        s.tail_subgroup = subgroup;
        SCOPED_TRACE(std::string(precision_name(precision)) + ", rr " + std::to_string(rr) + ", tail depth " +
                     std::to_string(depth) + ", per dispatch " + std::to_string(per_dispatch) + ", lanes " +
                     std::to_string(lanes) + ", queue " + std::to_string(entries) + ", step " +
                     std::to_string(step) + ", fill " + std::to_string(fill) + ", subgroup " +
                     std::to_string(subgroup));
        // A device whose subgroups cannot run the stage refuses a threshold.
        if (subgroup != kAuto && subgroup > 0 && !fits_tail_subgroup(test::shared_context().info.subgroup_size)) {
          EXPECT_THROW(render(test::shared_context(), scene, s), SettingError);
          continue;
        }
        const RenderResult got = render(test::shared_context(), scene, s);
        EXPECT_EQ(got.tail_depth, depth);
        EXPECT_EQ(got.tail_step, step);
        EXPECT_EQ(got.tail_fill, step ? fill : 0u);
        EXPECT_EQ(got.tail_subgroup, subgroup != kAuto ? subgroup : step ? subgroup_auto() : 0u);
        expect_same_result(got, want);
      }
    }
  }
  // The tail levels' auto: with triangles (this scene) levels of a step
  // of 1 where a fill applies (with the octree the subgroup stage's
  // threshold, with the BVH the device's resident threads, or one set),
  // one tail where none does (on a GPU: a CPU device takes levels
  // always); levels of a step of 1 for spheres alone; the same image
  // either way.
  {
    RenderSettings s;
    s.width = 37;
    s.height = 23;
    s.spp = 3;
    s.tail_depth = 2;
    const RenderResult device_fill = render(test::shared_context(), scene, s);
    const uint64_t resident = test::shared_context().info.resident_threads;
    const bool software = test::shared_context().info.software;
    EXPECT_EQ(device_fill.tail_step, resident > 0 || software ? kTailStepDefault : 0u);
    EXPECT_EQ(device_fill.tail_fill, subgroup_auto());
    EXPECT_EQ(device_fill.tail_subgroup, subgroup_auto());
    s.accel = Accel::Bvh;
    const RenderResult bvh_fill = render(test::shared_context(), scene, s);
    EXPECT_EQ(bvh_fill.tail_fill, resident > 0 ? std::min<uint64_t>(resident, UINT32_MAX) : 0u);
    EXPECT_EQ(bvh_fill.tail_subgroup, 0u);
    s.accel = Accel::Octree;
    s.tail_fill = 0;
    EXPECT_EQ(render(test::shared_context(), scene, s).tail_step, software ? kTailStepDefault : 0u);
    s.tail_fill = 500;
    const RenderResult set_fill = render(test::shared_context(), scene, s);
    EXPECT_EQ(set_fill.tail_step, kTailStepDefault);
    EXPECT_EQ(set_fill.tail_fill, 500u);
    s.tail_fill = RenderSettings::kTailAuto;
    Scene spheres = scene;
    spheres.meshes.clear();
    spheres.instances.clear();
    s.tail_step = 0;
    const RenderResult want = render(test::shared_context(), spheres, s);
    s.tail_step = RenderSettings::kTailAuto;
    const RenderResult got = render(test::shared_context(), spheres, s);
    EXPECT_EQ(got.tail_step, kTailStepDefault);
    EXPECT_EQ(got.tail_subgroup, 0u);  // spheres alone: the tail of before
    expect_same_result(got, want);
    // Spheres alone: the subgroup stage's lanes split the top level's
    // leaves too, in the closest-hit and the shadow rays' walks.
    for (uint32_t subgroup : {1000000000u, 200u}) {
      s.tail_subgroup = subgroup;
      SCOPED_TRACE("spheres alone, subgroup " + std::to_string(subgroup));
      if (!fits_tail_subgroup(test::shared_context().info.subgroup_size)) {
        EXPECT_THROW(render(test::shared_context(), spheres, s), SettingError);
        continue;
      }
      const RenderResult split = render(test::shared_context(), spheres, s);
      EXPECT_EQ(split.tail_subgroup, subgroup);
      expect_same_result(split, want);
    }
    s.tail_subgroup = RenderSettings::kTailAuto;
  }
  // The other structures' walks run in the same head and tail.
  for (Accel accel : {Accel::Bvh, Accel::Brute}) {
    RenderSettings s;
    s.width = 37;
    s.height = 23;
    s.spp = 4;
    s.accel = accel;
    s.tail_depth = 0;
    const RenderResult want = render(test::shared_context(), scene, s);
    s.tail_depth = 1;
    const RenderResult got = render(test::shared_context(), scene, s);
    SCOPED_TRACE(accel_name(accel));
    expect_same_result(got, want);
  }
}

// The tail stage's paths from a counter (RenderSettings::tail_fetch,
// shaders/path_trace.comp tail_fetch_paths): an invocation takes the next
// path when its own ends, so the same paths run in other invocations and
// the image is the same, bit for bit, through levels, a fill, the
// subgroup stage, a queue smaller than the paths and fp16. Auto: on a GPU
// with triangles or kTailFetchSpheresOctree spheres (kTailFetchSpheresBvh
// with the BVH), off for fewer spheres alone
// and without a tail queue; on a CPU
// device (llvmpipe cuts a loop after 65,535 iterations of an invocation)
// off, and On refused.
TEST_F(RenderTest, TailFetchDoesNotChangeTheResult) {
  const VulkanContext& ctx = test::shared_context();
  const Scene scene = spheres_and_icosphere();
  RenderSettings s;
  s.width = 37;
  s.height = 23;
  s.spp = 6;
  s.tail_depth = 1;
  s.tail_step = 1;
  s.tail_fill = 0;
  s.tail_fetch = TailFetch::On;
  if (ctx.info.software) {
    EXPECT_THROW(render(ctx, scene, s), SettingError);
    s.tail_fetch = TailFetch::Auto;
    EXPECT_FALSE(render(ctx, scene, s).tail_fetch);
    GTEST_SKIP() << "no tail fetch on a CPU device";
  }
  constexpr uint32_t kAuto = RenderSettings::kTailAuto;
  for (Precision precision : {Precision::FP32, Precision::FP16}) {
    for (auto [depth, entries, step, fill, subgroup] :
         {std::tuple{1u, 0u, 1u, 0u, 0u}, {2u, 0u, 1u, 300u, kAuto}, {1u, 64u, 1u, 0u, 0u}, {2u, 0u, 0u, 0u, 0u},
          {1u, 0u, 1u, 300u, 100u}}) {
      s.precision = precision;
      s.tail_depth = depth;
      s.tail_queue_entries = entries;
      s.tail_step = step;
      s.tail_fill = fill;
      s.tail_subgroup = subgroup;
      SCOPED_TRACE(std::string(precision_name(precision)) + ", tail depth " + std::to_string(depth) + ", queue " +
                   std::to_string(entries) + ", step " + std::to_string(step) + ", fill " + std::to_string(fill) +
                   ", subgroup " + std::to_string(subgroup));
      s.tail_fetch = TailFetch::Off;
      const RenderResult want = render(ctx, scene, s);
      EXPECT_FALSE(want.tail_fetch);
      s.tail_fetch = TailFetch::On;
      const RenderResult got = render(ctx, scene, s);
      EXPECT_TRUE(got.tail_fetch);
      expect_same_result(got, want);
      s.tail_fetch = TailFetch::Auto;
      EXPECT_TRUE(render(ctx, scene, s).tail_fetch);  // triangles on a GPU
    }
  }
  s = RenderSettings{};
  s.width = 37;
  s.height = 23;
  s.spp = 2;
  EXPECT_FALSE(render(ctx, spheres_and_icosphere(false), s).tail_fetch);  // few spheres alone
  // Spheres alone from the structure's count on: the auto takes it, the
  // same bits; the BVH not below its own.
  for (Accel accel : {Accel::Octree, Accel::Bvh}) {
    SCOPED_TRACE(accel_name(accel));
    s.accel = accel;
    const uint64_t from = accel == Accel::Bvh ? kTailFetchSpheresBvh : kTailFetchSpheresOctree;
    const Scene field = make_rtiow_scene({uint32_t(from) + 100u, 0.05f, 3});
    const RenderResult field_auto = render(ctx, field, s);
    EXPECT_TRUE(field_auto.tail_fetch);
    s.tail_fetch = TailFetch::Off;
    expect_same_result(field_auto, render(ctx, field, s));
    s.tail_fetch = TailFetch::Auto;
    if (accel == Accel::Octree) {
      s.accel = Accel::Bvh;
      EXPECT_FALSE(render(ctx, field, s).tail_fetch);  // below the BVH's count
    }
  }
  s.accel = Accel::Octree;
  s.tail_depth = 0;
  EXPECT_FALSE(render(ctx, scene, s).tail_fetch);  // no tail queue
}

// Light trapped in a mirror sphere (test::light_trap_scene) at 300
// bounces: paths of a hundred bounces and more, each
// bounce a walk of many steps. llvmpipe ends every loop of an 8-lane
// vector once 65,535 iterations of all its loops together have run, so
// the whole paths (a CPU device's default: a path an invocation) are cut
// short there, which RenderResult::cut_paths counts (path_trace.comp
// check_loop_limit); the tail levels, which trace a few bounces a
// dispatch, are not, and give the image a GPU gives with either; they are
// the auto on a CPU device above kCpuWholePathBounces bounces (whole paths
// up to it). A GPU has no such limit: nothing is cut, and both images are
// the same bit for bit. Fails where the check misses a cut path, or counts
// one that was not, or where the CPU auto at 300 bounces cuts paths.
TEST_F(RenderTest, PathsCutShortByTheLoopLimitAreCounted) {
  const VulkanContext& ctx = test::shared_context();
  const Scene scene = test::light_trap_scene();
  RenderSettings s;
  s.width = 80;
  s.height = 60;
  s.spp = 2;
  s.bounce_limit = 300;
  s.tail_depth = 0;  // whole paths, a path an invocation
  const RenderResult whole = render(ctx, scene, s);
  s.tail_depth = RenderSettings::kTailAuto;  // the tail levels on every device at 300 bounces
  const RenderResult levels = render(ctx, scene, s);
  EXPECT_EQ(levels.tail_depth, kTailDepthDefault);
  EXPECT_EQ(levels.tail_step, kTailStepDefault);
  EXPECT_EQ(levels.cut_paths, 0u);
  if (ctx.info.software) {
    EXPECT_GT(whole.cut_paths, 0u) << "the whole paths reach llvmpipe's loop limit here";
    EXPECT_LT(whole.rays, levels.rays);
  } else {
    EXPECT_EQ(whole.cut_paths, 0u);
    expect_same_result(whole, levels);
  }
  // Up to kCpuWholePathBounces the CPU auto keeps whole paths.
  s.width = s.height = 8;
  s.spp = 1;
  s.bounce_limit = kCpuWholePathBounces;
  EXPECT_EQ(render(ctx, scene, s).tail_depth, ctx.info.software ? 0u : kTailDepthDefault);
}

// The brute-force warning on a CPU device (software_loop_limit_warning):
// its bound counts every primitive a bounce's query loops over (spheres,
// instances, their triangles) and, where next-event estimation has a light
// to sample, the shadow ray's loop too. Measured on lavapipe (session 55,
// docs/reliability.md): 1,002 spheres with a sphere light cut paths at 60
// bounces, under the bound without the shadow rays (65), none with NEE off
// to 64. Fails where the bound leaves either out, or where it warns within
// the bound, on a GPU or for a tree.
TEST(SoftwareLoopLimitWarning, CountsEveryPrimitiveOfABounceAndTheShadowRay) {
  DeviceInfo cpu;
  cpu.name = "llvmpipe";
  cpu.software = true;
  Scene scene = test::furnace_scene();
  scene.materials = {{MaterialType::Lambertian, glm::vec3(0.5f)}};
  for (int i = 0; i < 1000; ++i) scene.spheres.push_back({{float(i), 0, 0}, 0.1f, 0});
  RenderSettings s;
  s.accel = Accel::Brute;
  s.bounce_limit = 65;  // 65 x 1,000 queries' iterations <= 65,535
  EXPECT_EQ(software_loop_limit_warning(cpu, scene, s), "");
  s.bounce_limit = 66;
  EXPECT_NE(software_loop_limit_warning(cpu, scene, s).find("1000 primitives can cut paths longer than 65 bounces"),
            std::string::npos)
      << software_loop_limit_warning(cpu, scene, s);

  // A sphere light: each bounce's shadow ray loops over the 1,001 spheres again.
  Material light;
  light.type = MaterialType::Emissive;
  light.radiance = glm::vec3(4.0f);
  scene.materials.push_back(light);
  scene.spheres.push_back({{0, 5, 0}, 0.5f, 1});
  s.bounce_limit = 32;  // 32 x 2,002 <= 65,535
  EXPECT_EQ(software_loop_limit_warning(cpu, scene, s), "");
  s.bounce_limit = 33;
  EXPECT_NE(software_loop_limit_warning(cpu, scene, s).find("longer than 32 bounces"), std::string::npos)
      << software_loop_limit_warning(cpu, scene, s);
  s.nee = false;  // no shadow rays
  EXPECT_EQ(software_loop_limit_warning(cpu, scene, s), "");
  s.nee = true;

  // Two instances of a two-triangle mesh: 1,001 spheres + 2 instances + 4 triangles.
  Mesh quad;
  quad.name = "quad";
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.materials = {0, 0};
  scene.meshes.push_back(quad);
  scene.instances = {{0, glm::mat4(1.0f)}, {0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 2))}};
  EXPECT_NE(software_loop_limit_warning(cpu, scene, s).find("1007 primitives"), std::string::npos)
      << software_loop_limit_warning(cpu, scene, s);

  // A tree, or a GPU: no warning.
  s.accel = Accel::Octree;
  EXPECT_EQ(software_loop_limit_warning(cpu, scene, s), "");
  s.accel = Accel::Brute;
  DeviceInfo gpu = cpu;
  gpu.software = false;
  EXPECT_EQ(software_loop_limit_warning(gpu, scene, s), "");
}

// Batches of about a quarter second, in whole rounds of a pixel's lanes;
// one round at least while it takes at most a second (a prompt stop).
TEST(NextBatch, TakesWholeRoundsOfLanesAndKeepsAStopPrompt) {
  EXPECT_EQ(next_batch(1.0, 1), 250u);
  EXPECT_EQ(next_batch(1.0, 8), 248u);   // 250 to whole rounds of 8
  EXPECT_EQ(next_batch(1.0, 4), 248u);
  EXPECT_EQ(next_batch(0.0, 8), 1024u);  // at most 1024
  EXPECT_EQ(next_batch(50.0, 8), 8u);    // 5 samples: one round of 8 takes 400 ms
  EXPECT_EQ(next_batch(125.0, 8), 8u);   // 2: one round takes exactly a second
  EXPECT_EQ(next_batch(200.0, 8), 1u);   // 1: a round would take 1.6 s
  EXPECT_EQ(next_batch(300.0, 1), 1u);
  EXPECT_EQ(next_batch(10.0, 4, 1000.0), 100u);  // another target (mpirun --batch-ms)
  EXPECT_EQ(next_batch(1.0, 0), 250u);   // no lanes counts as one
}

// On a CPU device a batch is whole images per thread: llvmpipe gives each of
// its threads one contiguous block of a dispatch's workgroups, and a batch of
// one sample gave one thread the image's top half, the other its bottom
// (optimisation log 85). The first batch is one such round, and so is the
// smallest later one; `--sample-lanes` there makes it a multiple of both.
TEST_F(RenderTest, CpuDeviceBatchesAreWholeImagesPerThread) {
  const VulkanContext& ctx = test::shared_context();
  if (!ctx.info.software) GTEST_SKIP() << "a GPU's batches are whole rounds of its lanes";
  ASSERT_GE(ctx.info.cpu_threads, 1u);
  ASSERT_LE(ctx.info.cpu_threads, 32u);
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 24;
  s.height = 16;
  s.spp = 4;
  PathTracer tracer(ctx, scene, s);
  EXPECT_EQ(tracer.batch_granule(), ctx.info.cpu_threads);
  EXPECT_EQ(tracer.first_batch(), ctx.info.cpu_threads);
  s.sample_lanes = 4;
  PathTracer lanes(ctx, scene, s);
  EXPECT_EQ(lanes.batch_granule() % 4, 0u);
  if (std::lcm(4u, ctx.info.cpu_threads) <= 32) {
    EXPECT_EQ(lanes.batch_granule(), std::lcm(4u, ctx.info.cpu_threads));
  }
}

// The tail queue's entries (optimisation log 117): on a GPU up to half a
// dispatch's paths where the whole queue (two halves with tail levels) fits
// an eighth of the device's memory; on a CPU device a quarter in the
// budget a half; never fewer than a workgroup's, more than an indirect
// dispatch's 65535 workgroups cover or a buffer holds.
TEST(TailQueue, EntriesUpToHalfTheDispatchsPathsOnAGpu) {
  const uint64_t entry = sizeof(gpu::GpuTailPath), gib = uint64_t(1) << 30, big = uint64_t(80) << 30;
  const uint64_t most = 65535 * 64;  // an indirect dispatch's workgroups of 64
  EXPECT_EQ(tail_queue_entries(1200 * 800 * 16, true, big, 4 * gib, 2), most);  // 1200x800, 16 samples
  EXPECT_EQ(tail_queue_entries(1200 * 800 * 8, true, big, 4 * gib, 2), 1200 * 800 * 8 / 2);
  EXPECT_EQ(tail_queue_entries(1200 * 800 * 8, true, 4 * gib, 4 * gib, 2), 4 * gib / 8 / (2 * entry));  // 4 GiB
  EXPECT_EQ(tail_queue_entries(1200 * 800 * 8, true, 2 * gib, 4 * gib, 1), 2 * gib / 8 / entry);
  EXPECT_EQ(tail_queue_entries(1200 * 800 * 8, true, big, gib / 8, 2), gib / 8 / (2 * entry));  // the buffer
  EXPECT_EQ(tail_queue_entries(100, true, big, 4 * gib, 2), 64u);                                // a workgroup
  const uint64_t cpu_budget = uint64_t(32) << 20;
  EXPECT_EQ(tail_queue_entries(160 * 90 * 8, false, cpu_budget, 4 * gib, 2), 160 * 90 * 8 / 4);
  EXPECT_EQ(tail_queue_entries(1600 * 900 * 8, false, cpu_budget, 4 * gib, 2), cpu_budget / entry);
}

// Auto lanes: 4, and 8 only for triangles in whole paths (optimisation log
// 71), fewer with the tail queue where 4 would leave lanes idle (log 116);
// never more than the dispatch's samples, and few enough rows of workgroups
// for the guaranteed 65535.
TEST(SampleLanes, AutoIsFourEightForTrianglesInWholePathsFewerWhereLanesIdle) {
  EXPECT_EQ(sample_lanes(0, false, true, 8, 800), 4u);   // spheres, tail queue
  EXPECT_EQ(sample_lanes(0, false, false, 8, 800), 4u);  // spheres, whole paths
  EXPECT_EQ(sample_lanes(0, true, true, 8, 800), 4u);    // triangles, tail queue
  EXPECT_EQ(sample_lanes(0, true, false, 8, 800), 8u);   // triangles, whole paths
  EXPECT_EQ(sample_lanes(2, true, false, 8, 800), 2u);   // the setting wins
  // With the tail queue, fewer lanes where 4 would leave some of the last
  // round's idle (log 116): 10 samples in 2 lanes, 5 rounds, none idle.
  EXPECT_EQ(sample_lanes(0, false, true, 10, 800), 2u);
  EXPECT_EQ(sample_lanes(0, true, true, 10, 800), 2u);
  EXPECT_EQ(sample_lanes(0, false, true, 16, 800), 4u);
  EXPECT_EQ(sample_lanes(0, false, true, 6, 800), 2u);
  EXPECT_EQ(sample_lanes(0, false, true, 3, 800), 1u);
  EXPECT_EQ(sample_lanes(0, false, false, 10, 800), 4u);  // whole paths: a dispatch in whole rounds
  EXPECT_EQ(sample_lanes(0, true, false, 10, 800), 8u);
  EXPECT_EQ(sample_lanes(4, false, true, 10, 800), 4u);   // the setting wins
  EXPECT_EQ(sample_lanes(0, false, false, 3, 800), 2u);   // at most the samples, a power of two
  EXPECT_EQ(sample_lanes(8, true, true, 1, 800), 1u);
  // 8 lanes make workgroups one row high: 70,000 rows would be 70,000 of them.
  EXPECT_EQ(sample_lanes(8, true, true, 8, 70000), 4u);
  EXPECT_EQ(sample_lanes(8, true, true, 8, 65535), 8u);
}

// The devices the per-device rules tell apart: a GPU, and lavapipe of Mesa
// 22.3, 25.0 and 26.1.
struct RuleDevices {
  DeviceInfo gpu, mesa22, mesa25, mesa26;
  RuleDevices() {
    mesa22.software = mesa25.software = mesa26.software = true;
    mesa22.llvmpipe_release = 2203;
    mesa25.llvmpipe_release = 2500;
    mesa26.llvmpipe_release = 2601;
  }
};

// RenderSettings::tail_subgroup's auto (optimisation log 141): four paths
// for each subgroup the device holds at once, for scenes with triangles,
// where the driver says; none where a subgroup would not fit a workgroup
// or has fewer lanes than a node has children.
TEST(TailSubgroup, AutoIsFourPathsForEachResidentSubgroupOverTriangles) {
  DeviceInfo h100;
  h100.resident_threads = 270336;
  h100.subgroup_size = 32;
  EXPECT_EQ(default_tail_subgroup(h100, true), 33792u);
  EXPECT_EQ(default_tail_subgroup(h100, false), 0u);  // spheres alone
  DeviceInfo wave64 = h100;
  wave64.subgroup_size = 64;
  EXPECT_EQ(default_tail_subgroup(wave64, true), 16896u);
  DeviceInfo wide = h100;
  wide.subgroup_size = 128;
  EXPECT_EQ(default_tail_subgroup(wide, true), 0u);
  DeviceInfo narrow = h100;
  narrow.resident_threads = 4096;
  narrow.subgroup_size = 8;  // a lane for each child of a node: the least
  EXPECT_EQ(default_tail_subgroup(narrow, true), 2048u);
  narrow.subgroup_size = 4;
  EXPECT_EQ(default_tail_subgroup(narrow, true), 0u);
  for (uint32_t lanes : {4u, 8u, 16u, 32u, 64u, 128u})
    EXPECT_EQ(fits_tail_subgroup(lanes), lanes >= 8 && lanes <= 64) << lanes;
  DeviceInfo unknown = h100;
  unknown.resident_threads = 0;  // lavapipe, or a driver that does not say
  EXPECT_EQ(default_tail_subgroup(unknown, true), 0u);
  unknown = h100;
  unknown.subgroup_size = 0;  // below Vulkan 1.2
  EXPECT_EQ(default_tail_subgroup(unknown, true), 0u);
}

// RenderSettings::bvh_walk's auto (optimisation log 123): while-while for
// a top level whose leaves hold 4 references or more on average, on a GPU.
TEST(BvhWalk, AutoIsWhileWhileOnAGpuWhereLeavesHoldFourOrMore) {
  DeviceInfo gpu;
  gpu.software = false;
  DeviceInfo cpu;
  cpu.software = true;
  EXPECT_TRUE(default_bvh_top_while(gpu, kBvhWhileRefsPerLeaf));
  EXPECT_TRUE(default_bvh_top_while(gpu, 6.7));  // 1M spheres of r = 0.1
  EXPECT_FALSE(default_bvh_top_while(gpu, 3.9));
  EXPECT_FALSE(default_bvh_top_while(gpu, 2.2));  // the peer's scene
  EXPECT_FALSE(default_bvh_top_while(cpu, 6.7));
  EXPECT_FALSE(default_bvh_top_while(gpu, 0.0));  // no top level
}

// Auto octant culling (optimisation log 106): off only for scenes without
// triangles on lavapipe from Mesa 25; the tracer resolves the setting so.
TEST(OctantCulling, AutoIsOffOnlyForSpheresOnLavapipeFromMesa25) {
  const auto [gpu, mesa22, mesa25, mesa26] = RuleDevices();
  for (bool triangles : {false, true}) {
    EXPECT_TRUE(default_octant_culling(gpu, triangles));
    EXPECT_TRUE(default_octant_culling(mesa22, triangles));
  }
  EXPECT_FALSE(default_octant_culling(mesa25, false));
  EXPECT_FALSE(default_octant_culling(mesa26, false));
  EXPECT_TRUE(default_octant_culling(mesa25, true));
}

// Auto leaf size (optimisation logs 110 and 115): 16 exactly where the
// culling's auto is off, 24 over spheres alone on a GPU, kOctreeLeaf
// elsewhere; the tracer builds with it.
TEST(OctreeLeaf, AutoIsSixteenWhereTheCullingIsOffAndLargerForGpuSpheres) {
  const auto [gpu, mesa22, mesa25, mesa26] = RuleDevices();
  EXPECT_EQ(default_octree_leaf(gpu, false), 24u);
  EXPECT_EQ(default_octree_leaf(gpu, true), kOctreeLeaf);
  for (bool triangles : {false, true}) EXPECT_EQ(default_octree_leaf(mesa22, triangles), kOctreeLeaf);
  EXPECT_EQ(default_octree_leaf(mesa25, false), 16u);
  EXPECT_EQ(default_octree_leaf(mesa26, false), 16u);
  EXPECT_EQ(default_octree_leaf(mesa25, true), kOctreeLeaf);
}

// Auto references per primitive and copy leaves (optimisation log 136): 12
// with copy leaves of 20 for triangles on a GPU, kOctreeRefs and none
// elsewhere; the tracer builds with them.
TEST(OctreeRefs, AutoIsTwelveWithCopyLeavesOnlyForTrianglesOnAGpu) {
  const auto [gpu, mesa22, mesa25, mesa26] = RuleDevices();
  EXPECT_EQ(default_octree_refs(gpu, true), 12u);
  EXPECT_EQ(default_copy_leaf(gpu, true), 20u);
  EXPECT_EQ(default_octree_refs(gpu, false), kOctreeRefs);
  EXPECT_EQ(default_copy_leaf(gpu, false), 0u);
  for (const DeviceInfo& d : {mesa22, mesa25, mesa26})
    for (bool triangles : {false, true}) {
      EXPECT_EQ(default_octree_refs(d, triangles), kOctreeRefs);
      EXPECT_EQ(default_copy_leaf(d, triangles), 0u);
    }
}

// Auto cells over the spheres' surfaces (optimisation logs 126 and 127): on
// a GPU for renders of kSurfaceCellsMinSamples samples or more, never on a
// CPU device.
TEST(SurfaceCells, AutoOnlyOnAGpuForLongRenders) {
  const auto [gpu, mesa22, mesa25, mesa26] = RuleDevices();
  EXPECT_TRUE(default_surface_cells(gpu, kSurfaceCellsMinSamples));
  EXPECT_TRUE(default_surface_cells(gpu, uint64_t(1) << 40));
  EXPECT_FALSE(default_surface_cells(gpu, kSurfaceCellsMinSamples - 1));
  EXPECT_FALSE(default_surface_cells(gpu, uint64_t(1200) * 800 * 10));  // render's default
  for (const DeviceInfo& d : {mesa22, mesa25, mesa26}) EXPECT_FALSE(default_surface_cells(d, uint64_t(1) << 40));
}

// lane_sample's workgroup array (optimisation log 114): twice the
// invocations on NVIDIA's driver, one entry each elsewhere.
TEST(LaneSampleSlots, TwiceTheInvocationsOnlyOnNvidiasDriver) {
  auto [gpu, mesa22, mesa25, mesa26] = RuleDevices();
  const uint32_t invocations = gpu::WORKGROUP_SIZE * gpu::WORKGROUP_SIZE;
  for (const DeviceInfo& d : {gpu, mesa22, mesa25, mesa26}) EXPECT_EQ(lane_sample_slots(d), invocations);
  gpu.nvidia = true;
  EXPECT_EQ(lane_sample_slots(gpu), 2 * invocations);
}

// The tracer resolves the per-device autos (the octant culling, log 106; the
// octree's leaf size, logs 110 and 115; its budget and copy leaves, log 136)
// with the rules above, and takes a setting as
// given; a BVH's top level takes the top level's node cost (bvh.h
// kBvhTopNodeCost, log 112), which makes another tree than the meshes' cost.
TEST_F(RenderTest, TreeSettingsResolvedForTheDeviceAndLevel) {
  VulkanContext& ctx = test::shared_context();
  const Scene scene = make_rtiow_scene({400, 0.2f, 3});
  RenderSettings s;
  s.width = 16;
  s.height = 8;
  {
    const PathTracer tracer(ctx, scene, s);
    EXPECT_EQ(tracer.octant_culling(), default_octant_culling(ctx.info, false));
    EXPECT_EQ(tracer.octree_stats().leaf_size, default_octree_leaf(ctx.info, false));
    EXPECT_EQ(tracer.octree_stats().max_refs, default_octree_refs(ctx.info, false));
  }
  Scene meshes = scene;
  test::place(meshes, test::icosphere(1, 0), glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)));
  {
    const PathTracer tracer(ctx, meshes, s);
    const OctreeStats& o = tracer.octree_stats();
    EXPECT_EQ(o.leaf_size, default_octree_leaf(ctx.info, true));
    // Built once with the autos, or again at the measured settings where
    // the first build was over the bound.
    EXPECT_EQ(o.max_refs, o.first_bytes_per_primitive > 0 ? kOctreeRefs : default_octree_refs(ctx.info, true));
    EXPECT_EQ(o.copy_leaf, o.first_bytes_per_primitive > 0 ? 0u : default_copy_leaf(ctx.info, true));
  }
  {
    // Copy leaves given directly (on a CPU device the autos set none): a
    // tree over kOctreeBytesBound bytes a primitive (leaves of one
    // reference; copy leaves of one, which keep no node) is built again at
    // kOctreeRefs without copy leaves; one under it is built once.
    RenderSettings c = s;
    c.octree.leaf_size = 1;
    c.octree.max_refs = 12;
    c.octree.copy_leaf = 1;
    const OctreeStats big = PathTracer(ctx, meshes, c).octree_stats();
    EXPECT_GT(big.first_bytes_per_primitive, kOctreeBytesBound);
    EXPECT_EQ(big.max_refs, kOctreeRefs);
    EXPECT_EQ(big.copy_leaf, 0u);
    c.octree.leaf_size = 10;
    c.octree.copy_leaf = 20;
    const OctreeStats small = PathTracer(ctx, meshes, c).octree_stats();
    EXPECT_LE(small.bytes_per_primitive, kOctreeBytesBound);
    EXPECT_EQ(small.first_bytes_per_primitive, 0.0);
    EXPECT_EQ(small.max_refs, 12u);
    EXPECT_EQ(small.copy_leaf, 20u);
  }
  s.octant_culling = OctantCulling::On;
  s.octree.leaf_size = 3;
  s.octree.max_refs = 5;
  {
    const PathTracer tracer(ctx, scene, s);
    EXPECT_TRUE(tracer.octant_culling());
    EXPECT_EQ(tracer.octree_stats().leaf_size, 3u);
    EXPECT_EQ(tracer.octree_stats().max_refs, 5u);
    EXPECT_EQ(tracer.octree_stats().copy_leaf, 0u);  // a budget given: no copy leaves
  }
  s.octant_culling = OctantCulling::Off;
  EXPECT_FALSE(PathTracer(ctx, scene, s).octant_culling());
  s.accel = Accel::Bvh;
  const OctreeStats bvh = PathTracer(ctx, scene, s).octree_stats();
  EXPECT_EQ(bvh.leaf_size, 0u);  // a BVH has no leaf size of this kind
  const std::vector<Aabb> boxes = primitive_boxes(scene);
  const uint32_t top = build_bvh(boxes, 2, {}, kBvhSpatialRefs, kBvhTopNodeCost).stats.leaves;
  ASSERT_NE(top, build_bvh(boxes, 2, {}, kBvhSpatialRefs, kBvhNodeCost).stats.leaves);
  EXPECT_EQ(bvh.leaves, top);
}

// The seam of the preview window: a tracer made once renders another camera,
// bounce limit and seed per pass, and gives exactly the image of a tracer
// made for them from the start. A move rebuilds nothing.
TEST_F(RenderTest, CameraBounceLimitAndSeedArePerPass) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  PathTracer tracer(ctx, scene, s);
  tracer.run_passes(pass_settings(scene, s), 0, 2);  // the accumulation of the first view ...

  Scene moved = scene;
  orbit(moved.camera, 0.3f, 0.1f);
  zoom(moved.camera, 2.0f);
  RenderSettings other = s;
  other.bounce_limit = 7;
  other.sample_seed = 5;
  other.spp = 3;
  tracer.reset();  // ... is cleared, as a camera move in the window does
  tracer.run_passes(pass_settings(moved, other), 0, 3);
  const RenderResult per_pass = tracer.read_result();
  const RenderResult fresh = render(ctx, moved, other);
  EXPECT_TRUE(same_bits(per_pass.mean, fresh.mean));
  EXPECT_EQ(per_pass.min_samples, 3u);
  // Each per-pass setting reaches the passes: the camera, the bounce limit
  // and the seed each change the image (the test would see one that stayed
  // as it was set up).
  EXPECT_FALSE(same_bits(per_pass.mean, render(ctx, scene, other).mean)) << "camera";
  for (auto [what, change] : {std::pair<const char*, void (*)(PassSettings&)>{"bounce limit", [](PassSettings& p) { p.bounce_limit = 50; }},
                              {"seed", [](PassSettings& p) { p.sample_seed = 1; }}}) {
    PassSettings p = pass_settings(moved, other);
    change(p);
    tracer.reset();
    tracer.run_passes(p, 0, 3);
    EXPECT_FALSE(same_bits(tracer.read_result().mean, per_pass.mean)) << what;
  }
}

// Spheres that overlap (a field denser than they are wide): with their
// hidden parts left out of the trees (OctreeParams::hidden_parts, the
// default) each structure tests far fewer spheres a query and renders every
// pixel as with whole spheres; and a tree built so refuses a pass whose
// camera moved (its rays could start inside an opaque sphere).
TEST_F(RenderTest, HiddenPartsSpareTestsAndChangeNoPixel) {
  VulkanContext& ctx = test::shared_context();
  const Scene scene = make_rtiow_scene({3000, 1.0f, 4});
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.spp = 2;
  s.bounce_limit = 8;
  s.walk_stats = true;
  for (Accel accel : {Accel::Octree, Accel::Bvh}) {
    SCOPED_TRACE(accel_name(accel));
    s.accel = accel;
    s.octree.hidden_parts = HiddenParts::Keep;
    const RenderResult keep = render(ctx, scene, s);
    EXPECT_EQ(keep.octree.spheres_clipped + keep.octree.spheres_hidden, 0u);
    s.octree.hidden_parts = HiddenParts::Cull;
    const RenderResult cull = render(ctx, scene, s);
    EXPECT_GT(cull.octree.spheres_clipped, scene.spheres.size() / 2);
    EXPECT_TRUE(same_bits(keep.mean, cull.mean));
    ASSERT_EQ(keep.walk.queries, cull.walk.queries);
    EXPECT_LT(3 * cull.walk.primitives, keep.walk.primitives)
        << cull.walk.primitives << " sphere tests against " << keep.walk.primitives;
    // The octree's cells over the spheres' surfaces (--octree-surfaces,
    // log 126): auto on a GPU for long renders only (not this one, log 127;
    // SurfaceCells.AutoOnlyOnAGpuForLongRenders); on and off, the same image
    // (this field is not dense enough for them to save tests: octree_test's
    // grid is).
    EXPECT_FALSE(cull.octree.surface_cells);
    {
      // A render long enough: the tracer resolves auto by the rule (built,
      // not rendered).
      RenderSettings long_render = s;
      long_render.spp = uint32_t(kSurfaceCellsMinSamples / (uint64_t(s.width) * s.height) + 1);
      const PathTracer tracer(ctx, scene, long_render);
      EXPECT_EQ(tracer.octree_stats().surface_cells, accel == Accel::Octree && !ctx.info.software);
    }
    s.octree.surface_cells = SurfaceCells::On;
    const RenderResult surfaces = render(ctx, scene, s);
    s.octree.surface_cells = SurfaceCells::Off;
    const RenderResult boxes = render(ctx, scene, s);
    s.octree.surface_cells = SurfaceCells::Auto;
    EXPECT_EQ(surfaces.octree.surface_cells, accel == Accel::Octree);
    EXPECT_FALSE(boxes.octree.surface_cells);
    EXPECT_TRUE(same_bits(keep.mean, surfaces.mean));
    EXPECT_TRUE(same_bits(keep.mean, boxes.mean));
  }
  s.walk_stats = false;
  Scene moved = scene;
  orbit(moved.camera, 0.3f, 0.1f);
  {
    PathTracer tracer(ctx, scene, s);
    tracer.run_passes(pass_settings(scene, s), 0, 1);
    EXPECT_THROW(tracer.run_passes(pass_settings(moved, s), 0, 1), std::logic_error);
  }
  s.octree.hidden_parts = HiddenParts::Keep;
  PathTracer tracer(ctx, scene, s);
  tracer.run_passes(pass_settings(moved, s), 0, 1);
}

// The camera's tiles (RenderSettings::camera_tiles): camera rays tested
// against their tile's list of spheres render every bit as the walks do,
// with either structure, in fp32 and fp16, through a lens and a pinhole,
// over trees that left hidden parts out (the peer's field, the dense
// field), where tiles overflow their lists (the dense field)
// and walk, on an image whose last row and column of tiles are partial,
// in whole paths and with the tail queue; the camera rays of tiles that
// do not overflow expand no node.
TEST_F(RenderTest, CameraTilesChangeNoPixel) {
  VulkanContext& ctx = test::shared_context();
  // The peer's field (tools/peer): a pinhole, and small spheres that
  // overlap the big ones, whose trees leave those parts out.
  const Scene pinhole = load_scene_json(OCTRACE_SOURCE_DIR "/tools/scenes/peer_field.json");
  // A lens 2 wide: at the field's depths a ray leaves its pinhole ray's
  // side of a tile by several pixels.
  Scene wide = make_rtiow_scene({200, 0.2f, 1});
  wide.camera.aperture = 2.0f;
  const std::pair<const char*, Scene> scenes[] = {{"a lens", make_rtiow_scene({200, 0.2f, 1})},
                                                  {"a wide lens", wide},
                                                  {"a pinhole", pinhole},
                                                  {"dense", make_rtiow_scene({3000, 1.0f, 4})}};
  // A render with the tiles off and the same with them on.
  const auto off_and_on = [&ctx](const Scene& scene, RenderSettings settings) {
    settings.camera_tiles = CameraTiles::Off;
    RenderResult off = render(ctx, scene, settings);
    settings.camera_tiles = CameraTiles::On;
    return std::pair{std::move(off), render(ctx, scene, settings)};
  };
  RenderSettings s;
  s.width = 62;
  s.height = 37;
  s.spp = 2;
  s.bounce_limit = 8;
  for (const auto& [name, scene] : scenes) {
    for (Accel accel : {Accel::Octree, Accel::Bvh}) {
      for (Precision precision : {Precision::FP32, Precision::FP16}) {
        SCOPED_TRACE(std::string(name) + ", " + accel_name(accel) + ", " + precision_name(precision));
        s.accel = accel;
        s.precision = precision;
        const auto [off, on] = off_and_on(scene, s);
        EXPECT_FALSE(off.camera_tiles);
        EXPECT_TRUE(on.camera_tiles);
        if (std::string(name) == "a pinhole" || std::string(name) == "dense") {
          EXPECT_GT(on.octree.spheres_clipped + on.octree.spheres_hidden, 0u);
        }
        expect_same_result(on, off);
      }
    }
  }
  // With the tail queue (the head takes the camera rays), and in whole
  // paths (the tail queue off): on lavapipe its auto is off, on a GPU on.
  s.precision = Precision::FP32;
  for (uint32_t tail : {2u, 0u}) {
    for (Accel accel : {Accel::Octree, Accel::Bvh}) {
      SCOPED_TRACE(std::string("tail depth ") + std::to_string(tail) + ", " + accel_name(accel));
      s.accel = accel;
      s.tail_depth = tail;
      const auto [off, on] = off_and_on(pinhole, s);
      EXPECT_EQ(on.tail_depth, tail);
      expect_same_result(on, off);
    }
  }
  s.tail_depth = RenderSettings::kTailAuto;
  // Camera rays alone, counted: every tile of the field of 200 takes its
  // list; most of the wide lens's and the pinhole's do, and those near the
  // horizon walk (at this size more spheres reach them than a list holds),
  // as every tile of the dense field does; the same pixels.
  s.accel = Accel::Octree;
  s.precision = Precision::FP32;
  s.bounce_limit = 1;
  s.spp = 1;
  s.walk_stats = true;
  for (const auto& [name, scene] : scenes) {
    SCOPED_TRACE(name);
    const auto [off, on] = off_and_on(scene, s);
    expect_same_result(on, off);
    EXPECT_EQ(on.walk.queries, off.walk.queries);
    EXPECT_GT(off.walk.nodes, 0u);
    if (std::string(name) == "a lens") {
      EXPECT_EQ(on.walk.nodes, 0u);
    } else if (std::string(name) != "dense") {
      EXPECT_GT(on.walk.nodes, 0u);
      EXPECT_LT(2 * on.walk.nodes, off.walk.nodes) << on.walk.nodes << " nodes against " << off.walk.nodes;
    } else {
      EXPECT_EQ(on.walk.nodes, off.walk.nodes);
    }
  }
  // A tracer keeps its lists from batch to batch while the camera stays,
  // and makes them again when it moves: after a batch from one camera, a
  // reset and batches from another, the other camera's image as a fresh
  // tracer renders it.
  s.walk_stats = false;
  s.bounce_limit = 8;
  s.spp = 3;
  const Scene& field = scenes[0].second;
  Scene moved = field;
  orbit(moved.camera, 0.3f, 0.1f);
  s.camera_tiles = CameraTiles::On;
  PathTracer tracer(ctx, field, s);
  tracer.run_passes(pass_settings(field, s), 0, 2);
  tracer.reset();
  tracer.run_passes(pass_settings(moved, s), 0, 2);
  tracer.run_passes(pass_settings(moved, s), 2, 1);
  expect_same_result(tracer.read_result(), render(ctx, moved, s));
}

// RenderSettings::camera_tiles' auto: on for spheres alone with a tree, up
// to the device's bound on their count (optimisation log 143); on where
// that holds past the bound; refused where it cannot.
TEST_F(RenderTest, CameraTilesAutoForFewSpheresWithATree) {
  VulkanContext& ctx = test::shared_context();
  const Scene spheres = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  EXPECT_TRUE(PathTracer(ctx, spheres, s).camera_tiles());
  s.accel = Accel::Bvh;
  EXPECT_TRUE(PathTracer(ctx, spheres, s).camera_tiles());
  s.accel = Accel::Brute;
  EXPECT_FALSE(PathTracer(ctx, spheres, s).camera_tiles());
  s.camera_tiles = CameraTiles::On;
  EXPECT_THROW(PathTracer(ctx, spheres, s), SettingError);
  s.accel = Accel::Octree;
  Scene mesh = spheres;
  test::place(mesh, test::icosphere(1, 0));
  EXPECT_THROW(PathTracer(ctx, mesh, s), SettingError);
  s.camera_tiles = CameraTiles::Auto;
  EXPECT_FALSE(PathTracer(ctx, mesh, s).camera_tiles());
  // The bound: the rtiow field has 4 spheres besides its small ones.
  const uint64_t bound = ctx.info.software ? kCameraTileSpheresCpu : kCameraTileSpheresGpuOctree;
  const Scene at = make_rtiow_scene({bound - 4, 0.05f, 1});
  const Scene past = make_rtiow_scene({bound - 3, 0.05f, 1});
  EXPECT_TRUE(PathTracer(ctx, at, s).camera_tiles());
  EXPECT_FALSE(PathTracer(ctx, past, s).camera_tiles());
  s.camera_tiles = CameraTiles::Off;
  EXPECT_FALSE(PathTracer(ctx, at, s).camera_tiles());
  s.camera_tiles = CameraTiles::On;
  EXPECT_TRUE(PathTracer(ctx, past, s).camera_tiles());
}

TEST(CameraTiles, AutoUpToAThousandSpheresOnACpuAndFourOrEightThousandOnAGpu) {
  DeviceInfo gpu, cpu;
  gpu.software = false;
  cpu.software = true;
  for (uint64_t n : {1ull, 492ull, 1024ull, 1025ull, 4096ull, 4097ull, 8004ull, 8192ull, 8193ull, 1000004ull}) {
    for (Accel accel : {Accel::Octree, Accel::Bvh}) {
      EXPECT_EQ(default_camera_tiles(cpu, accel, n), n <= 1024) << n;
      EXPECT_EQ(default_camera_tiles(gpu, accel, n), n <= (accel == Accel::Bvh ? 4096u : 8192u)) << n;
    }
  }
}

// RenderSettings::dispatch_times: every dispatch of a batch named, by
// stage and tail level, in the order they ran, as often as they ran, their
// times within the batch's; the same image; a reset starts the sums again.
TEST_F(RenderTest, DispatchTimesNameEveryDispatch) {
  VulkanContext& ctx = test::shared_context();
  const Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 37;
  s.height = 23;
  s.spp = 6;
  s.bounce_limit = 8;
  s.samples_per_dispatch = 3;
  s.sample_lanes = 1;
  s.camera_tiles = CameraTiles::On;
  s.dispatch_times = true;
  // The head to bounce 2, then levels of 1, 2 and the last 3 bounces, each
  // with its subgroup stage where the device can run it.
  s.tail_depth = 2;
  s.tail_step = 1;
  const bool stage = fits_tail_subgroup(ctx.info.subgroup_size);
  s.tail_subgroup = stage ? 100u : 0u;
  std::vector<std::pair<std::string, uint32_t>> staged = {{"camera_tiles", 0}, {"head", 0}};
  for (uint32_t level = 0; level < 3; ++level) {
    staged.emplace_back("tail", level);
    if (stage) staged.emplace_back("tail_subgroup", level);
  }
  staged.emplace_back("sum", 0);
  for (uint32_t tail : {2u, 0u}) {
    SCOPED_TRACE("tail depth " + std::to_string(tail));
    s.tail_depth = tail;
    const std::vector<std::pair<std::string, uint32_t>> want =
        tail ? staged : std::vector<std::pair<std::string, uint32_t>>{{"camera_tiles", 0}, {"whole", 0}};
    PathTracer tracer(ctx, scene, s);
    EXPECT_TRUE(tracer.dispatch_times().empty());
    // Two batches of one camera and one of another: the tiles once for
    // each camera (the second batch keeps the first's), the others once a
    // dispatch of samples.
    Scene moved = scene;
    orbit(moved.camera, 0.2f, 0.0f);
    double passes_ms = 0;
    for (uint32_t first : {0u, 4u, 6u}) {
      const double ms = tracer.run_passes(pass_settings(first < 6 ? scene : moved, s), first, first ? 2 : 4);
      ASSERT_GE(ms, 0.0);
      passes_ms += ms;
    }
    const std::vector<DispatchTime>& got = tracer.dispatch_times();
    ASSERT_EQ(got.size(), want.size());
    double sum_ms = 0;
    for (size_t i = 0; i < want.size(); ++i) {
      SCOPED_TRACE(want[i].first + " " + std::to_string(want[i].second));
      EXPECT_EQ(got[i].stage, want[i].first);
      EXPECT_EQ(got[i].level, want[i].second);
      EXPECT_EQ(got[i].runs, want[i].first == "camera_tiles" ? 2u : 4u);
      EXPECT_GE(got[i].ms, 0.0);
      sum_ms += got[i].ms;
    }
    EXPECT_GT(sum_ms, 0.0);
    EXPECT_LE(sum_ms, passes_ms * (1.0 + 1e-6) + 1e-6);
    // A reset forgets the lists: a batch from the same camera after it
    // makes them again, as a fresh tracer's first does (bench's renders).
    {
      PathTracer again(ctx, scene, s);
      again.run_passes(pass_settings(scene, s), 0, 2);
      again.reset();
      again.run_passes(pass_settings(scene, s), 0, 2);
      const std::vector<DispatchTime>& after = again.dispatch_times();
      ASSERT_FALSE(after.empty());
      EXPECT_EQ(after.front().stage, "camera_tiles");
      EXPECT_EQ(after.front().runs, 1u);
    }
    // The paths each tail level took, in whichever of its two stages ran
    // it: some at the first level, never more at a later one (a level
    // queues at most the paths it took), none outside the tail.
    uint64_t before = UINT64_MAX;
    for (uint32_t level = 0; level < 3 && tail; ++level) {
      uint64_t paths = 0;
      for (const DispatchTime& d : got)
        if (d.level == level && d.tail()) paths += d.paths;
      if (level == 0) {
        EXPECT_GT(paths, 0u);
      }
      EXPECT_LE(paths, before) << "level " << level;
      before = paths;
    }
    // The subgroup stage takes a level of fewer paths than its threshold
    // (100 here), the tail stage the others: at most 99 paths a run in the
    // one, none or at least 100 in the other.
    for (const DispatchTime& d : got) {
      if (!d.tail()) {
        EXPECT_EQ(d.paths, 0u) << d.stage;
      }
      if (d.stage == "tail_subgroup") {
        EXPECT_LE(d.paths, d.runs * 99) << "level " << d.level;
      }
      if (d.stage == "tail") {
        EXPECT_TRUE(d.paths == 0 || d.paths >= 100) << "level " << d.level << ": " << d.paths;
      }
    }
    tracer.reset();
    EXPECT_TRUE(tracer.dispatch_times().empty());
    const RenderResult timed = render(ctx, scene, s);
    EXPECT_FALSE(timed.dispatches.empty());
    RenderSettings untimed = s;
    untimed.dispatch_times = false;
    const RenderResult plain = render(ctx, scene, untimed);
    EXPECT_TRUE(plain.dispatches.empty());
    expect_same_result(timed, plain);
  }
}

// A tracer resized and switched to another accel (the octree built on the
// way), precision and effects renders what a tracer made with those settings
// renders.
TEST_F(RenderTest, ResizeAndReconfigureMatchAFreshTracer) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.spp = 2;
  s.accel = Accel::Brute;  // the octree (the BVH) is built when asked for, and again when switched back
  PathTracer tracer(ctx, scene, s);
  tracer.run_passes(pass_settings(scene, s), 0, 2);
  // Every accel, precision and effects setting switched to and away from;
  // the general pipeline (`all`) only where other tests compile it too
  // (effects_test: the octree's, fp32): a general pipeline is the whole
  // path tracer, some 25 s of llvmpipe's time on a 2-core machine when the
  // shader cache is cold, as in CI.
  for (const auto& [accel, precision, all] :
       {std::tuple{Accel::Brute, Precision::FP16, false}, std::tuple{Accel::Octree, Precision::FP32, true},
        std::tuple{Accel::Octree, Precision::FP16All, false}, std::tuple{Accel::Bvh, Precision::FP32, false}}) {
    RenderSettings want = s;
    want.width = 40;
    want.height = 20;
    want.accel = accel;
    want.precision = precision;
    want.all_effects = all;
    tracer.resize(want.width, want.height);
    tracer.reconfigure(scene, accel, precision, all);
    tracer.run_passes(pass_settings(scene, want), 0, want.spp);
    EXPECT_TRUE(same_bits(tracer.read_result().mean, render(ctx, scene, want).mean))
        << accel_name(accel) << " " << precision_name(precision) << (all ? " all" : " auto");
  }
}

// The device holds the materials only as the render's precision reads them
// (log 130), and the checkpoint's scene hash covers both forms all the same:
// one scene hashes alike in every precision (and as before: a state saved by
// an earlier octrace resumes, checked in log 130).
TEST_F(RenderTest, SceneHashIsTheSameInEveryPrecision) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  Material pbr;
  pbr.type = MaterialType::Pbr;
  pbr.albedo = glm::vec3(0.3f, 0.6f, 0.9f);
  pbr.metallic = 0.25f;
  pbr.roughness = 0.7f;
  pbr.transmission = 0.5f;
  pbr.thin_walled = true;
  pbr.emission = glm::vec3(0.1f, 0.2f, 0.3f);
  scene.materials.push_back(pbr);
  scene.spheres[5].material = uint32_t(scene.materials.size() - 1);
  RenderSettings s;
  s.width = 8;
  s.height = 8;
  std::vector<uint64_t> hashes;
  for (Precision p : {Precision::FP32, Precision::FP16, Precision::FP16All}) {
    s.precision = p;
    hashes.push_back(PathTracer(ctx, scene, s).scene_hash());
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
  scene.materials.back().roughness = 0.75f;  // and the hash sees the materials
  s.precision = Precision::FP16;
  EXPECT_NE(PathTracer(ctx, scene, s).scene_hash(), hashes[0]);
}

// What the device or scene cannot do is refused, and the tracer keeps what it had.
TEST_F(RenderTest, ReconfigureRefusedKeepsTheTracer) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = test::furnace_scene();
  scene.materials = {test::emitter(glm::vec3(1e5f))};  // beyond half's range
  scene.spheres = {{{0, 0, 0}, 1.0f, 0}};
  RenderSettings s;
  s.width = 16;
  s.height = 16;
  s.spp = 1;
  PathTracer tracer(ctx, scene, s);
  EXPECT_THROW(tracer.reconfigure(scene, Accel::Octree, Precision::FP16, false), SettingError);
  EXPECT_EQ(tracer.settings().precision, Precision::FP32);
  tracer.run_passes(pass_settings(scene, s), 0, 1);
  EXPECT_TRUE(same_bits(tracer.read_result().mean, render(ctx, scene, s).mean));
}

// Rays per second counts every segment: a path that escapes at once is one
// ray; one that cannot escape (the camera inside a closed white sphere) is
// as many rays as the bounce limit.
TEST_F(RenderTest, RaysCountEverySegment) {
  const uint64_t paths = 48 * 32 * 3;
  Scene empty = test::furnace_scene();
  EXPECT_EQ(render_small(empty, 3).rays, paths);
  Scene inside = test::furnace_scene();
  inside.materials = {test::lambertian(1.0f)};
  inside.spheres = {{{0, 0, 6}, 2.0f, 0}};  // around the camera
  EXPECT_EQ(render_small(inside, 3, 5).rays, 5 * paths);
  EXPECT_EQ(render_small(inside, 3, 1).rays, paths);
}

// --walk-stats counts what the walks do and changes no pixel. Brute force at
// depth 1 tests every sphere once per query, one query per camera ray; the
// BVH tests the root's box and two children's boxes per internal node; the
// octree tests the rtiow ground (its big list) as a leaf of every query; shadow
// rays are queries too; without the setting nothing is counted. Every
// query walks: the camera's tiles, which spare camera rays the walk, are off
// (CameraTilesChangeNoPixel counts them).
TEST_F(RenderTest, WalkStatsCountTheWalksAndChangeNoPixel) {
  Scene scene = make_rtiow_scene({40, 0.2f, 3});
  RenderSettings s;
  s.width = 24;
  s.height = 16;
  s.spp = 2;
  s.bounce_limit = 1;
  s.accel = Accel::Brute;
  s.walk_stats = true;
  s.camera_tiles = CameraTiles::Off;
  const uint64_t camera_rays = 24 * 16 * 2;
  RenderResult r = render(test::shared_context(), scene, s);
  ASSERT_TRUE(r.walk.counted);
  EXPECT_EQ(r.walk.queries, camera_rays);
  EXPECT_EQ(r.walk.primitives, camera_rays * scene.spheres.size());
  EXPECT_EQ(r.walk.nodes + r.walk.leaves + r.walk.boxes + r.walk.instances + r.walk.node_slots, 0u);
  // Every query tests every sphere with the lanes that started it, so the
  // subgroups are as full at the sphere tests as where the queries start (on
  // llvmpipe, whose lanes keep in step, exactly; a GPU may let the lanes of
  // a warp part after a miss's early return).
  const uint32_t lanes = test::shared_context().info.subgroup_size;
  ASSERT_GT(lanes, 0u);
  EXPECT_GE(r.walk.query_slots, r.walk.queries);
  EXPECT_LE(r.walk.query_slots, r.walk.queries * lanes);
  EXPECT_EQ(r.walk.query_slots % lanes, 0u);
  if (test::shared_context().info.software) {
    EXPECT_EQ(r.walk.query_slots, r.walk.queries);  // 24x16 fills its subgroups: every lane casts a camera ray
    EXPECT_EQ(r.walk.primitive_slots, r.walk.query_slots * scene.spheres.size());
  }

  s.bounce_limit = 8;
  for (Accel accel : {Accel::Brute, Accel::Octree, Accel::Bvh}) {
    SCOPED_TRACE(accel_name(accel));
    s.accel = accel;
    s.walk_stats = false;
    const RenderResult plain = render(test::shared_context(), scene, s);
    EXPECT_FALSE(plain.walk.counted);
    EXPECT_EQ(plain.walk.queries, 0u);
    s.walk_stats = true;
    const RenderResult counted = render(test::shared_context(), scene, s);
    EXPECT_EQ(std::memcmp(plain.mean.rgb.data(), counted.mean.rgb.data(), plain.mean.rgb.size() * sizeof(float)), 0);
    const WalkStats& w = counted.walk;
    EXPECT_EQ(w.queries, counted.rays);  // no lights: one query per segment
    if (accel == Accel::Bvh) {
      EXPECT_EQ(w.boxes, w.queries + 2 * w.nodes);  // spheres: a binary top level (accel/bvh.h)
    }
    if (accel == Accel::Octree) {
      EXPECT_GE(w.leaves, w.queries);  // the ground, in the big list
      EXPECT_GE(w.boxes, w.queries + w.nodes);  // the root's, and one child's at least per node
    }
    if (accel != Accel::Brute) {
      EXPECT_GT(w.nodes, 0u);
      EXPECT_LT(w.primitives, w.queries * scene.spheres.size() / 4);  // the structures spare most tests
    }
    // A step's slots are the subgroup's lanes, of which at least one is busy
    // there: between the count and the count times the lanes. Paths part
    // after their first bounce, so some lanes idle where queries start.
    const uint32_t lanes = test::shared_context().info.subgroup_size;
    for (auto [count, slots] : {std::pair{w.queries, w.query_slots}, std::pair{w.nodes, w.node_slots},
                                std::pair{w.primitives, w.primitive_slots}}) {
      EXPECT_GE(slots, count);
      EXPECT_LE(slots, count * lanes);
      EXPECT_EQ(slots % lanes, 0u);
    }
    EXPECT_GT(w.query_slots, w.queries);
  }

  scene.lights = {test::point_light({0.0f, 4.0f, 0.0f}, 10.0f)};
  s.accel = Accel::Octree;
  const RenderResult lit = render(test::shared_context(), scene, s);
  EXPECT_GT(lit.walk.queries, lit.rays);  // and shadow rays
  // The subgroup stage's lanes all walk one path's rays, which the counts
  // would take for many walks: with the counting its auto is off, and a
  // threshold set is refused.
  s.accel = Accel::Octree;
  s.tail_depth = 2;
  s.tail_fill = 1000;
  s.walk_stats = true;
  EXPECT_EQ(render(test::shared_context(), scene, s).tail_subgroup, 0u);
  s.tail_subgroup = 1000000;
  EXPECT_THROW(render(test::shared_context(), scene, s), SettingError);
  s.walk_stats = false;
  if (fits_tail_subgroup(test::shared_context().info.subgroup_size))
    EXPECT_EQ(render(test::shared_context(), scene, s).tail_subgroup, 1000000u);
  else
    EXPECT_THROW(render(test::shared_context(), scene, s), SettingError);
  // So is one over another structure, whose leaves the lanes do not split.
  s.accel = Accel::Bvh;
  EXPECT_THROW(render(test::shared_context(), scene, s), SettingError);
}

// Instancing changes what is stored, not what is seen: one mesh placed nine
// times renders as nine copies of it, each placed once. (The copies are
// baked into world space and the shared ones tested in object space, so the
// rounding differs and a few paths go elsewhere: means within 0.5%, SSIM
// >= 0.98.) With every instance baked (--instancing bake) the device holds
// the same world-space triangles as for the copies: the same image, bit for
// bit, with every structure.
TEST_F(RenderTest, InstancesRenderAsCopies) {
  Scene copies = test::furnace_scene();
  copies.sky.type = SkyType::Gradient;
  copies.materials = {test::lambertian({0.7f, 0.4f, 0.3f}), test::glass(1.5f)};
  for (int i = 0; i < 9; ++i)
    test::place(copies, test::icosphere(2, uint32_t(i & 1), i % 3 == 0),
                glm::translate(glm::mat4(1.0f), glm::vec3(float(i % 3) - 1.0f, float(i / 3) - 1.0f, 0.0f)) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(i == 4 ? -0.4f : 0.4f, 0.4f, 0.4f)));
  Scene shared = copies;
  // The four distinct meshes: (material 0, smooth), (1, smooth), (0, flat), (1, flat).
  shared.meshes = {copies.meshes[0], copies.meshes[3], copies.meshes[2], copies.meshes[1]};
  for (int i = 0; i < 9; ++i) shared.instances[size_t(i)].mesh = uint32_t((i % 3 == 0 ? 0 : 2) + (i & 1));
  ASSERT_EQ(instanced_triangle_count(shared), instanced_triangle_count(copies));
  for (Accel accel : {Accel::Octree, Accel::Brute}) {
    RenderSettings s;
    s.width = 48;
    s.height = 32;
    s.accel = accel;
    s.spp = 16;
    s.octree.instancing = Instancing::Keep;  // 2.25x the stored triangles: Auto would keep them too
    const RenderResult a = render(test::shared_context(), shared, s);
    const RenderResult b = render(test::shared_context(), copies, s);
    double sum_a = 0, sum_b = 0;
    for (size_t i = 0; i < a.mean.rgb.size(); ++i) {
      sum_a += a.mean.rgb[i];
      sum_b += b.mean.rgb[i];
    }
    EXPECT_LE(std::abs(sum_a - sum_b) / sum_b, 0.005) << accel_name(accel);
    EXPECT_GE(compare_images(a.mean, b.mean).ssim, 0.98) << accel_name(accel);
    EXPECT_EQ(a.nonfinite_samples + b.nonfinite_samples, 0u);
  }
  for (Accel accel : {Accel::Octree, Accel::Bvh, Accel::Brute}) {
    RenderSettings s;
    s.width = 48;
    s.height = 32;
    s.accel = accel;
    s.spp = 4;
    s.octree.instancing = Instancing::Bake;
    SCOPED_TRACE(std::string(accel_name(accel)) + ": every instance baked against the copies' image");
    expect_same_result(render(test::shared_context(), shared, s), render(test::shared_context(), copies, s));
  }
}

// A scene that is one mesh instance and no sphere on the device (its meshes
// all baked) is queried without the top-level walk (SPEC_ONE_INSTANCE,
// accel/closest_hit.glsl): every query, shadow rays too, enters the
// instance, and the image is the one the walk gives, bit for bit, with
// either tree: the walk runs again once a tiny sphere far below the
// scene, which no ray meets, is a second top-level primitive.
TEST_F(RenderTest, OneInstanceIsQueriedWithoutTheTopLevelWalk) {
  Scene one = test::furnace_scene();
  one.sky.type = SkyType::Gradient;
  one.materials = {test::lambertian({0.7f, 0.4f, 0.3f}), test::glass(1.5f)};
  for (int i = 0; i < 3; ++i)
    test::place(one, test::icosphere(2, uint32_t(i & 1), i == 1),
                glm::translate(glm::mat4(1.0f), glm::vec3(1.2f * float(i - 1), 0.0f, 0.0f)) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
  one.lights = {test::point_light({0.0f, 3.0f, 2.0f}, 20.0f)};
  Scene walked = one;
  walked.spheres = {{{0.0f, -1e4f, 0.0f}, 1e-3f, 0}};
  for (Accel accel : {Accel::Octree, Accel::Bvh}) {
    SCOPED_TRACE(accel_name(accel));
    RenderSettings s;
    s.width = 48;
    s.height = 32;
    s.spp = 4;
    s.accel = accel;
    s.walk_stats = true;
    const RenderResult a = render(test::shared_context(), one, s);
    const RenderResult b = render(test::shared_context(), walked, s);
    EXPECT_EQ(a.walk.instances, a.walk.queries);  // camera, bounce and shadow rays alike
    EXPECT_GT(a.walk.queries, a.rays);            // shadow rays were asked
    if (accel == Accel::Bvh) {
      EXPECT_LT(b.walk.instances, b.walk.queries);  // its walk tests the instance's box first
    }
    expect_same_result(a, b);  // one instance: the image of the top-level walk
    EXPECT_EQ(a.nonfinite_samples + b.nonfinite_samples, 0u);
  }
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
