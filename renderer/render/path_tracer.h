// Renders a Scene on a VulkanContext. The scene and its acceleration structure
// are uploaded once (render/gpu_scene.h); the camera, the bounce limit, the
// sampler's seed and the sample index are per pass (push constants); each pass
// adds one sample per pixel to fp32 accumulation buffers; the mean is read back.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>

#include "accel/octree.h"
#include "core/clock.h"
#include "io/image.h"
#include "render/render_state.h"
#include "render/settings.h"
#include "scene/features.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace octrace {

struct Buffer;

// What may change from one pass to the next without touching the scene on the
// device, its acceleration structure or the pipeline.
struct PassSettings {
  Camera camera;
  uint32_t bounce_limit = 50;
  uint32_t sample_seed = 1;
  uint32_t rr_depth = 0;  // Russian roulette from this bounce on (0: off)
};
// The scene's camera with the settings' bounce limit, seed and roulette.
PassSettings pass_settings(const Scene& scene, const RenderSettings& settings);

struct RenderTimings {
  double accel_build_ms = 0;   // octree or BVH build on the CPU (wall)
  double upload_ms = 0;        // buffer creation and scene upload (wall)
  double pipeline_ms = 0;      // compute pipeline creation (wall)
  double render_device_ms = 0; // path-tracing passes, timestamp queries (device)
  double render_wall_ms = 0;   // the same passes, wall clock incl. submission
  double readback_ms = 0;      // accumulation download and resolve (wall)
};

// The accumulation state: what a render *is*.
// What the walks did over a render's passes (RenderSettings::walk_stats;
// shaders/shared/shared.h WALK_*): all zeros when not counted. Every walk
// counts: camera rays, bounces, shadow rays, the meshes' own trees.
struct WalkStats {
  bool counted = false;
  uint64_t queries = 0;     // closest-hit and shadow-ray queries of the scene
  uint64_t nodes = 0;       // internal nodes expanded (their children's boxes tested)
  uint64_t leaves = 0;      // leaves (and big lists) whose primitives were tested
  uint64_t boxes = 0;       // ray/box tests
  uint64_t primitives = 0;  // ray/primitive tests (spheres and triangles)
  uint64_t instances = 0;   // mesh instances entered (their trees walked)
  // How full the subgroups were (shared.h WALK_*_SLOTS): the subgroup's size
  // summed over the steps where its lanes started a query, expanded a node,
  // tested a primitive. queries / query_slots is the share of lanes busy at
  // such a step, and so on.
  uint64_t query_slots = 0;
  uint64_t node_slots = 0;
  uint64_t primitive_slots = 0;
  WalkStats& operator+=(const WalkStats& o);
};

// What the passes counted in the stats buffer since the last reset
// (shared.h RenderStats), read back at once: RenderResult's fields of the
// same names.
struct RenderCounts {
  uint64_t nonfinite_samples = 0;
  uint64_t cut_paths = 0;
  WalkStats walk;  // zeros and counted = false without RenderSettings::walk_stats
  RenderCounts& operator+=(const RenderCounts& o);
};

// One kind of dispatch of the passes (RenderSettings::dispatch_times): its
// stage, its tail level, how often it ran, its device time in all, from
// the end of the dispatch before it, and the paths a tail level took.
struct DispatchTime {
  std::string stage;   // camera_tiles, whole, head, tail, tail_subgroup or sum
  uint32_t level = 0;  // the tail level (tail, tail_subgroup); 0 for the others
  uint64_t runs = 0;
  double ms = 0;
  uint64_t paths = 0;  // tail, tail_subgroup: the paths it traced (0 where the other stage took the level)
  bool tail() const { return stage == "tail" || stage == "tail_subgroup"; }
};
// Adds `from`'s runs and times to those of the same stage and level in
// `into`, in the order they first ran.
void add_dispatch_times(std::vector<DispatchTime>& into, const std::vector<DispatchTime>& from);

