#include "render/path_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/trigonometric.hpp>

#include "render/gpu_layout.h"
#include "path_trace_fp16.h"
#include "path_trace_fp16_all.h"
#include "path_trace_fp32.h"
#include "vk/resources.h"

namespace octrace {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string mib_string(uint64_t bytes) {
  return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB";
}

// The camera of "Ray Tracing in One Weekend" v4, in double on the host: a
// viewport on the focus plane, `vfov` tall, and a thin lens of diameter
// `aperture` at lookfrom.
void set_camera(gpu::FrameParams& f, const Camera& c, int width, int height) {
  glm::dvec3 from(c.lookfrom), at(c.lookat), vup(c.vup);
  double h = std::tan(glm::radians(double(c.vfov)) / 2.0);
  double viewport_h = 2.0 * h * c.focus_dist;
  double viewport_w = viewport_h * double(width) / double(height);
  glm::dvec3 w = glm::normalize(from - at);
  glm::dvec3 u = glm::normalize(glm::cross(vup, w));
  glm::dvec3 v = glm::cross(w, u);
  glm::dvec3 horizontal = viewport_w * u;
  glm::dvec3 vertical = -viewport_h * v;  // rows go down the image
  glm::dvec3 corner = from - double(c.focus_dist) * w - horizontal / 2.0 - vertical / 2.0;
  f.cam_origin = glm::vec3(from);
  f.lens_radius = c.aperture / 2.0f;
  f.lens_u = glm::vec3(u);
  f.lens_v = glm::vec3(v);
  f.pixel00 = glm::vec3(corner);
  f.pixel_du = glm::vec3(horizontal / double(width));
  f.pixel_dv = glm::vec3(vertical / double(height));
}

void set_sky(gpu::FrameParams& f, const Sky& sky) {
  f.sky_type = uint32_t(sky.type);
  f.sky_a = sky.type == SkyType::Uniform ? sky.radiance : sky.down;
  f.sky_b = sky.up;
}

}  // namespace

const char* precision_name(Precision p) {
  switch (p) {
    case Precision::FP16: return "fp16";
    case Precision::FP16All: return "fp16-all";
    default: return "fp32";
  }
}

Precision parse_precision(const std::string& name) {
  for (Precision p : {Precision::FP32, Precision::FP16, Precision::FP16All})
    if (name == precision_name(p)) return p;
  throw InputError("--precision: expected fp32, fp16 or fp16-all, got \"" + name + "\"");
}

