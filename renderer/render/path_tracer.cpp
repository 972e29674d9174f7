#include "render/path_tracer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdlib>
#include <bit>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

#include "accumulate.h"
#include "camera_tiles.h"
#include "camera_tiles_split.h"
#include "core/clock.h"
#include "core/errors.h"
#include "core/text.h"
#include "path_trace_fp16.h"
#include "path_trace_fp16_all.h"
#include "path_trace_fp16_all_split.h"
#include "path_trace_fp16_split.h"
#include "path_trace_fp32.h"
#include "path_trace_fp32_split.h"
#include "render/camera.h"
#include "render/gpu_layout.h"
#include "render/gpu_scene.h"
#include "vk/resources.h"
#include "vk/timer.h"

namespace octrace {

PassSettings pass_settings(const Scene& scene, const RenderSettings& settings) {
  return {scene.camera, settings.bounce_limit, settings.sample_seed, settings.rr_depth};
}

// Invocations of a path-tracing workgroup (path_trace.comp's local size).
constexpr uint32_t kWorkgroupInvocations = gpu::WORKGROUP_SIZE * gpu::WORKGROUP_SIZE;
// The subgroup stage's fewest lanes: one for each of a node's children.
constexpr uint32_t kTailSubgroupMinLanes = 8;
bool fits_tail_subgroup(uint32_t subgroup_size) {
  return subgroup_size >= kTailSubgroupMinLanes && subgroup_size <= kWorkgroupInvocations;
}

struct PathTracer::State {
  const VulkanContext& ctx;
  RenderSettings settings;
  RenderTimings timings;
  SceneFeatures scene_features, every_feature;  // for --effects auto and all
  SceneFeatures features;                        // what the pipeline is specialised to

  // Lanes (PassParams.sample_lanes) are compiled in on GPUs, and on software
  // devices only when asked for: llvmpipe (Mesa 22.3) lost whole workgroups
  // of the pipeline with the barrier when paths were long (brute force over
  // 8000 spheres, depth >= 10), and a CPU device has no tail to hide anyway.
  bool sample_lanes_enabled() const { return !ctx.info.software || settings.sample_lanes > 1; }
  // RenderSettings::big_list for the pipeline specialised to `f`.
  bool big_leaf(const SceneFeatures& f) const {
    if (settings.big_list != BigList::Auto) return settings.big_list == BigList::FirstLeaf;
    return ctx.info.software || !f.triangles;
  }
  // SPEC_ONE_INSTANCE: the scene on the device is one mesh instance and no
  // sphere. Not in the general pipeline (`--effects all`), which keeps the
  // top-level walk as it keeps every effect: one pipeline for every scene,
  // the one the tests compare the specialised ones with.
  bool one_instance() const {
    return !settings.all_effects && scene.values.sphere_count == 0 && scene.values.instance_count == 1;
  }
  // RenderSettings::octant_culling for this device and scene.
  bool octant_culling() const {
    if (settings.octant_culling != OctantCulling::Auto) return settings.octant_culling == OctantCulling::On;
    return default_octant_culling(ctx.info, scene_features.triangles);
  }
  // RenderSettings::bvh_walk for this device and tree: whether the top
  // level's binary BVH walk is in while-while form.
  bool bvh_top_while() const {
    if (scene.tree != Accel::Bvh) return false;
    if (settings.bvh_walk != BvhWalk::Auto) return settings.bvh_walk == BvhWalk::WhileWhile;
    return default_bvh_top_while(ctx.info, scene.octree.top_refs_per_leaf());
  }
  // RenderSettings::nearest_child for this device: whether the octree walk holds it.
  bool hold_nearest() const {
    if (settings.nearest_child != NearestChild::Auto) return settings.nearest_child == NearestChild::Held;
    return ctx.info.software;
  }
  // RenderSettings::tail_depth for this device: the bounce at which the
  // tail queue takes paths (0: no queue). Auto queues on GPUs, and on a
  // CPU device only above kCpuWholePathBounces: there the queue's levels
  // are another translation of the path tracer (0.5-0.8 s on a cold
  // cache, the cold test suite 1.5x as long; optimisation logs 49 and
  // 156), but longer paths in one invocation near llvmpipe's loop limit,
  // which cuts them short (RenderResult::cut_paths), and a level traces a
  // few bounces a dispatch.
  uint32_t tail_depth() const {
    if (settings.tail_depth != RenderSettings::kTailAuto) return settings.tail_depth;
    if (ctx.info.software && settings.bounce_limit <= kCpuWholePathBounces) return 0u;
    return kTailDepthDefault;
  }
  static_assert(kMaxTailLevels == gpu::MAX_TAIL_LEVELS);
  // RenderSettings::tail_subgroup as set or its auto (default_tail_subgroup
  // with the octree, off with walk_stats; validate_settings refuses a count
  // with either other), before tail_step() decides whether there are levels
  // (0: none).
  uint32_t subgroup_setting() const {
    if (settings.tail_subgroup != RenderSettings::kTailAuto) return settings.tail_subgroup;
    if (settings.accel != Accel::Octree || settings.walk_stats) return 0u;
    return default_tail_subgroup(ctx.info, scene_features.triangles);
  }
  // RenderSettings::tail_fill as set (auto: the subgroup stage's threshold
  // where there is one, so that the levels pack their paths until the
  // stage takes them; else the device's resident threads, 0 where
  // unknown), before tail_step() decides whether there are levels.
  uint32_t fill_setting() const {
    if (settings.tail_fill != RenderSettings::kTailAuto) return settings.tail_fill;
    if (subgroup_setting() > 0) return subgroup_setting();
    return uint32_t(std::min<uint64_t>(ctx.info.resident_threads, UINT32_MAX));
  }
  // RenderSettings::tail_step resolved (0: one tail level). Auto: levels
  // for scenes of spheres alone, and with triangles where a fill applies
  // (optimisation logs 63 and 64: on the H200 the levels took 40% off
  // 8,000 spheres; without a fill they made the balloon 45% slower, with
  // the device's fill it is unchanged and the engine 11-15% faster); on a
  // CPU device levels always, where one tail stage would trace the rest
  // of a path in one invocation, toward llvmpipe's loop limit (the
  // balloon's passes the same either way at 200 bounces, log 157).
  uint32_t tail_step() const {
    if (tail_depth() == 0) return 0u;
    if (settings.tail_step != RenderSettings::kTailAuto) return settings.tail_step;
    if (ctx.info.software) return kTailStepDefault;  // one tail stage would take the rest of a path
    return scene_features.triangles && fill_setting() == 0 ? 0u : kTailStepDefault;
  }
  // RenderSettings::tail_fill resolved (0: every level queues its survivors).
  uint32_t tail_fill() const { return tail_step() == 0 ? 0u : fill_setting(); }
  // RenderSettings::tail_subgroup resolved (0: no subgroup stage).
  // Auto: only with levels.
  uint32_t tail_subgroup() const {
    if (tail_depth() == 0) return 0u;
    if (settings.tail_subgroup != RenderSettings::kTailAuto) return subgroup_setting();
    return tail_step() > 0 ? subgroup_setting() : 0u;
  }
  // Whether a dispatch runs as head and sum (and tail, with a queue): one
  // sample per invocation and each pixel's values added after. Auto on a
  // software device has it without a queue: its compiler (llvmpipe 22.3)
  // ends a loop after 65535 iterations counted over the whole invocation,
  // so the whole paths take one sample per dispatch there (optimisation
  // log 16), and the head takes a batch in one dispatch instead, which
  // keeps lavapipe's threads busy: the default scene's passes 18% faster.
  bool staged() const {
    return tail_depth() > 0 || (ctx.info.software && settings.tail_depth == RenderSettings::kTailAuto);
  }
  // Samples one dispatch takes (RenderSettings::samples_per_dispatch; 0
  // here: the whole batch): one for the whole paths on a software device.
  uint32_t samples_per_dispatch() const {
    if (settings.samples_per_dispatch) return settings.samples_per_dispatch;
    return ctx.info.software && !staged() ? 1u : 0u;
  }
  GpuScene scene;
  // The lens the tree's boxes left hidden parts out for (HiddenParts::Cull,
  // where some sphere's box shrank): a pass must start its rays there.
  std::optional<Camera> culled_for;
  void note_culling(const Scene& sc) {
    const OctreeStats& o = scene.octree;
    culled_for.reset();
    if (settings.accel != Accel::Brute && scene.tree != Accel::Brute && (o.spheres_clipped > 0 || o.spheres_hidden > 0))
      culled_for = sc.camera;
  }
  uint64_t sphere_count = 0;  // the scene's
  // The camera's tiles (RenderSettings::camera_tiles): why the scene on the
  // device cannot have them, or nothing where it can.
  std::string camera_tiles_unfit() const {
    if (settings.accel == Accel::Brute) return "brute force walks no tree";
    if (scene_features.triangles) return "the lists hold spheres, and the scene has triangles";
    if (sphere_count == 0) return "the scene has no sphere";
    // No bound on the size: the lists take 132 bytes for 64 pixels, the
    // accumulation buffers 16 a pixel each, which create_accumulation
    // refuses first where they do not fit. So the answer does not change
    // with resize(), which keeps the pipelines.
    return "";
  }
  uint64_t camera_tile_count() const {
    const uint64_t across = (uint64_t(settings.width) + gpu::CAMERA_TILE_PIXELS - 1) / gpu::CAMERA_TILE_PIXELS;
    return across * ((uint64_t(settings.height) + gpu::CAMERA_TILE_PIXELS - 1) / gpu::CAMERA_TILE_PIXELS);
  }
  uint64_t camera_tile_bytes() const { return camera_tile_count() * (1 + gpu::CAMERA_TILE_REFS) * sizeof(uint32_t); }
  // RenderSettings::tail_fetch resolved (create_pipeline refuses On on a
  // CPU device): whether the tail stage, where there is one, takes its
  // paths from the level's counter.
  bool tail_fetch() const {
    if (tail_depth() == 0 || settings.tail_fetch == TailFetch::Off || ctx.info.software) return false;
    return settings.tail_fetch == TailFetch::On || scene_features.triangles ||
           sphere_count >= (settings.accel == Accel::Bvh ? kTailFetchSpheresBvh : kTailFetchSpheresOctree);
  }
  // RenderSettings::camera_tiles resolved (create_pipeline refuses On
  // where they cannot be).
  bool camera_tiles() const {
    if (settings.camera_tiles == CameraTiles::Off || !camera_tiles_unfit().empty()) return false;
    return settings.camera_tiles == CameraTiles::On || default_camera_tiles(ctx.info, settings.accel, sphere_count);
  }
  Buffer accum_sum, accum_comp, accum_sq, stats;
  // The camera's tiles (shared.h BINDING_CAMERA_TILES) and the stage that
  // writes them; a placeholder and no pipeline without.
  Buffer camera_tile_lists;
  ComputePipeline camera_tiles_pipeline;
  // The camera and size the lists hold (record_passes makes them again only
  // for another; create_camera_tiles forgets them with the buffer): what
  // camera_tiles.comp reads of PassParams.
  struct CameraTilesFor {
    glm::vec3 origin, pixel00, du, dv;
    float lens_radius;
    uint32_t width, height;
    bool operator==(const CameraTilesFor&) const = default;
  };
  mutable std::optional<CameraTilesFor> camera_tiles_for;
  // With the tail queue: each sample's value per [sample of the dispatch]
  // [pixel], the queue and its TailControl (shared.h); 16-byte placeholders
  // without.
  Buffer tail_values, tail_queue, tail_control;
  uint32_t tail_samples = 0;   // samples one head dispatch takes (tail_values holds them)
  uint32_t tail_capacity = 0;  // GpuTailPath entries of tail_queue
  // The whole paths (STAGE_WHOLE), or staged its head, with a queue its
  // tail and with RenderSettings::tail_subgroup its subgroup stage
  // (path_trace.comp STAGE_*), and the sum (accumulate.comp).
  ComputePipeline pipeline, tail_pipeline, tail_subgroup_pipeline, accumulate_pipeline;
  GpuTimer timer;
  // RenderSettings::dispatch_times: a timestamp after each dispatch of a
  // batch (0 at its start; the pool grows to the batch's most), what each
  // dispatch was, and the sums since the last reset; and a copy of each
  // dispatch of samples' TailControl array (the paths its levels took).
  struct DispatchMark {
    const char* stage;
    uint32_t level;
    uint32_t samples;  // tail levels: which dispatch of samples of the batch
  };
  GpuTimer dispatch_timer;
  Buffer dispatch_controls;
  mutable std::vector<DispatchMark> dispatch_marks;
  mutable uint32_t dispatch_samples = 0;  // dispatches of samples recorded in the batch
  // Whether run_passes is recording a batch it times (a caller of
  // record_passes of its own, the preview, times none).
  mutable bool dispatch_recording = false;
  std::vector<DispatchTime> dispatch_sums;
  // After a dispatch: its timestamp, with its stage and tail level (while
  // the pool, which run_passes sized to the batch, has room).
  void mark_dispatch(VkCommandBuffer cmd, const char* stage, uint32_t level = 0) const {
    if (!dispatch_recording || dispatch_marks.size() + 1 >= dispatch_timer.count) return;
    dispatch_marks.push_back({stage, level, dispatch_samples});
    timer_mark(dispatch_timer, cmd, uint32_t(dispatch_marks.size()));
  }