struct RenderResult {
  Image mean;              // linear mean radiance per pixel
  Image variance_of_mean;  // per pixel and channel: sample variance / count
  std::vector<float> count;  // per pixel: samples added (NaN/Inf ones are not)
  uint32_t min_samples = 0;       // smallest per-pixel sample count
  uint64_t nonfinite_samples = 0; // NaN/Inf samples rejected (0 for a clean render)
  // CPU devices: invocations whose loops llvmpipe's limit of 65,535
  // iterations ended early, so that their paths were cut short (0 for a
  // correct render; always 0 on a GPU; shaders/path_trace.comp
  // check_loop_limit).
  uint64_t cut_paths = 0;
  uint64_t rays = 0;              // ray segments traced (camera rays and bounces)
  WalkStats walk;                 // with RenderSettings::walk_stats
  std::vector<DispatchTime> dispatches;  // with RenderSettings::dispatch_times (summed over devices)
  RenderTimings timings;
  OctreeStats octree;             // of the octree or the BVH; zeros for Accel::Brute
  SceneFeatures features;         // what the pipeline was specialised to
  // The driver's statistics of the path-tracing pipeline (ComputePipeline::statistics),
  // then those of the tail stage's and the subgroup stage's, each name after "tail stage: "
  // and "subgroup stage: ".
  std::vector<std::pair<std::string, std::string>> pipeline_statistics;
  // Buffers the scene's big arrays were split into (0: one per array;
  // shaders/shared/scene_buffers.glsl) and the largest part's bytes.
  uint32_t buffer_parts = 0;
  uint64_t buffer_part_bytes = 0;
  bool octant_culling = true;  // RenderSettings::octant_culling in force
  bool camera_tiles = false;   // RenderSettings::camera_tiles in force
  bool bvh_top_while = false;  // RenderSettings::bvh_walk in force: while-while (a BVH's top level)
  uint32_t tail_depth = 0;   // the tail queue's bounce in force (RenderSettings::tail_depth; 0: off)
  uint32_t tail_step = 0;    // bounces per tail level in force (RenderSettings::tail_step; 0: one level)
  uint32_t tail_fill = 0;    // RenderSettings::tail_fill in force (0: every level queues its survivors)
  uint32_t tail_subgroup = 0;  // RenderSettings::tail_subgroup in force (0: no subgroup stage)
  bool tail_fetch = false;     // RenderSettings::tail_fetch in force (false without a tail stage)
  uint32_t samples = 0;      // samples per pixel the state holds (settings.spp unless interrupted)
  bool interrupted = false;  // render(): RenderControl::stop ended it early
};

// RenderSettings::octant_culling's auto: whether the octree walk culls
// children by octant on `device` for a scene with (`triangles`) or without
// meshes. Off for a scene without triangles on lavapipe from Mesa 25, whose
// llvmpipe no longer loops over a vector's lanes for each load (optimisation
// log 88), so the box tests the culling saves cost less than its own
// arithmetic: the default scene's passes 6-7% faster without it on Mesa
// 25.0.7, 8,000 spheres 6%; the meshes 0-5% slower, so on for them. On
// elsewhere: on Mesa 22.3.6 culling off is 44% slower, on the H100 1.5-8.6%
// (logs 29 and 106). Between 22.3 and 25.0 no release was measured.
bool default_octant_culling(const DeviceInfo& device, bool triangles);

// RenderSettings::bvh_walk's auto: whether the top level's binary BVH walk
// takes its while-while form on `device`, for a top level whose leaves hold
// `refs_per_leaf` references on average. On a GPU where that is at least
// kBvhWhileRefsPerLeaf: on the H200 the 1M-sphere field (r = 0.1, leaves of
// 6.7 spheres, 6.4 tested a leaf) 19.7% faster, the sparse fields of 1.8-3.1
// a leaf 1.3-4.0% slower (the peer's scene +4.0%, 488 spheres +3.5%, 8,000
// +1.3%; optimisation log 123). One loop on CPU devices: on lavapipe (Mesa
// 22.3.6) while-while took the 1M field 14.5% longer.
bool default_bvh_top_while(const DeviceInfo& device, double refs_per_leaf);
inline constexpr double kBvhWhileRefsPerLeaf = 4.0;