void validate_settings(const RenderSettings& s) {
  if (s.width < 1 || s.height < 1)
    throw InputError("--size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     ": width and height must be >= 1");
  // The dispatch grid is at most 65535 workgroups of 8 per dimension on every
  // device we know; far above any sensible image.
  const int max_side = 65535 * int(gpu::WORKGROUP_SIZE);
  if (s.width > max_side || s.height > max_side)
    throw InputError("--size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     ": each side must be <= " + std::to_string(max_side));
  if (s.spp < 1) throw InputError("--spp: must be >= 1");
  if (uint64_t(s.first_sample) + s.spp > (uint64_t(1) << 32))
    throw InputError("--first-sample: first sample + spp must be <= 2^32");
  if (s.spp > (1u << 24))
    throw InputError("--spp: must be <= 16777216 (sample counts are exact fp32 integers)");
  if (s.max_depth < 1) throw InputError("--depth: must be >= 1");
}

struct PathTracer::State {
  const VulkanContext& ctx;
  RenderSettings settings;
  RenderTimings timings;
  uint64_t pixels = 0;
  OctreeStats octree;
  SceneFeatures features;
  Buffer frame, spheres, sphere_materials, materials, accum_sum, accum_comp, accum_sq, stats, nodes, refs;
  ComputePipeline pipeline;
  VkQueryPool queries = VK_NULL_HANDLE;

  explicit State(const VulkanContext& c) : ctx(c) {}
  ~State() {
    if (queries) vkDestroyQueryPool(ctx.device, queries, nullptr);
  }
};

PathTracer::PathTracer(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings)
    : state_(std::make_unique<State>(ctx)) {
  validate_settings(settings);
  State& s = *state_;
  s.settings = settings;
  s.pixels = uint64_t(settings.width) * uint64_t(settings.height);

  // Every buffer must fit in one storage-buffer binding on this device; say
  // which one does not, and why, before asking the driver for memory.
  const uint64_t accum_bytes = s.pixels * sizeof(glm::vec4);
  const uint64_t limit = ctx.limits.maxStorageBufferRange;
  if (accum_bytes > limit)
    throw InputError("--size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                     ": the accumulation buffers need " + mib_string(accum_bytes) +
                     " each, the device allows " + mib_string(limit) + " per buffer");
  const uint64_t sphere_bytes = scene.spheres.size() * sizeof(gpu::GpuSphere);
  if (sphere_bytes > limit)
    throw InputError(std::to_string(scene.spheres.size()) + " spheres need " + mib_string(sphere_bytes) +
                     ", the device allows " + mib_string(limit) + " per buffer");

  auto start = Clock::now();
  Octree octree;
  if (settings.accel == Accel::Octree) {
    octree = build_octree(scene.spheres, settings.octree);
    s.octree = octree.stats;
    s.timings.accel_build_ms = ms_since(start);
    const uint64_t node_bytes = octree.nodes.size() * sizeof(gpu::GpuOctreeNode);
    const uint64_t ref_bytes = octree.refs.size() * sizeof(uint32_t);
    if (std::max(node_bytes, ref_bytes) > limit)
      throw InputError("the octree of " + std::to_string(scene.spheres.size()) + " spheres needs " +
                       mib_string(std::max(node_bytes, ref_bytes)) + " in one buffer, the device allows " +
                       mib_string(limit) + " (try a larger --octree-leaf)");
  }

  start = Clock::now();
  std::vector<gpu::GpuSphere> spheres(scene.spheres.size());
  std::vector<uint32_t> sphere_materials(scene.spheres.size());
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    spheres[i] = {scene.spheres[i].center, scene.spheres[i].radius};
    sphere_materials[i] = scene.spheres[i].material;
  }
  const bool half = settings.precision != Precision::FP32;
  if (half && !ctx.fp16_enabled)
    throw InputError(std::string("--precision ") + precision_name(settings.precision) + ": the device " +
                     ctx.info.name + " lacks " + (ctx.info.shader_float16 ? "storageBuffer16BitAccess" : "shaderFloat16"));
  std::vector<gpu::GpuMaterial> materials(scene.materials.size());
  std::vector<gpu::GpuMaterialHalf> materials_half(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    gpu::GpuMaterial& g = materials[i];
    g.type = uint32_t(m.type);
    g.color = m.type == MaterialType::Emissive ? m.radiance : m.albedo;
    g.fuzz = m.fuzz;
    g.ior = m.ior;
    // Half's largest value is 65504: a brighter emitter would become inf.
    if (half && (g.color.r > 65504.0f || g.color.g > 65504.0f || g.color.b > 65504.0f))
      throw InputError("materials[" + std::to_string(i) + "]: radiance above 65504 does not fit --precision " +
                       precision_name(settings.precision));
    materials_half[i].color_type = {glm::packHalf1x16(g.color.r), glm::packHalf1x16(g.color.g),
                                    glm::packHalf1x16(g.color.b), glm::packHalf1x16(float(g.type))};
    materials_half[i].params = {glm::packHalf1x16(g.fuzz), glm::packHalf1x16(g.ior), 0, 0};
  }
  gpu::FrameParams frame{};
  set_camera(frame, scene.camera, settings.width, settings.height);
  set_sky(frame, scene.sky);
  frame.width = uint32_t(settings.width);
  frame.height = uint32_t(settings.height);
  frame.max_depth = settings.max_depth;
  frame.sample_seed = settings.sample_seed;
  frame.sphere_count = uint32_t(scene.spheres.size());
  frame.big_count = octree.big_count;

  create_buffer(s.frame, ctx, sizeof(frame), false, "frame parameters");
  create_buffer(s.spheres, ctx, sphere_bytes, false, "sphere buffer");
  create_buffer(s.sphere_materials, ctx, sphere_materials.size() * 4, false, "sphere material buffer");
  const size_t material_bytes = half ? materials_half.size() * sizeof(gpu::GpuMaterialHalf)
                                    : materials.size() * sizeof(gpu::GpuMaterial);
  create_buffer(s.materials, ctx, material_bytes, false, "material buffer");
  create_buffer(s.accum_sum, ctx, accum_bytes, false, "accumulation buffer");
  create_buffer(s.accum_comp, ctx, accum_bytes, false, "accumulation buffer");
  create_buffer(s.accum_sq, ctx, accum_bytes, false, "accumulation buffer");
  create_buffer(s.stats, ctx, sizeof(gpu::RenderStats), false, "statistics buffer");
  create_buffer(s.nodes, ctx, octree.nodes.size() * sizeof(gpu::GpuOctreeNode), false, "octree node buffer");
  create_buffer(s.refs, ctx, octree.refs.size() * sizeof(uint32_t), false, "octree reference buffer");
  upload_buffer(ctx, s.nodes, octree.nodes.data(), octree.nodes.size() * sizeof(gpu::GpuOctreeNode));
  upload_buffer(ctx, s.refs, octree.refs.data(), octree.refs.size() * sizeof(uint32_t));
  upload_buffer(ctx, s.frame, &frame, sizeof(frame));
  upload_buffer(ctx, s.spheres, spheres.data(), sphere_bytes);
  upload_buffer(ctx, s.sphere_materials, sphere_materials.data(), sphere_materials.size() * 4);
  upload_buffer(ctx, s.materials, half ? static_cast<const void*>(materials_half.data()) : materials.data(),
                material_bytes);
  s.timings.upload_ms = ms_since(start);

  start = Clock::now();
  const uint32_t accel = settings.accel == Accel::Octree ? gpu::ACCEL_OCTREE : gpu::ACCEL_BRUTE;
  s.features = settings.all_effects ? all_features(scene) : scene_features(scene);
  const SceneFeatures& f = s.features;
  // FEATURE_SKY: the sky's type, or SKY_RUNTIME for the general pipeline; a
  // black sky of any type is specialised to none.
  const uint32_t sky = settings.all_effects ? gpu::SKY_RUNTIME : f.sky_black ? gpu::SKY_NONE : uint32_t(f.sky);
  const uint32_t* spirv = path_trace_fp32_spv;
  size_t spirv_bytes = sizeof(path_trace_fp32_spv);
  if (settings.precision == Precision::FP16) {
    spirv = path_trace_fp16_spv;
    spirv_bytes = sizeof(path_trace_fp16_spv);
  } else if (settings.precision == Precision::FP16All) {
    spirv = path_trace_fp16_all_spv;
    spirv_bytes = sizeof(path_trace_fp16_all_spv);
  }
  create_compute_pipeline(s.pipeline, ctx, spirv, spirv_bytes, gpu::BINDING_COUNT, sizeof(gpu::PassConstants),
                          {{gpu::SPEC_ACCEL, accel},
                           {gpu::SPEC_LAMBERTIAN, f.lambertian},
                           {gpu::SPEC_METAL, f.metal},
                           {gpu::SPEC_FUZZ, f.fuzzy_metal},
                           {gpu::SPEC_DIELECTRIC, f.dielectric},
                           {gpu::SPEC_EMISSIVE, f.emissive},
                           {gpu::SPEC_DEFOCUS, f.defocus},
                           {gpu::SPEC_SKY, sky},
                           {gpu::SPEC_ANY_LIGHT, f.any_light}});
  bind_buffers(s.pipeline, {&s.frame, &s.spheres, &s.sphere_materials, &s.materials, &s.accum_sum,
                            &s.accum_comp, &s.accum_sq, &s.stats, &s.nodes, &s.refs});
  s.timings.pipeline_ms = ms_since(start);

  VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  query_info.queryCount = 2;
  VK_CHECK(vkCreateQueryPool(ctx.device, &query_info, nullptr, &s.queries));
  reset();
}

PathTracer::~PathTracer() = default;

const RenderTimings& PathTracer::setup_timings() const { return state_->timings; }
const OctreeStats& PathTracer::octree_stats() const { return state_->octree; }
const SceneFeatures& PathTracer::features() const { return state_->features; }
const Buffer& PathTracer::accum_sum() const { return state_->accum_sum; }
const Buffer& PathTracer::accum_comp() const { return state_->accum_comp; }
const RenderSettings& PathTracer::settings() const { return state_->settings; }

void PathTracer::reset() {
  State& s = *state_;
  submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
    for (Buffer* b : {&s.accum_sum, &s.accum_comp, &s.accum_sq, &s.stats})
      vkCmdFillBuffer(cmd, b->buffer, 0, VK_WHOLE_SIZE, 0);
  });
}