  explicit State(const VulkanContext& c) : ctx(c) {}
  uint64_t pixels() const { return uint64_t(settings.width) * uint64_t(settings.height); }
  void create_accumulation();
  void create_camera_tiles();
  void bind_accumulation();
  void create_pipeline();
  void create_stage(ComputePipeline& p, uint32_t stage, const uint32_t* spirv, size_t spirv_bytes);
  void record_staged_passes(VkCommandBuffer cmd, gpu::PassParams pc, uint32_t first_sample, uint32_t count,
                            uint32_t per_dispatch) const;
  uint32_t batch_granule() const;
};

// Bytes the tail queue's buffers may take each: a quarter GiB on a GPU, 32
// MiB in a software device's host memory, or the device's limit per buffer
// if that is less.
static uint64_t tail_buffer_bytes(const VulkanContext& ctx) {
  return std::min<uint64_t>(uint64_t(1) << (ctx.info.software ? 25 : 28), ctx.limits.maxStorageBufferRange);
}

// The accumulation state, three arrays of one vec4 per pixel (shared.h).
void PathTracer::State::create_accumulation() {
  State& s = *this;
  const uint64_t bytes = s.pixels() * sizeof(glm::vec4);
  const uint64_t limit = s.ctx.limits.maxStorageBufferRange;
  if (bytes > limit)
    throw SettingError("size", " " + std::to_string(s.settings.width) + "x" + std::to_string(s.settings.height) +
                                   ": the accumulation buffers need " + mib_string(bytes) +
                                   " each, the device allows " + mib_string(limit) + " per buffer");
  create_buffer(s.accum_sum, s.ctx, bytes, false, "accumulation buffer");
  create_buffer(s.accum_comp, s.ctx, bytes, false, "accumulation buffer");
  create_buffer(s.accum_sq, s.ctx, bytes, false, "accumulation buffer");
  // The tail queue: as many samples per head dispatch as tail_values holds
  // (in whole rounds of lanes, at most 16), and a queue for part of their
  // paths (tail_queue_entries). A head that finds the queue full finishes
  // its path itself: the size is a matter of speed, not of the image.
  s.tail_samples = s.tail_capacity = 0;
  // With tail levels, two halves: a level reads one and queues into the other.
  const uint64_t halves = s.tail_step() > 0 ? 2 : 1;
  if (s.staged()) {
    const uint64_t value_bytes = s.pixels() * sizeof(glm::vec4);
    uint64_t budget = tail_buffer_bytes(s.ctx);
    // A CPU device's head dispatch takes whole images per thread
    // (batch_granule) where the values of that many fit one buffer, past the
    // budget if need be: 1600x900 takes 23 MB a sample.
    uint32_t granule = 1;
    if (s.ctx.info.software) {
      granule = s.batch_granule();
      budget = std::max(budget, std::min<uint64_t>(granule * value_bytes, limit));
    }
    // At most 16 samples: what the H200 runs of log 49 took at 1200x800
    // (the budget's 17 in whole rounds of 8); more saves little per
    // dispatch and costs memory on small images.
    s.tail_samples = uint32_t(std::clamp<uint64_t>(budget / value_bytes, 1, 2 * gpu::MAX_SAMPLE_LANES));
    if (s.tail_samples >= gpu::MAX_SAMPLE_LANES) s.tail_samples -= s.tail_samples % gpu::MAX_SAMPLE_LANES;
    if (granule > 1 && s.tail_samples >= granule) s.tail_samples -= s.tail_samples % granule;
    // No more than a dispatch takes.
    if (s.samples_per_dispatch()) s.tail_samples = std::min(s.tail_samples, s.samples_per_dispatch());
    if (s.tail_depth() > 0)
      s.tail_capacity = tail_queue_entries(s.pixels() * s.tail_samples, !s.ctx.info.software,
                                           s.ctx.info.software ? budget : device_memory(s.ctx).bytes, limit, halves);
    if (s.settings.tail_queue_entries) s.tail_capacity = std::min(s.tail_capacity, s.settings.tail_queue_entries);
  }
  create_buffer(s.tail_values, s.ctx, uint64_t(s.tail_samples) * s.pixels() * sizeof(glm::vec4), false,
                "tail queue's values");
  create_buffer(s.tail_queue, s.ctx, halves * s.tail_capacity * sizeof(gpu::GpuTailPath), false, "tail queue");
  create_buffer(s.tail_control, s.ctx, gpu::MAX_TAIL_LEVELS * sizeof(gpu::TailControl), false,
                "tail queue's control");
}

uint32_t tail_queue_entries(uint64_t paths, bool gpu, uint64_t bytes, uint64_t limit, uint64_t halves) {
  const uint64_t entry = sizeof(gpu::GpuTailPath), group = gpu::WORKGROUP_SIZE * gpu::WORKGROUP_SIZE;
  const uint64_t wanted = gpu ? std::min(paths / 2, bytes / 8 / (halves * entry)) : std::min(paths / 4, bytes / entry);
  return uint32_t(std::min<uint64_t>({std::max(wanted, group), 65535 * group, limit / (halves * entry)}));
}

// The camera's tiles' buffer for the image's size, or a placeholder.
void PathTracer::State::create_camera_tiles() {
  State& s = *this;
  s.camera_tiles_for.reset();
  create_buffer(s.camera_tile_lists, s.ctx, s.camera_tiles() ? s.camera_tile_bytes() : 0, false, "camera's tiles");
}

void PathTracer::State::bind_accumulation() {
  State& s = *this;
  for (ComputePipeline* p : {&s.pipeline, &s.tail_pipeline, &s.tail_subgroup_pipeline, &s.accumulate_pipeline,
                             &s.camera_tiles_pipeline}) {
    if (p->pipeline == VK_NULL_HANDLE) continue;
    bind_buffers(*p, {{gpu::BINDING_ACCUM_SUM, &s.accum_sum},
                      {gpu::BINDING_ACCUM_COMP, &s.accum_comp},
                      {gpu::BINDING_ACCUM_SQ, &s.accum_sq},
                      {gpu::BINDING_STATS, &s.stats},
                      {gpu::BINDING_TAIL_VALUES, &s.tail_values},
                      {gpu::BINDING_TAIL_QUEUE, &s.tail_queue},
                      {gpu::BINDING_TAIL_CONTROL, &s.tail_control},
                      {gpu::BINDING_CAMERA_TILES, &s.camera_tile_lists}});
  }
}

// The pipeline of the settings' precision, accel and effects, bound to the
// scene on the device and the accumulation.
void PathTracer::State::create_pipeline() {
  State& s = *this;
  const RenderSettings& settings = s.settings;
  const bool half = settings.precision != Precision::FP32;
  if (half && !s.ctx.fp16_enabled)
    throw SettingError("precision", std::string(" ") + precision_name(settings.precision) + ": the device " +
                                        s.ctx.info.name + " lacks " +
                                        (s.ctx.info.shader_float16 ? "storageBuffer16BitAccess" : "shaderFloat16"));
  if (s.tail_subgroup() > 0 && !fits_tail_subgroup(s.ctx.info.subgroup_size))
    throw SettingError("tail_subgroup", ": the device " + s.ctx.info.name + "'s subgroups of " +
                                            std::to_string(s.ctx.info.subgroup_size) + " lanes are not " +
                                            std::to_string(kTailSubgroupMinLanes) + " to " +
                                            std::to_string(kWorkgroupInvocations) + " (a lane for each of a node's " +
                                            "children, within a workgroup); use auto or off");
  if (settings.tail_fetch == TailFetch::On && s.ctx.info.software)
    throw SettingError("tail_fetch", ": the device " + s.ctx.info.name +
                                         " is a CPU device, where llvmpipe ends a loop after 65,535 iterations " +
                                         "counted over the whole invocation and would lose the paths of one that " +
                                         "takes many; use auto or off");
  if (settings.camera_tiles == CameraTiles::On && !s.camera_tiles_unfit().empty())
    throw SettingError("camera_tiles", ": " + s.camera_tiles_unfit() + "; use auto or off");
  auto start = Clock::now();
  s.features = settings.all_effects ? s.every_feature : s.scene_features;
  // A scene split over several buffers (GpuScene::part_log2) has a pipeline
  // of its own (shaders/shared/scene_buffers.glsl), so that one in one
  // buffer per array runs the code it always has.
  const GpuScene& g = s.scene;
  const bool split = g.part_log2 != 0;
  const uint32_t* spirv = split ? path_trace_fp32_split_spv : path_trace_fp32_spv;
  size_t spirv_bytes = split ? sizeof(path_trace_fp32_split_spv) : sizeof(path_trace_fp32_spv);
  if (settings.precision == Precision::FP16) {
    spirv = split ? path_trace_fp16_split_spv : path_trace_fp16_spv;
    spirv_bytes = split ? sizeof(path_trace_fp16_split_spv) : sizeof(path_trace_fp16_spv);
  } else if (settings.precision == Precision::FP16All) {
    spirv = split ? path_trace_fp16_all_split_spv : path_trace_fp16_all_spv;
    spirv_bytes = split ? sizeof(path_trace_fp16_all_split_spv) : sizeof(path_trace_fp16_all_spv);
  }
  create_stage(s.pipeline, s.staged() ? gpu::STAGE_HEAD : gpu::STAGE_WHOLE, spirv, spirv_bytes);
  if (s.tail_depth() > 0) create_stage(s.tail_pipeline, gpu::STAGE_TAIL, spirv, spirv_bytes);
  else destroy_compute_pipeline(s.tail_pipeline);
  if (s.tail_subgroup() > 0) create_stage(s.tail_subgroup_pipeline, gpu::STAGE_TAIL_SUBGROUP, spirv, spirv_bytes);
  else destroy_compute_pipeline(s.tail_subgroup_pipeline);
  s.create_camera_tiles();
  if (s.camera_tiles()) {
    create_compute_pipeline(s.camera_tiles_pipeline, s.ctx, split ? camera_tiles_split_spv : camera_tiles_spv,
                            split ? sizeof(camera_tiles_split_spv) : sizeof(camera_tiles_spv), gpu::BINDING_COUNT,
                            sizeof(gpu::PassParams), {{gpu::SPEC_PART_LOG2, g.part_log2}});
    bind_buffers(s.camera_tiles_pipeline, {{gpu::BINDING_SCENE, &g.params},
                                           {gpu::BINDING_SPHERES, &g.spheres},
                                           {gpu::BINDING_BUFFER_PARTS, &g.part_table}});
  } else {
    destroy_compute_pipeline(s.camera_tiles_pipeline);
  }
  if (s.staged())
    create_compute_pipeline(s.accumulate_pipeline, s.ctx, accumulate_spv, sizeof(accumulate_spv), gpu::BINDING_COUNT,
                            sizeof(gpu::PassParams));
  else
    destroy_compute_pipeline(s.accumulate_pipeline);
  bind_accumulation();
  s.timings.pipeline_ms = ms_since(start);
}

// One pipeline of the path tracer (path_trace.comp STAGE_*), specialised to
// the settings and the features in force, bound to the scene on the device.
void PathTracer::State::create_stage(ComputePipeline& p, uint32_t stage, const uint32_t* spirv, size_t spirv_bytes) {
  State& s = *this;
  const RenderSettings& settings = s.settings;
  const bool half = settings.precision != Precision::FP32;
  const SceneFeatures& f = s.features;
  // SPEC_SKY: the sky's type, or SKY_RUNTIME for the general pipeline; a
  // black sky of any type is specialised to none.
  const uint32_t sky = settings.all_effects ? gpu::SKY_RUNTIME : f.sky_black ? gpu::SKY_NONE : uint32_t(f.sky);
  const uint32_t accel = settings.accel == Accel::Octree ? gpu::ACCEL_OCTREE
                         : settings.accel == Accel::Bvh ? gpu::ACCEL_BVH
                                                        : gpu::ACCEL_BRUTE;
  const GpuScene& g = s.scene;
  create_compute_pipeline(p, s.ctx, spirv, spirv_bytes, gpu::BINDING_COUNT, sizeof(gpu::PassParams),
                          {{gpu::SPEC_ACCEL, accel},
                           {gpu::SPEC_LAMBERTIAN, f.lambertian},
                           {gpu::SPEC_METAL, f.metal},
                           {gpu::SPEC_FUZZ, f.fuzzy_metal},
                           {gpu::SPEC_DIELECTRIC, f.dielectric},
                           {gpu::SPEC_EMISSIVE, f.emissive},
                           {gpu::SPEC_PBR, f.pbr},
                           {gpu::SPEC_DEFOCUS, f.defocus},
                           {gpu::SPEC_SAMPLE_LANES, s.sample_lanes_enabled()},
                           {gpu::SPEC_LANE_SAMPLE_SLOTS, lane_sample_slots(s.ctx.info)},
                           {gpu::SPEC_OCTANT_CULLING, s.octant_culling()},
                           {gpu::SPEC_BIG_LEAF, s.big_leaf(f)},
                           {gpu::SPEC_OCTREE_HOLD_NEAREST, s.hold_nearest()},
                           {gpu::SPEC_BVH_TOP_WIDE, g.tree == Accel::Bvh && g.octree.bvh_top_width > 2},
                           {gpu::SPEC_BVH_MESH_WIDE, g.tree == Accel::Bvh && g.octree.bvh_mesh_width > 2},
                           {gpu::SPEC_BVH_TOP_WHILE, s.bvh_top_while()},
                           {gpu::SPEC_SPHERES_IN_TREE_ORDER, g.octree.bvh_sphere_order},
                           {gpu::SPEC_ONE_INSTANCE, one_instance()},
                           {gpu::SPEC_WALK_STATS, settings.walk_stats},
                           {gpu::SPEC_SKY, sky},
                           {gpu::SPEC_ANY_LIGHT, f.any_light},
                           {gpu::SPEC_SPHERES, f.spheres},
                           {gpu::SPEC_TRIANGLES, f.triangles},
                           {gpu::SPEC_VERTEX_NORMALS, f.vertex_normals},
                           {gpu::SPEC_TEXTURES, f.textures},
                           {gpu::SPEC_SURFACE_EMISSION, f.surface_emission},
                           {gpu::SPEC_NORMAL_MAPS, f.normal_maps},
                           {gpu::SPEC_ALPHA, f.alpha},
                           {gpu::SPEC_SINGLE_SIDED, f.single_sided},
                           {gpu::SPEC_TRANSMISSION, f.transmission},
                           {gpu::SPEC_ABSORPTION, f.absorption},
                           {gpu::SPEC_NEE, settings.nee && f.nee_lights()},
                           {gpu::SPEC_PUNCTUAL, f.punctual},
                           {gpu::SPEC_SKY_LIGHT, f.sky_light},
                           {gpu::SPEC_TRIANGLE_LIGHTS, f.triangle_lights},
                           {gpu::SPEC_PART_LOG2, g.part_log2},
                           {gpu::SPEC_STAGE, stage},
                           {gpu::SPEC_TAIL_SUBGROUP, s.tail_subgroup()},
                           {gpu::SPEC_CAMERA_TILES, s.camera_tiles()},
                           {gpu::SPEC_TAIL_FETCH, s.tail_fetch()},
                           {gpu::SPEC_LOOP_LIMIT_CHECK, s.ctx.info.software}},
                          // Brute force reaches llvmpipe's loop limit first; the
                          // optimizer would change where it cuts (vk/specialize.h).
                          settings.accel != Accel::Brute);
  bind_buffers(p, {{gpu::BINDING_SCENE, &g.params},
                   {gpu::BINDING_SPHERES, &g.spheres},
                   {gpu::BINDING_TRIANGLES, &g.triangles},
                   {gpu::BINDING_TRIANGLE_NORMALS, &g.triangle_normals},
                   {gpu::BINDING_INSTANCES, &g.instances},
                   {gpu::BINDING_MESHES, &g.meshes},
                   {gpu::BINDING_SPHERE_MATERIALS, &g.sphere_materials},
                   {gpu::BINDING_MATERIALS, half ? &g.materials_half : &g.materials},
                   {gpu::BINDING_OCTREE_NODES, &g.nodes},
                   {gpu::BINDING_OCTREE_REFS, &g.refs},
                   {gpu::BINDING_TEXTURES, &g.textures},
                   {gpu::BINDING_TEXELS, &g.texels},
                   {gpu::BINDING_TRIANGLE_UVS, &g.triangle_uvs},
                   {gpu::BINDING_TEXTURE_TRANSFORMS, &g.texture_transforms},
                   {gpu::BINDING_TRANSMISSION, &g.transmission},
                   {gpu::BINDING_LIGHTS, &g.lights},
                   {gpu::BINDING_SPHERE_LIGHTS, &g.sphere_lights},
                   {gpu::BINDING_TRIANGLE_LIGHTS, &g.triangle_lights},
                   {gpu::BINDING_ENVMAP_TEXELS, &g.envmap_texels},
                   {gpu::BINDING_ENVMAP_MARGINAL, &g.envmap_marginal},
                   {gpu::BINDING_ENVMAP_CONDITIONAL, &g.envmap_conditional},
                   {gpu::BINDING_BUFFER_PARTS, &g.part_table}});
}

PathTracer::PathTracer(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings)
    : state_(std::make_unique<State>(ctx)) {
  validate_settings(settings);
  State& s = *state_;
  s.settings = settings;
  s.scene_features = scene_features(scene);
  s.sphere_count = scene.spheres.size();
  if (s.settings.octree.leaf_size == 0)
    s.settings.octree.leaf_size = default_octree_leaf(ctx.info, s.scene_features.triangles);
  if (s.settings.octree.max_refs == 0) {
    // The budget's auto brings its copy leaves (and the bound they keep).
    s.settings.octree.max_refs = default_octree_refs(ctx.info, s.scene_features.triangles);
    s.settings.octree.copy_leaf = default_copy_leaf(ctx.info, s.scene_features.triangles);
  }
  if (s.settings.octree.surface_cells == SurfaceCells::Auto)
    s.settings.octree.surface_cells =
        default_surface_cells(ctx.info, uint64_t(settings.spp) * s.pixels()) ? SurfaceCells::On : SurfaceCells::Off;
  s.every_feature = all_features(scene);
  check_precision(scene, settings.precision);
  s.create_accumulation();
  create_buffer(s.stats, ctx, sizeof(gpu::RenderStats), false, "statistics buffer");
  upload_scene(s.scene, ctx, scene, settings.accel, s.settings.octree,
               3 * s.pixels() * sizeof(glm::vec4) + sizeof(gpu::RenderStats) + s.tail_values.size +
                   s.tail_queue.size,
               settings.precision);
  s.timings.accel_build_ms = s.scene.accel_build_ms;
  s.timings.upload_ms = s.scene.upload_ms;
  s.note_culling(scene);
  s.create_pipeline();
  create_timer(s.timer, ctx);
  reset();
}

PathTracer::~PathTracer() = default;

const RenderTimings& PathTracer::setup_timings() const { return state_->timings; }
const OctreeStats& PathTracer::octree_stats() const { return state_->scene.octree; }
uint32_t PathTracer::buffer_parts() const { return uint32_t(state_->scene.parts.size()); }
uint64_t PathTracer::buffer_part_bytes() const {
  return state_->scene.part_log2 ? uint64_t(1) << state_->scene.part_log2 : 0;
}
const SceneFeatures& PathTracer::features() const { return state_->features; }
bool PathTracer::octant_culling() const { return state_->octant_culling(); }
uint32_t PathTracer::tail_depth() const { return state_->tail_depth(); }
uint32_t PathTracer::tail_step() const { return state_->tail_step(); }
uint32_t PathTracer::tail_fill() const { return state_->tail_fill(); }
uint32_t PathTracer::tail_subgroup() const { return state_->tail_subgroup(); }
bool PathTracer::camera_tiles() const { return state_->camera_tiles(); }
const Buffer& PathTracer::accum_sum() const { return state_->accum_sum; }
const Buffer& PathTracer::accum_comp() const { return state_->accum_comp; }
const RenderSettings& PathTracer::settings() const { return state_->settings; }

void PathTracer::reset() {
  State& s = *state_;
  s.dispatch_sums.clear();
  s.camera_tiles_for.reset();
  submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
    for (Buffer* b : {&s.accum_sum, &s.accum_comp, &s.accum_sq})
      vkCmdFillBuffer(cmd, b->buffer, 0, VK_WHOLE_SIZE, 0);
    // The stats zero but for loop_bound, 2 (path_trace.comp
    // check_loop_limit), in ranges that do not overlap.
    const VkDeviceSize bound = offsetof(gpu::RenderStats, loop_bound);
    vkCmdFillBuffer(cmd, s.stats.buffer, 0, bound, 0);
    vkCmdFillBuffer(cmd, s.stats.buffer, bound, sizeof(uint32_t), 2);
    vkCmdFillBuffer(cmd, s.stats.buffer, bound + sizeof(uint32_t), VK_WHOLE_SIZE, 0);
  });
}