// RenderSettings::octree.leaf_size's auto (0): kOctreeLeaf (10), but 16 where
// default_octant_culling is off (scenes without triangles on lavapipe from
// Mesa 25): without the culling a leaf's sphere tests cost less against the
// node visits around them, and larger leaves took 4-5% off the default
// scene's and 8,000 spheres' passes on Mesa 25.0.7, 1M spheres within 0.1%;
// on Mesa 22.3.6, with the culling, 16 was 2.6% slower (optimisation log 110).
// And 24 for a scene without triangles on a GPU: on the H100 the peer's scene
// 6.0% faster than at 10, 8,000 spheres 5.0%, 488 1.1%, 1M within 0.7%; 32
// cost 488 spheres 17% (optimisation log 115). Scenes with triangles keep 10
// (the leaf measured on the meshes: logs 30 and 56; 20 cost a uniform
// 1M-triangle sheet 10% on the H100, log 132), but see default_copy_leaf.
uint32_t default_octree_leaf(const DeviceInfo& device, bool triangles);
inline constexpr uint32_t kOctreeLeafUnculled = 16;
inline constexpr uint32_t kOctreeLeafGpuSpheres = 24;

// RenderSettings::octree.max_refs's auto (0): kOctreeRefs (8), but 12 for a
// scene with triangles on a GPU, with default_copy_leaf's copy leaves: the
// budget lets the meshes whose budget binds split further, and the copy
// leaves keep their trees within issue 11's 48 bytes a triangle
// (optimisation log 136). Spheres are not clipped, and their trees do not
// spend the budget the way a mesh's do; on lavapipe the pair did not make the
// engine faster (+6%, inside the spread: log 136).
uint32_t default_octree_refs(const DeviceInfo& device, bool triangles);
inline constexpr uint32_t kOctreeRefsGpuTriangles = 12;

// OctreeParams::copy_leaf (and with it the bytes bound) where the tracer
// resolves max_refs as auto: 20 for a scene with triangles on a GPU, 0
// (none) elsewhere. On the H100 the engine's passes 4.7% faster than at 8
// references without them, at 45.7 bytes a triangle (68 at 12 references
// without them), its tree built in 15% less time; the balloon 3.9% faster,
// a uniform 1M-triangle sheet even, 400 instances of a 70k grid 1.7%
// faster (optimisation log 136).
uint32_t default_copy_leaf(const DeviceInfo& device, bool triangles);
inline constexpr uint32_t kCopyLeafGpuTriangles = 20;

// RenderSettings::octree.surface_cells's auto: whether the octree's top
// level follows the spheres' surfaces where the hidden parts were left out
// (optimisation log 126), for a render of `samples` samples (pixels x spp)
// on `device`. On a GPU from kSurfaceCellsMinSamples: on the H100 the cells
// took 1.62 ms off the 1M field's 10 spp at 1200x800 and 21.3 ms off 10M's,
// for a build 132 ms and 1.16 s longer on 16 cores, so the whole process
// gains from about 815 spp (1M) and 545 spp (10M) there; a shorter render
// loses (optimisation log 127). Off on CPU devices, where the passes gained
// nothing at 1M and the build took twice as long. A render shared by several
// devices (render/multi_device.h) counts its samples whole on each: each
// device's share is smaller, so the rule errs toward the cells there.
bool default_surface_cells(const DeviceInfo& device, uint64_t samples);
inline constexpr uint64_t kSurfaceCellsMinSamples = uint64_t(600) * 1200 * 800;

// The entries of path_trace.comp's workgroup array lane_sample (its
// SPEC_LANE_SAMPLE_SLOTS): one per invocation is all it uses, but twice that
// on NVIDIA's driver, whose compiler budgets the pipeline's registers by the
// workgroup memory it declares: below 96 entries (64 invocations) it gives
// 40 registers and adds 768 bytes of workgroup memory of its own, from 96 to
// 160 47 registers and none, and the walks are 3.5-4.8% faster on the H100
// (the peer's scene with either structure; 8,000 spheres 2%, the meshes
// within 1%); from 192 entries 57 registers and slower again (eight times
// the entries: 57-72% slower). 128 sits inside the plateau (optimisation
// log 114). The image is the same.
uint32_t lane_sample_slots(const DeviceInfo& device);