void PathTracer::record_passes(VkCommandBuffer cmd, uint32_t first_sample, uint32_t count) const {
  const State& s = *state_;
  const uint32_t groups_x = (uint32_t(s.settings.width) + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE;
  const uint32_t groups_y = (uint32_t(s.settings.height) + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.layout, 0, 1, &s.pipeline.set, 0,
                          nullptr);
  for (uint32_t i = 0; i < count; ++i) {
    if (i > 0) compute_barrier(cmd);
    gpu::PassConstants pc{first_sample + i, s.settings.rr_depth ? s.settings.rr_depth : UINT32_MAX};
    vkCmdPushConstants(cmd, s.pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, groups_x, groups_y, 1);
  }
}

double PathTracer::run_passes(uint32_t first_sample, uint32_t count) {
  State& s = *state_;
  submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, s.queries, 0, 2);
    // Earlier submissions (reset, previous batches) wrote the accumulation.
    compute_barrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s.queries, 0);
    record_passes(cmd, first_sample, count);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s.queries, 1);
  });
  uint64_t stamps[2] = {0, 0};
  VK_CHECK(vkGetQueryPoolResults(s.ctx.device, s.queries, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return double(stamps[1] - stamps[0]) * double(s.ctx.limits.timestampPeriod) * 1e-6;
}

RenderResult PathTracer::read_result() {
  State& s = *state_;
  auto start = Clock::now();
  std::vector<glm::vec4> sum(s.pixels), comp(s.pixels), sq(s.pixels);
  gpu::RenderStats stats{};
  download_buffer(s.ctx, s.accum_sum, sum.data(), s.pixels * sizeof(glm::vec4));
  download_buffer(s.ctx, s.accum_comp, comp.data(), s.pixels * sizeof(glm::vec4));
  download_buffer(s.ctx, s.accum_sq, sq.data(), s.pixels * sizeof(glm::vec4));
  download_buffer(s.ctx, s.stats, &stats, sizeof(stats));

  RenderResult r;
  r.mean.width = r.variance_of_mean.width = s.settings.width;
  r.mean.height = r.variance_of_mean.height = s.settings.height;
  r.mean.rgb.resize(s.pixels * 3);
  r.variance_of_mean.rgb.resize(s.pixels * 3);
  r.nonfinite_samples = stats.nonfinite_samples;
  r.count.resize(s.pixels);
  r.min_samples = UINT32_MAX;
  for (uint64_t i = 0; i < s.pixels; ++i) {
    double n = sum[i].w;
    r.min_samples = std::min(r.min_samples, uint32_t(n));
    r.count[i] = float(n);
    for (int c = 0; c < 3; ++c) {
      // The Kahan sum is sum - comp (comp holds what the float sum overshot).
      double total = double(sum[i][c]) - double(comp[i][c]);
      double mean = n > 0 ? total / n : 0.0;
      double var = n > 1 ? double(sq[i][c]) / (n - 1) : 0.0;
      r.mean.rgb[3 * i + c] = float(mean);
      r.variance_of_mean.rgb[3 * i + c] = n > 0 ? float(var / n) : 0.0f;
    }
  }
  if (s.pixels == 0) r.min_samples = 0;
  s.timings.readback_ms = ms_since(start);
  r.timings = s.timings;
  r.octree = s.octree;
  r.features = s.features;
  return r;
}

RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const ProgressFn& progress) {
  PathTracer tracer(ctx, scene, settings);
  double device_ms = 0;
  auto start = Clock::now();
  // Batches grow until one takes about a quarter second: few submissions for
  // fast passes, regular progress and no driver watchdog for slow ones.
  uint32_t done = 0, batch = 1;
  while (done < settings.spp) {
    uint32_t n = std::min(batch, settings.spp - done);
    auto batch_start = Clock::now();
    device_ms += tracer.run_passes(settings.first_sample + done, n);
    double batch_ms = ms_since(batch_start);
    done += n;
    if (progress) progress(done, settings.spp);
    double per_pass = batch_ms / n;
    batch = uint32_t(std::clamp(250.0 / std::max(per_pass, 1e-3), 1.0, 1024.0));
  }
  double wall_ms = ms_since(start);
  RenderResult r = tracer.read_result();
  r.timings.render_device_ms = device_ms;
  r.timings.render_wall_ms = wall_ms;
  return r;
}

}  // namespace octrace