void PathTracer::resize(int width, int height) {
  State& s = *state_;
  VK_CHECK(vkDeviceWaitIdle(s.ctx.device));  // the accumulation and its bindings are replaced
  RenderSettings next = s.settings;
  next.width = width;
  next.height = height;
  validate_settings(next);
  const RenderSettings previous = s.settings;
  s.settings = next;
  try {
    s.create_accumulation();
    s.create_camera_tiles();
  } catch (...) {
    s.settings = previous;
    throw;
  }
  s.bind_accumulation();
  reset();
}

void PathTracer::reconfigure(const Scene& scene, Accel accel, Precision precision, bool all_effects) {
  State& s = *state_;
  VK_CHECK(vkDeviceWaitIdle(s.ctx.device));  // the pipeline is replaced
  const RenderSettings previous = s.settings;
  try {
    check_precision(scene, precision);
    s.settings.accel = accel;
    s.settings.precision = precision;
    s.settings.all_effects = all_effects;
    if (accel != Accel::Brute && s.scene.tree != accel) {
      upload_octree(s.scene, s.ctx, scene, accel, s.settings.octree);
      s.timings.accel_build_ms = s.scene.accel_build_ms;
    }
    upload_materials(s.scene, s.ctx, scene, precision);  // the scene went up with the first precision's only
    s.note_culling(scene);  // brute force walks no tree: any camera
    s.create_pipeline();
  } catch (const InputError&) {
    s.settings = previous;
    s.note_culling(scene);
    s.create_pipeline();
    throw;
  }
  reset();
}