// RenderSettings::tail_subgroup's auto with the octree: kTailSubgroupPaths
// paths for each subgroup `device` holds resident at once, where its driver
// says how many threads that is (an H100: 4 x 270,336 / 32 = 33,792), for a
// scene with triangles; 0 (no subgroup stage) elsewhere, and where a
// subgroup has fewer than 8 lanes (one for each child of a node) or would
// not fit a workgroup of 64. On the H100 (fill and threshold
// 32,768) the engine's passes 0.948x, the balloon's 0.726x; spheres alone
// keep the tail of before, not measured to gain, the stage's barrier and
// dispatch a level costing 488 spheres 2% where it did not run
// (optimisation log 141).
uint32_t default_tail_subgroup(const DeviceInfo& device, bool triangles);

// RenderSettings::camera_tiles' auto for a scene of spheres alone with
// `accel`'s tree: whether its `spheres` are few enough on `device`. The
// lists cost each batch a test of every sphere for each tile of 64 pixels
// (a subgroup a tile), where a camera ray saves a walk; the more spheres,
// the more tiles overflow their lists and walk all the same. On lavapipe
// (Mesa 22.3.6, the octree, 400x225, 10 spp) the default scene's passes
// took 0.87x the time with them, 2,000 spheres 0.97x, 4,000 1.07x: at most
// kCameraTileSpheresCpu. On the H100 (1200x800, 10 spp, r = 0.1) with
// the BVH 2,000 spheres 0.93x, 8,000 1.009x, 16,000 1.10x: at most
// kCameraTileSpheresGpuBvh; with the octree 8,000 0.96x, 16,000 1.04x: at
// most kCameraTileSpheresGpuOctree; the peer's scene 0.83x (BVH) and 0.77x
// (octree), 488 spheres 0.94x and 0.86x (optimisation log 143).
bool default_camera_tiles(const DeviceInfo& device, Accel accel, uint64_t spheres);
inline constexpr uint64_t kCameraTileSpheresCpu = 1024;
inline constexpr uint64_t kCameraTileSpheresGpuBvh = 4096;
inline constexpr uint64_t kCameraTileSpheresGpuOctree = 8192;

// Whether subgroups of `subgroup_size` lanes can run the subgroup stage: at
// least a lane for each of an octree node's eight children (the split node
// step, accel/octree_descend.glsl), and within a workgroup of 64 (a path's
// lanes share it: path_trace.comp). Elsewhere its auto is 0 and a
// threshold set is refused (SettingError).
bool fits_tail_subgroup(uint32_t subgroup_size);

// Called after each batch of passes: passes done, total passes.
using ProgressFn = std::function<void(uint32_t done, uint32_t total)>;

// A scene uploaded to a device with its pipeline and an accumulation state,
// ready to run passes; reusable for several renders (benchmarks, the preview
// window, whose camera moves cost nothing but a restart of the accumulation).
class PathTracer {
 public:
  // Validates the settings, uploads the scene (and the octree for
  // Accel::Octree, the BVH for Accel::Bvh), creates the pipeline of settings.precision and
  // all_effects, and a cleared accumulation state of width x height.
  PathTracer(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings);
  ~PathTracer();
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // Clears the accumulation buffers and the statistics, and forgets the
  // camera's tiles' lists: the next batch runs as a fresh tracer's first,
  // list pass included (`bench` times each render so; log 148).
  void reset();
  // A new, cleared accumulation state of another size; the scene and the
  // pipeline stay. Waits for the device to be idle first.
  void resize(int width, int height);
  // Another acceleration structure, precision or effects over the same scene
  // on the device (`scene` is the one the tracer was made with: an octree
  // not built yet is built from it); the accumulation is cleared. Waits for
  // the device to be idle first. Throws InputError for what the scene or
  // device cannot do, and then keeps the configuration it had.
  void reconfigure(const Scene& scene, Accel accel, Precision precision, bool all_effects);
  // Adds passes [first_sample, first_sample + count) in one submission and
  // waits; returns their device time in milliseconds.
  double run_passes(const PassSettings& pass, uint32_t first_sample, uint32_t count);
  // The samples a batch holds a whole multiple of where it can. On a GPU how
  // many invocations share a pixel when a batch has enough samples for them
  // (1 where lanes are compiled out): the smallest batch that uses them. On
  // a CPU device its threads (DeviceInfo::cpu_threads): llvmpipe gives each
  // thread one contiguous block of a dispatch's workgroups, so that a
  // dispatch of one sample gave one thread the image's top half and the
  // other its bottom; with whole images each, both stay busy to the end (the
  // default scene's passes 6.7% faster on two; optimisation log 85).
  uint32_t batch_granule() const;
  // The samples of a render's first batch, before a batch's time is known:
  // batch_granule(), and on a GPU with the staged passes as many as one
  // dispatch of the head takes (its tail, the longest path's bounces one
  // after another, then comes once for them; optimisation log 50).
  uint32_t first_batch() const;
  // Records the same passes into `cmd` without submitting, for a caller that
  // adds its own work to the submission (the preview's resolve pass).
  void record_passes(VkCommandBuffer cmd, const PassSettings& pass, uint32_t first_sample, uint32_t count) const;
  // The accumulation buffers a resolve pass reads (layout in shared/shared.h):
  // Kahan sum with the sample count in .w, and the compensation terms.
  const Buffer& accum_sum() const;
  const Buffer& accum_comp() const;
  // The settings in force (width, height, accel, precision and effects follow
  // resize and reconfigure).
  const RenderSettings& settings() const;
  // The result of the samples added since the last reset: the buffers are
  // read back and resolved as they arrive, without a host copy of them.
  RenderResult read_result();
  // The same from an accumulation already read back (read_accumulation).
  RenderResult read_result(const Accumulation& acc);
  // The stats buffer's counts since the last reset, in one read.
  RenderCounts counts();
  // The dispatches' device times since the last reset (empty without
  // RenderSettings::dispatch_times).
  const std::vector<DispatchTime>& dispatch_times() const;
  // The raw accumulation buffers, and a state to continue from (a
  // checkpoint; InputError if its size is not the tracer's).
  Accumulation read_accumulation();
  void write_accumulation(const Accumulation& acc);
  // GpuScene::content_hash of the scene on the device.
  uint64_t scene_hash() const;
  const RenderTimings& setup_timings() const;
  const OctreeStats& octree_stats() const;
  // RenderResult::buffer_parts and buffer_part_bytes of the scene on the device.
  uint32_t buffer_parts() const;
  uint64_t buffer_part_bytes() const;
  const SceneFeatures& features() const;
  // RenderSettings::octant_culling resolved for the device and the scene.
  bool octant_culling() const;
  // The tail queue's bounce in force (RenderSettings::tail_depth resolved
  // for the device; 0: off).
  uint32_t tail_depth() const;
  // Bounces per tail level in force (RenderSettings::tail_step resolved; 0: one level).
  uint32_t tail_step() const;
  // RenderSettings::tail_fill resolved (0 without levels or without a fill).
  uint32_t tail_fill() const;
  // RenderSettings::tail_subgroup resolved (0: no subgroup stage).
  uint32_t tail_subgroup() const;
  // RenderSettings::camera_tiles resolved for the scene, device and size.
  bool camera_tiles() const;

 private:
  // What a result has besides the images (read_result).
  void finish_result(RenderResult& r, Clock::time_point start);
  struct State;
  std::unique_ptr<State> state_;
};

// llvmpipe (Mesa 22.3) ends a shader loop after 65535 iterations, counted
// over the whole invocation. Brute force runs its loop over every primitive
// (spheres, instances and their triangles) at every bounce, and again for
// the bounce's shadow ray where next-event estimation has a light to
// sample: with N primitives, paths longer than 65535 / N bounces (65535 /
// 2N with shadow rays) can be cut short, and the image is wrong where they
// are (the render counts them: RenderResult::cut_paths). Returns a one-line
// warning for such a render on a software device, or an empty string. It
// counts a whole path's bounces: the tail levels a CPU device takes above
// kCpuWholePathBounces trace fewer a dispatch, but their last level traces
// the rest of a path, and a path the tail queue has no room for finishes in
// the head.
std::string software_loop_limit_warning(const DeviceInfo& device, const Scene& scene, const RenderSettings& settings);