// The measurements behind sample_lanes' auto (path_tracer.h): on the H100
// (docs/performance.md, optimisation log), in whole paths, lanes cut the
// balloon from 31 ms to 11 ms (8) and 14 ms (4), because light trapped in a
// closed mesh makes a few pixels' paths run to the bounce limit; on the
// sphere fields 4 lanes cost nothing and 8 cost 6-14% (a barrier per round
// for paths of even length). With the tail queue the long paths finish in
// the tail, and on the H200 4 lanes were 1.8-5.2% faster than 8 on both
// meshes with both structures (optimisation log 71). A staged head
// dispatch runs its samples in rounds of lanes, and a last round its samples
// do not fill leaves lanes idle: 10 samples in 4 lanes take 12 invocations a
// pixel. Auto takes fewer lanes where they leave fewer idle (10 samples in 2
// lanes): on the H100 -8% at 488 spheres, -6% at 1M, -4% at 8,000 (log 116).
uint32_t sample_lanes(uint32_t setting, bool triangles, bool staged, uint32_t count, uint32_t height) {
  uint32_t lanes = setting ? setting : triangles && !staged ? 8u : 4u;
  if (!setting && staged)
    for (uint32_t fewer = lanes / 2; fewer >= 1; fewer /= 2)
      if ((count + fewer - 1) / fewer * fewer < (count + lanes - 1) / lanes * lanes) lanes = fewer;
  while (lanes > 1 && (lanes > count || (height + gpu::WORKGROUP_SIZE / lanes - 1) / (gpu::WORKGROUP_SIZE / lanes) > 65535))
    lanes /= 2;
  return lanes;
}