// RenderResult::cut_paths in words, for the warnings after a render that
// cut paths (`render`, `bench`): "N invocations of the CPU device's path
// tracer reached llvmpipe's limit of 65,535 loop iterations, which cut
// their paths short".
std::string cut_paths_note(uint64_t cut_paths);

// Punctual lights are reached by next-event estimation only: a one-line
// warning for a scene that has some when it is off, or an empty string.
std::string punctual_without_nee_warning(const Scene& scene, const RenderSettings& settings);

// The mean, variance of the mean, counts, smallest count and rays of an
// accumulation state, as PathTracer::read_result has them (the other fields
// of `r` are left as they are).
void resolve_accumulation(const Accumulation& acc, RenderResult& r);

// The next batch's samples, after one whose passes took `per_pass_ms` each:
// as many as take about `target_ms` (at least 1, at most 1024), in whole
// multiples of `lanes` (PathTracer::batch_granule: a pixel's lanes, so that
// no dispatch ends with lanes idle, optimisation log 42; a CPU device's
// threads, log 85); a batch too small for one
// round grows to one while that takes at most a second, so that a stop
// still waits no longer than that.
uint32_t next_batch(double per_pass_ms, uint32_t lanes, double target_ms = 250.0);

// The tail queue's entries (each of its `halves`, which share one buffer)
// for head dispatches of `paths` paths. On a GPU half the paths, the whole
// queue in an eighth of the device's memory `bytes`: a path that finds the
// queue full finishes in its head, and where more than the queue's share
// of paths outlive the head's bounces the heads run long (8,000 spheres at
// 16 samples a dispatch, 1200x800: 26% faster with the 4.19M entries an
// indirect dispatch covers than with the 2.8M of the values' 256 MiB
// budget; optimisation log 117). On a CPU device a quarter of the paths in
// `bytes` a half. At least one workgroup's, at most what an indirect
// dispatch of 65535 workgroups covers and a buffer of `limit` bytes holds.
uint32_t tail_queue_entries(uint64_t paths, bool gpu, uint64_t bytes, uint64_t limit, uint64_t halves);

// Invocations per pixel for a dispatch of `count` samples (PassParams) of an
// image `height` rows high: the setting (RenderSettings::sample_lanes), at
// most `count`, a power of two, and few enough that the workgroup count
// stays within the guaranteed 65535. Auto (0): 4, and 8 for scenes with
// triangles rendered in whole paths (no tail queue: `staged` false;
// optimisation logs 14, 31 and 71); with the tail queue 2 or 1 where 4
// would leave lanes of the last round idle (10 samples: 2; log 116). Lanes
// decide which invocation traces which sample, never the image.
uint32_t sample_lanes(uint32_t setting, bool triangles, bool staged, uint32_t count, uint32_t height);

// What a caller may do to a render while it runs.
struct RenderControl {
  ProgressFn progress;                      // after each batch of passes
  const std::atomic<bool>* stop = nullptr;  // set (a signal): stop after the batch in flight
  // Called after a batch when at least `checkpoint_seconds` have passed since
  // the last call (or the start), and once at the end (finished or stopped),
  // with the state, its samples per pixel and the scene's hash.
  double checkpoint_seconds = 0;
  std::function<void(const Accumulation&, uint32_t samples, uint64_t scene_hash)> checkpoint;
  // Continue from this state, which holds `resume_samples` samples per pixel
  // (indices first_sample .. + resume_samples - 1); the render adds the rest
  // up to settings.spp. `check_resume` is called with the scene's hash
  // before any pass, to refuse a state of another scene (by throwing).
  const Accumulation* resume = nullptr;
  uint32_t resume_samples = 0;
  std::function<void(uint64_t scene_hash)> check_resume;
};

// The whole render: set-up, settings.spp passes in batches sized to about a
// quarter second each (progress after each), read-back.
RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const RenderControl& control);
RenderResult render(const VulkanContext& ctx, const Scene& scene, const RenderSettings& settings,
                    const ProgressFn& progress = {});

}  // namespace octrace