// The staged passes (path_trace.comp, accumulate.comp): per dispatch of
// samples the head (one invocation per sample, in rounds of lanes along z),
// with a queue the tail over the paths it queued (an indirect dispatch the
// head sized; with RenderSettings::tail_step one per tail level, each sized
// by the level before), and the sum of the values in sample order.
void PathTracer::State::record_staged_passes(VkCommandBuffer cmd, gpu::PassParams pc, uint32_t first_sample,
                                             uint32_t count, uint32_t per_dispatch) const {
  const State& s = *this;
  const uint32_t width = uint32_t(s.settings.width), height = uint32_t(s.settings.height);
  const uint32_t groups_x = (width + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE;
  // Without a queue the head traces every path to its end.
  const bool queue = s.tail_depth() > 0;
  pc.tail_depth = queue ? s.tail_depth() : UINT32_MAX;
  pc.tail_capacity = s.tail_capacity;
  pc.tail_fill = s.tail_fill();
  const auto bind = [&](const ComputePipeline& p) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  };
  // Tail levels: the first takes the head's queue; with a step, level l
  // traces step * 2^l bounces on (fewer paths live on, for longer) and
  // queues the rest for the next; the last (at most MAX_TAIL_LEVELS)
  // finishes them. A step of 1 from bounce 2 to a limit of 50: levels to
  // bounces 3, 5, 9, 17, 33 and the rest.
  const uint32_t step = s.tail_step();
  const uint64_t after_head = pc.bounce_limit > pc.tail_depth ? pc.bounce_limit - pc.tail_depth : 0u;
  uint32_t levels = 1;
  for (uint64_t span = step; queue && step > 0 && levels < gpu::MAX_TAIL_LEVELS && span < after_head; ++levels)
    span += uint64_t(step) << levels;
  std::array<gpu::TailControl, gpu::MAX_TAIL_LEVELS> empty;
  empty.fill(gpu::TailControl{0u, 0u, 1u, 1u, 0u, 1u, 1u, 0u});
  for (uint32_t done = 0; done < count; done += pc.sample_count) {
    pc.sample_index = first_sample + done;
    pc.sample_count = std::min(per_dispatch, count - done);
    pc.sample_lanes = s.sample_lanes_enabled()
                          ? sample_lanes(s.settings.sample_lanes, s.scene_features.triangles, true, pc.sample_count, height)
                          : 1u;
    const uint32_t tile_height = gpu::WORKGROUP_SIZE / pc.sample_lanes;
    // The previous dispatch's tail and sum read the queue and the values.
    compute_barrier(cmd);
    if (queue) {
      vkCmdUpdateBuffer(cmd, s.tail_control.buffer, 0, levels * sizeof(gpu::TailControl), empty.data());
      compute_barrier(cmd);
    }
    bind(s.pipeline);
    vkCmdDispatch(cmd, groups_x, (height + tile_height - 1) / tile_height,
                  (pc.sample_count + pc.sample_lanes - 1) / pc.sample_lanes);
    s.mark_dispatch(cmd, "head");
    for (uint32_t level = 0; queue && level < levels; ++level) {
      compute_barrier(cmd);
      pc.tail_level = level;
      const uint64_t end = pc.tail_depth + ((2ull << level) - 1) * step;  // after 2^(l+1) - 1 steps
      pc.tail_end = level + 1 < levels ? uint32_t(std::min<uint64_t>(end, UINT32_MAX)) : UINT32_MAX;
      bind(s.tail_pipeline);
      // A level's TailControl: groups_x, groups_y, groups_z (after its
      // count) are the VkDispatchIndirectCommand.
      vkCmdDispatchIndirect(cmd, s.tail_control.buffer,
                            level * sizeof(gpu::TailControl) + offsetof(gpu::TailControl, groups_x));
      s.mark_dispatch(cmd, "tail", level);
      // A level of fewer paths than tail_subgroup: the subgroup stage (the
      // tail stage's invocations left them alone). The two write other
      // parts of the same buffers, which a barrier orders all the same.
      if (s.tail_subgroup_pipeline.pipeline != VK_NULL_HANDLE) {
        compute_barrier(cmd);
        bind(s.tail_subgroup_pipeline);
        vkCmdDispatchIndirect(cmd, s.tail_control.buffer,
                              level * sizeof(gpu::TailControl) + offsetof(gpu::TailControl, subgroup_groups_x));
        s.mark_dispatch(cmd, "tail_subgroup", level);
      }
    }
    compute_barrier(cmd);
    if (s.dispatch_recording && queue) {
      // The paths each level took (dispatch_times), before the next
      // dispatch of samples clears them.
      const VkBufferCopy copy{0, s.dispatch_samples * gpu::MAX_TAIL_LEVELS * sizeof(gpu::TailControl),
                              levels * sizeof(gpu::TailControl)};
      vkCmdCopyBuffer(cmd, s.tail_control.buffer, s.dispatch_controls.buffer, 1, &copy);
    }
    if (s.dispatch_recording) ++s.dispatch_samples;
    bind(s.accumulate_pipeline);
    vkCmdDispatch(cmd, groups_x, (height + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE, 1);
    s.mark_dispatch(cmd, "sum");
  }
}

void PathTracer::record_passes(VkCommandBuffer cmd, const PassSettings& pass, uint32_t first_sample,
                               uint32_t count) const {
  const State& s = *state_;
  // Rays from elsewhere could start inside an opaque sphere and meet what
  // it hides, which the tree left out: a caller whose camera moves builds
  // with HiddenParts::Keep (the preview does).
  if (s.culled_for && (pass.camera.lookfrom != s.culled_for->lookfrom || pass.camera.aperture > s.culled_for->aperture))
    throw std::logic_error("a camera moved from where the tree left hidden sphere parts out (HiddenParts::Cull)");
  const uint32_t width = uint32_t(s.settings.width), height = uint32_t(s.settings.height);
  gpu::PassParams pc{};
  set_pass_camera(pc, pass.camera, s.settings.width, s.settings.height);
  pc.width = width;
  pc.height = height;
  pc.bounce_limit = pass.bounce_limit;
  pc.sample_seed = pass.sample_seed;
  pc.rr_depth = pass.rr_depth ? pass.rr_depth : UINT32_MAX;
  const uint32_t groups_x = (width + gpu::WORKGROUP_SIZE - 1) / gpu::WORKGROUP_SIZE;
  // The camera's tiles for this camera, a subgroup a tile, after the
  // passes before them (this batch's or the last) have read the last ones;
  // kept from the batch before where its camera and size were these.
  const State::CameraTilesFor tiles_for{pc.cam_origin, pc.pixel00, pc.pixel_du, pc.pixel_dv,
                                        pc.lens_radius, pc.width, pc.height};
  if (s.camera_tiles_pipeline.pipeline != VK_NULL_HANDLE && s.camera_tiles_for != tiles_for) {
    s.camera_tiles_for = tiles_for;
    compute_barrier(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.camera_tiles_pipeline.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.camera_tiles_pipeline.layout, 0, 1,
                            &s.camera_tiles_pipeline.set, 0, nullptr);
    vkCmdPushConstants(cmd, s.camera_tiles_pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
    // A subgroup a tile; past 65535 workgroups the stage's loop takes the rest.
    const uint64_t per_group = std::max<uint64_t>(kWorkgroupInvocations / std::max(s.ctx.info.subgroup_size, 1u), 1);
    vkCmdDispatch(cmd, uint32_t(std::min<uint64_t>((s.camera_tile_count() + per_group - 1) / per_group, 65535)), 1, 1);
    s.mark_dispatch(cmd, "camera_tiles");
    compute_barrier(cmd);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.layout, 0, 1, &s.pipeline.set, 0,
                          nullptr);
  const uint32_t per_dispatch = s.samples_per_dispatch() ? s.samples_per_dispatch() : count;
  if (s.staged()) {
    s.record_staged_passes(cmd, pc, first_sample, count, std::min(per_dispatch, s.tail_samples));
    return;
  }
  for (uint32_t done = 0; done < count; done += pc.sample_count) {
    if (done > 0) compute_barrier(cmd);
    pc.sample_index = first_sample + done;
    pc.sample_count = std::min(per_dispatch, count - done);
    pc.sample_lanes = s.sample_lanes_enabled()
                          ? sample_lanes(s.settings.sample_lanes, s.scene_features.triangles, false, pc.sample_count, height)
                          : 1u;
    // Spheres only: a dispatch whose samples do not fill its lanes' last
    // round takes the whole rounds, and the rest follows in a dispatch of
    // fewer lanes (on the H200 -7% and -9% at 8,000 and 488 spheres, 10 spp:
    // 8 samples in 4 lanes and 2 in 2 rather than a third round with two
    // lanes of four idle). With triangles the partial round stays: there
    // idle lanes cost less than more paths to a warp, whose time is its
    // longest path's, and light trapped in a closed mesh makes some paths
    // long (the balloon +9.5%; the engine -7%; optimisation log 42).
    if (!s.scene_features.triangles && pc.sample_count > pc.sample_lanes)
      pc.sample_count -= pc.sample_count % pc.sample_lanes;
    const uint32_t tile_height = gpu::WORKGROUP_SIZE / pc.sample_lanes;
    vkCmdPushConstants(cmd, s.pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
    vkCmdDispatch(cmd, groups_x, (height + tile_height - 1) / tile_height, 1);
    s.mark_dispatch(cmd, "whole");
  }
}

uint32_t PathTracer::first_batch() const {
  const State& s = *state_;
  const uint32_t lanes = batch_granule();
  if (!s.staged() || s.ctx.info.software) return lanes;
  return std::max(lanes, s.tail_samples);
}

uint32_t PathTracer::batch_granule() const { return state_->batch_granule(); }

uint32_t PathTracer::State::batch_granule() const {
  const State& s = *this;
  const uint32_t lanes = s.sample_lanes_enabled() ? sample_lanes(s.settings.sample_lanes, s.scene_features.triangles,
                                                                 s.staged(), gpu::MAX_SAMPLE_LANES,
                                                                 uint32_t(s.settings.height))
                                                  : 1u;
  if (!s.ctx.info.software || s.ctx.info.cpu_threads <= 1) return lanes;
  // Whole images per thread, and whole rounds of lanes (`--sample-lanes` on
  // a CPU device): their least common multiple, where that stays a batch of
  // at most 32 samples.
  const uint32_t both = std::lcm(lanes, s.ctx.info.cpu_threads);
  return both <= 32 ? both : lanes;
}

double PathTracer::run_passes(const PassSettings& pass, uint32_t first_sample, uint32_t count) {
  State& s = *state_;
  if (s.settings.dispatch_times) {
    // At most: the camera's tiles, and for each dispatch of samples (one
    // sample each at the least) the head and the sum, and each tail level
    // with its subgroup stage.
    // (mark_dispatch stops at the pool's end: past 2^20, 30,000 dispatches
    // of samples, which no batch reaches, the rest would go untimed.)
    const uint64_t most = std::min<uint64_t>(2 + uint64_t(count) * (2 + 2 * gpu::MAX_TAIL_LEVELS), 1u << 20);
    if (most > s.dispatch_timer.count) create_timer(s.dispatch_timer, s.ctx, uint32_t(most));
    const uint64_t controls = uint64_t(count) * gpu::MAX_TAIL_LEVELS * sizeof(gpu::TailControl);
    if (s.tail_depth() > 0 && controls > s.dispatch_controls.size)
      create_buffer(s.dispatch_controls, s.ctx, controls, false, "tail levels' path counts");
    s.dispatch_marks.clear();
    s.dispatch_samples = 0;
  }
  try {
    submit_and_wait(s.ctx, [&](VkCommandBuffer cmd) {
      // Earlier submissions (reset, previous batches) wrote the accumulation.
      compute_barrier(cmd);
      timer_begin(s.timer, cmd);
      if (s.settings.dispatch_times) timer_begin(s.dispatch_timer, cmd);
      s.dispatch_recording = s.settings.dispatch_times;
      record_passes(cmd, pass, first_sample, count);
      s.dispatch_recording = false;
      timer_end(s.timer, cmd);
    });
  } catch (...) {
    // A batch that did not run may have recorded the camera's tiles.
    s.dispatch_recording = false;
    s.camera_tiles_for.reset();
    throw;
  }
  if (s.settings.dispatch_times) {
    const std::vector<double> ms = timer_intervals_ms(s.dispatch_timer, uint32_t(s.dispatch_marks.size() + 1));
    std::vector<gpu::TailControl> controls;
    if (s.tail_depth() > 0) {
      controls.resize(size_t(s.dispatch_samples) * gpu::MAX_TAIL_LEVELS);
      download_buffer(s.ctx, s.dispatch_controls, controls.data(), controls.size() * sizeof(gpu::TailControl));
    }
    for (size_t i = 0; i < ms.size(); ++i) {
      const State::DispatchMark& m = s.dispatch_marks[i];
      DispatchTime d{m.stage, m.level, 1, ms[i], 0};
      // A level's paths run in the tail stage, or in the subgroup stage
      // where they are fewer than its threshold (path_trace.comp).
      if (d.tail()) {
        const uint64_t taken =
            std::min(controls.at(size_t(m.samples) * gpu::MAX_TAIL_LEVELS + m.level).count, s.tail_capacity);
        const bool in_subgroups = taken < s.tail_subgroup();
        d.paths = (d.stage == "tail_subgroup") == in_subgroups ? taken : 0;
      }
      add_dispatch_times(s.dispatch_sums, {d});
    }
  }
  return timer_ms(s.timer);
}

const std::vector<DispatchTime>& PathTracer::dispatch_times() const { return state_->dispatch_sums; }

void add_dispatch_times(std::vector<DispatchTime>& into, const std::vector<DispatchTime>& from) {
  for (const DispatchTime& d : from) {
    auto same = std::find_if(into.begin(), into.end(),
                             [&](const DispatchTime& e) { return e.stage == d.stage && e.level == d.level; });
    if (same == into.end()) {
      into.push_back(d);
    } else {
      same->runs += d.runs;
      same->ms += d.ms;
      same->paths += d.paths;
    }
  }
}

Accumulation PathTracer::read_accumulation() {
  State& s = *state_;
  const uint64_t pixels = s.pixels();
  Accumulation a{s.settings.width, s.settings.height, std::vector<glm::vec4>(pixels), std::vector<glm::vec4>(pixels),
                 std::vector<glm::vec4>(pixels)};
  const size_t bytes = pixels * sizeof(glm::vec4);
  download_buffers(s.ctx, {{&s.accum_sum, a.sum.data(), bytes},
                           {&s.accum_comp, a.comp.data(), bytes},
                           {&s.accum_sq, a.sq.data(), bytes}});
  return a;
}

void PathTracer::write_accumulation(const Accumulation& a) {
  State& s = *state_;
  const uint64_t pixels = s.pixels();
  if (a.width != s.settings.width || a.height != s.settings.height || a.sum.size() != pixels ||
      a.comp.size() != pixels || a.sq.size() != pixels)
    throw InputError("accumulation state of " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " for a render of " + std::to_string(s.settings.width) + "x" + std::to_string(s.settings.height));
  VK_CHECK(vkDeviceWaitIdle(s.ctx.device));
  upload_buffer(s.ctx, s.accum_sum, a.sum.data(), pixels * sizeof(glm::vec4));
  upload_buffer(s.ctx, s.accum_comp, a.comp.data(), pixels * sizeof(glm::vec4));
  upload_buffer(s.ctx, s.accum_sq, a.sq.data(), pixels * sizeof(glm::vec4));
}

uint64_t PathTracer::scene_hash() const { return state_->scene.content_hash; }

namespace {

// The variance of the mean (an image the size of r.mean), the smallest count
// and the rays of a result whose mean and counts are in place, from the
// accumulation's M2 buffer (`sq`: M2 per channel, the ray segments in .w).
// For both read-backs: resolve_accumulation and PathTracer::read_result.
void resolve_m2(const glm::vec4* sq, RenderResult& r) {
  const uint64_t pixels = r.count.size();
  r.variance_of_mean = Image{r.mean.width, r.mean.height, std::vector<float>(pixels * 3)};
  r.min_samples = pixels ? UINT32_MAX : 0;
  r.rays = 0;
  for (uint64_t i = 0; i < pixels; ++i) {
    const double n = r.count[i];
    r.min_samples = std::min(r.min_samples, uint32_t(n));
    r.rays += std::bit_cast<uint32_t>(sq[i].w);
    for (int c = 0; c < 3; ++c) r.variance_of_mean.rgb[3 * i + c] = pixel_variance_of_mean(sq[i][c], n);
  }
}

}  // namespace

void resolve_accumulation(const Accumulation& a, RenderResult& r) {
  // The mean and count as a checkpoint's state has them (render_state.h) ...
  RenderState state = state_of(a);
  r.mean = std::move(state.mean);
  r.count = std::move(state.count);
  // ... and the variance of the mean, the smallest count and the rays.
  resolve_m2(a.sq.data(), r);
}

RenderCounts PathTracer::counts() {
  State& s = *state_;
  gpu::RenderStats stats{};
  download_buffer(s.ctx, s.stats, &stats, sizeof(stats));
  RenderCounts c;
  c.nonfinite_samples = stats.nonfinite_samples;
  c.cut_paths = stats.cut_paths;
  if (!s.settings.walk_stats) return c;
  const auto count = [&](uint32_t k) { return uint64_t(stats.walk[2 * k]) | uint64_t(stats.walk[2 * k + 1]) << 32; };
  WalkStats& w = c.walk;
  w.counted = true;
  w.queries = count(gpu::WALK_QUERIES);
  w.nodes = count(gpu::WALK_NODES);
  w.leaves = count(gpu::WALK_LEAVES);
  w.boxes = count(gpu::WALK_BOXES);
  w.primitives = count(gpu::WALK_PRIMITIVES);
  w.instances = count(gpu::WALK_INSTANCES);
  w.query_slots = count(gpu::WALK_QUERY_SLOTS);
  w.node_slots = count(gpu::WALK_NODE_SLOTS);
  w.primitive_slots = count(gpu::WALK_PRIMITIVE_SLOTS);
  return c;
}

WalkStats& WalkStats::operator+=(const WalkStats& o) {
  counted = counted || o.counted;
  queries += o.queries;
  nodes += o.nodes;
  leaves += o.leaves;
  boxes += o.boxes;
  primitives += o.primitives;
  instances += o.instances;
  query_slots += o.query_slots;
  node_slots += o.node_slots;
  primitive_slots += o.primitive_slots;
  return *this;
}

RenderCounts& RenderCounts::operator+=(const RenderCounts& o) {
  nonfinite_samples += o.nonfinite_samples;
  cut_paths += o.cut_paths;
  walk += o.walk;
  return *this;
}

// resolve_accumulation's values, each buffer resolved as it arrives in the
// staging memory, in the same arithmetic: the sum's count and colour (kept
// in the mean until the compensation comes), the compensation's mean, then
// M2's variance and rays (resolve_m2, as resolve_accumulation). No copy of
// the three buffers on the host (optimisation log 97).
RenderResult PathTracer::read_result() {
  State& s = *state_;
  auto start = Clock::now();
  RenderResult r;
  const uint64_t pixels = s.pixels();
  const int w = s.settings.width, h = s.settings.height;
  r.mean = Image{w, h, std::vector<float>(pixels * 3)};
  r.count.resize(pixels);
  float* mean = r.mean.rgb.data();
  float* count = r.count.data();
  const auto pixels_of = [](const void* mapped) { return static_cast<const glm::vec4*>(mapped); };
  const size_t bytes = pixels * sizeof(glm::vec4);
  download_buffers(s.ctx, {{&s.accum_sum, nullptr, bytes,
                            [&](const void* mapped) {
                              const glm::vec4* sum = pixels_of(mapped);
                              for (uint64_t i = 0; i < pixels; ++i) {
                                count[i] = sum[i].w;
                                for (int c = 0; c < 3; ++c) mean[3 * i + c] = sum[i][c];
                              }
                            }},
                           {&s.accum_comp, nullptr, bytes,
                            [&](const void* mapped) {
                              const glm::vec4* comp = pixels_of(mapped);
                              for (uint64_t i = 0; i < pixels; ++i)
                                for (int c = 0; c < 3; ++c)
                                  mean[3 * i + c] = pixel_mean(mean[3 * i + c], comp[i][c], count[i]);
                            }},
                           {&s.accum_sq, nullptr, bytes,
                            [&](const void* mapped) { resolve_m2(pixels_of(mapped), r); }}});
  finish_result(r, start);
  return r;
}

RenderResult PathTracer::read_result(const Accumulation& acc) {
  auto start = Clock::now();
  RenderResult r;
  resolve_accumulation(acc, r);
  finish_result(r, start);
  return r;
}

// What a result has besides the images: the device's counters, the timings
// (the read-back's from `start`), the tree and the pipeline's choices.
void PathTracer::finish_result(RenderResult& r, Clock::time_point start) {
  State& s = *state_;
  const RenderCounts c = counts();
  r.nonfinite_samples = c.nonfinite_samples;
  r.cut_paths = c.cut_paths;
  r.walk = c.walk;
  r.dispatches = s.dispatch_sums;
  s.timings.readback_ms = ms_since(start);
  r.timings = s.timings;
  r.octree = s.scene.octree;
  r.buffer_parts = buffer_parts();
  r.buffer_part_bytes = buffer_part_bytes();
  r.features = s.features;
  r.octant_culling = s.octant_culling();
  r.camera_tiles = s.camera_tiles();
  r.bvh_top_while = s.bvh_top_while();
  r.tail_depth = s.tail_depth();
  r.tail_step = s.tail_step();
  r.tail_fill = s.tail_fill();
  r.tail_subgroup = s.tail_subgroup();
  r.tail_fetch = s.tail_fetch();
  // The path-tracing pipeline's (the whole paths, or the head), then the
  // tail stage's and the subgroup stage's where the render has them.
  r.pipeline_statistics = s.pipeline.statistics;
  for (const auto& [stage, p] : {std::pair<const char*, const ComputePipeline*>{"tail stage", &s.tail_pipeline},
                                 {"subgroup stage", &s.tail_subgroup_pipeline}})
    if (p->pipeline != VK_NULL_HANDLE)
      for (const auto& [name, value] : p->statistics) r.pipeline_statistics.emplace_back(std::string(stage) + ": " + name, value);
}

bool default_camera_tiles(const DeviceInfo& device, Accel accel, uint64_t spheres) {
  if (device.software) return spheres <= kCameraTileSpheresCpu;
  return spheres <= (accel == Accel::Bvh ? kCameraTileSpheresGpuBvh : kCameraTileSpheresGpuOctree);
}

bool default_octant_culling(const DeviceInfo& device, bool triangles) {
  return triangles || device.llvmpipe_release < 2500;
}

bool default_bvh_top_while(const DeviceInfo& device, double refs_per_leaf) {
  return !device.software && refs_per_leaf >= kBvhWhileRefsPerLeaf;
}

uint32_t default_octree_leaf(const DeviceInfo& device, bool triangles) {
  if (!default_octant_culling(device, triangles)) return kOctreeLeafUnculled;
  return device.software || triangles ? kOctreeLeaf : kOctreeLeafGpuSpheres;
}

uint32_t default_octree_refs(const DeviceInfo& device, bool triangles) {
  return !device.software && triangles ? kOctreeRefsGpuTriangles : kOctreeRefs;
}

uint32_t default_copy_leaf(const DeviceInfo& device, bool triangles) {
  return !device.software && triangles ? kCopyLeafGpuTriangles : 0;
}

bool default_surface_cells(const DeviceInfo& device, uint64_t samples) {
  return !device.software && samples >= kSurfaceCellsMinSamples;
}

uint32_t lane_sample_slots(const DeviceInfo& device) {
  return device.nvidia ? 2 * kWorkgroupInvocations : kWorkgroupInvocations;
}

uint32_t default_tail_subgroup(const DeviceInfo& device, bool triangles) {
  if (!triangles || !fits_tail_subgroup(device.subgroup_size)) return 0u;
  return uint32_t(std::min<uint64_t>(device.resident_threads / device.subgroup_size * kTailSubgroupPaths, UINT32_MAX));
}

std::string software_loop_limit_warning(const DeviceInfo& device, const Scene& scene, const RenderSettings& settings) {
  constexpr uint64_t kLoopLimit = 65535;
  if (!device.software || settings.accel != Accel::Brute) return {};
  // Brute force's query loops over the spheres, the instances and each
  // instance's triangles (accel/closest_hit.glsl); a bounce asks one, and
  // with next-event estimation a shadow ray's too.
  const uint64_t primitives = scene.spheres.size() + scene.instances.size() + instanced_triangle_count(scene);
  const bool shadow_rays = settings.nee && scene_features(scene).nee_lights();
  const uint64_t per_bounce = std::max<uint64_t>(primitives * (shadow_rays ? 2 : 1), 1);
  if (per_bounce * settings.bounce_limit <= kLoopLimit) return {};
  return device.name + " ends a shader loop after 65535 iterations per invocation: brute force over " +
         std::to_string(primitives) + " primitives" + (shadow_rays ? ", twice a bounce with a shadow ray," : "") +
         " can cut paths longer than " + std::to_string(kLoopLimit / per_bounce) +
         " bounces short (the image is wrong where it does; `render` and `bench` report how many they cut; the octree "
         "and the BVH test a few primitives a bounce)";
}

std::string cut_paths_note(uint64_t cut_paths) {
  return std::to_string(cut_paths) +
         " invocations of the CPU device's path tracer reached llvmpipe's limit of 65,535 loop iterations, which cut "
         "their paths short";
}

std::string punctual_without_nee_warning(const Scene& scene, const RenderSettings& settings) {
  if (settings.nee || !scene_features(scene).punctual) return {};
  return "next-event estimation is off: the scene's " + std::to_string(scene.lights.size()) +
         (scene.lights.size() == 1 ? " punctual light adds" : " punctual lights add") +
         " nothing (no ray can hit a point, spot or directional light)";
}

uint32_t next_batch(double per_pass_ms, uint32_t lanes, double target_ms) {
  const double per_pass = std::max(per_pass_ms, 1e-3);
  uint32_t batch = uint32_t(std::clamp(target_ms / per_pass, 1.0, 1024.0));
  lanes = std::max(lanes, 1u);
  if (batch >= lanes) return batch - batch % lanes;
  return per_pass * lanes <= 1000.0 ? lanes : batch;
}

RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const RenderControl& control) {
  PathTracer tracer(ctx, scene, settings);
  const PassSettings pass = pass_settings(scene, settings);
  uint32_t done = 0;
  if (control.resume) {
    if (control.check_resume) control.check_resume(tracer.scene_hash());
    tracer.write_accumulation(*control.resume);
    done = std::min(control.resume_samples, settings.spp);
  }
  double device_ms = 0;
  auto start = Clock::now(), last_checkpoint = start;
  bool interrupted = false;
  // Batches grow until one takes about a quarter second: few submissions for
  // fast passes, regular progress, a prompt stop and no driver watchdog for
  // slow ones. The first is one batch granule (a pixel's lanes, so that it
  // runs with all of them; a CPU device's threads, so that each takes whole
  // images); on a GPU as many as a dispatch of the staged head takes.
  const uint32_t lanes = tracer.batch_granule();
  uint32_t batch = tracer.first_batch();
  // Test hook: OCTRACE_TEST_DEVICE_LOST_AFTER=N fails the render as a lost
  // device would, after the first batch that reaches N samples and its
  // checkpoint (tests/app/interrupt_test). That batch checkpoints whether or
  // not the interval has passed: on a fast GPU the first N samples can take
  // less than any interval, and the test is of what a loss after a
  // checkpoint reports, not of the timer.
  const char* lose_env = std::getenv("OCTRACE_TEST_DEVICE_LOST_AFTER");
  const uint32_t lose_after = lose_env ? uint32_t(std::strtoul(lose_env, nullptr, 10)) : UINT32_MAX;
  while (done < settings.spp) {
    if (control.stop && control.stop->load()) {
      interrupted = true;
      break;
    }
    uint32_t n = std::min(batch, settings.spp - done);
    if (done < lose_after) n = std::min(n, lose_after - done);
    auto batch_start = Clock::now();
    device_ms += tracer.run_passes(pass, settings.first_sample + done, n);
    double batch_ms = ms_since(batch_start);
    done += n;
    if (control.progress) control.progress(done, settings.spp);
    double per_pass = batch_ms / n;
    batch = next_batch(per_pass, lanes);
    const bool lose_now = done == lose_after && done < settings.spp;
    if (control.checkpoint && done < settings.spp &&
        (lose_now || ms_since(last_checkpoint) >= 1000.0 * control.checkpoint_seconds)) {
      control.checkpoint(tracer.read_accumulation(), done, tracer.scene_hash());
      last_checkpoint = Clock::now();
    }
    if (lose_now) throw_vk_error(VK_ERROR_DEVICE_LOST, "vkQueueSubmit");
  }
  double wall_ms = ms_since(start);
  // Read back once: with checkpoints the final state and the result share
  // the buffers; without, they are resolved as they arrive.
  RenderResult r;
  if (control.checkpoint) {
    auto readback_start = Clock::now();
    const Accumulation acc = tracer.read_accumulation();
    const double download_ms = ms_since(readback_start);
    control.checkpoint(acc, done, tracer.scene_hash());  // the final state
    r = tracer.read_result(acc);
    r.timings.readback_ms += download_ms;
  } else {
    r = tracer.read_result();
  }
  r.timings.render_device_ms = device_ms;
  r.timings.render_wall_ms = wall_ms;
  r.samples = done;
  r.interrupted = interrupted;
  return r;
}

RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const ProgressFn& progress) {
  RenderControl control;
  control.progress = progress;
  return render(ctx, scene, settings, control);
}

}  // namespace octrace
