// What a render is asked to do besides the scene: the acceleration structure,
// the precision variant, the effects, the image and the sampling. Plain
// values; validate_settings checks them before anything is allocated.
#pragma once

#include <cstdint>
#include <string>

#include "accel/octree.h"
#include "core/errors.h"

namespace octrace {

enum class Accel { Brute, Octree, Bvh };
const char* accel_name(Accel a);
// "octree" | "bvh" | "brute"; throws SettingError("accel").
Accel parse_accel(const std::string& name);
// "auto" | "tree" | "scene" (OctreeParams::bvh_sphere_order); parse throws
// SettingError("octree.bvh_sphere_order").
const char* sphere_order_name(SphereOrder o);
SphereOrder parse_sphere_order(const std::string& name);
// "auto" | "keep" | "bake" (OctreeParams::instancing); parse throws
// SettingError("octree.instancing").
const char* instancing_name(Instancing i);
Instancing parse_instancing(const std::string& name);
// "cull" | "keep" (OctreeParams::hidden_parts; the command line parses
// its own auto | cull | keep: app/main.cpp RenderOptions::parsed).
const char* hidden_parts_name(HiddenParts h);
// "auto" | "on" | "off" (OctreeParams::surface_cells); parse throws
// SettingError("octree.surface_cells").
const char* surface_cells_name(SurfaceCells c);
SurfaceCells parse_surface_cells(const std::string& name);

// An auto | on | off setting's value as the enum E of its choices (E::Auto,
// E::On, E::Off); SettingError naming `setting` for anything else.
template <typename E>
E parse_auto_on_off(const std::string& value, const char* setting) {
  if (value == "auto") return E::Auto;
  if (value == "on") return E::On;
  if (value == "off") return E::Off;
  throw SettingError(setting, ": expected auto, on or off, got \"" + value + "\"");
}

// The extra triangles (placed - stored) up to which Instancing::Auto bakes
// every instance: at most some 180 MB more on the device (a triangle, its
// normals, its uvs and its share of the tree take about 170 bytes).
inline constexpr uint64_t kAutoBakeExtraTriangles = uint64_t(1) << 20;

// Whether `instancing` bakes every instance of a scene that stores `stored`
// triangles and places `placed` (instanced_triangle_count): Bake always,
// Keep never, Auto where the copies add at most the stored triangles again
// and at most kAutoBakeExtraTriangles. Why (optimisation log 68): on the
// H200 the engine's octree rendered 18% faster with every instance baked
// (its BVH 3.5% slower: an instance's tree in object space has the tighter
// boxes), on lavapipe the octree 7% and the BVH 30% faster; and issue 11's
// many instances of one mesh (400 of 70k triangles) stay instanced.
bool bakes_every_instance(Instancing instancing, uint64_t stored, uint64_t placed);

// Which quantities the shading code keeps in half (shaders/shading/precision.glsl).
enum class Precision { FP32, FP16, FP16All };
const char* precision_name(Precision p);
// "fp32" | "fp16" | "fp16-all"; throws SettingError("precision").
Precision parse_precision(const std::string& name);

// Where the octree walks test the big list (RenderSettings::big_list).
enum class BigList { Auto, FirstLeaf, OwnLoop };
// What the octree walk does with a node's nearest child
// (RenderSettings::nearest_child).
enum class NearestChild { Auto, Pushed, Held };
// Whether the octree walk culls children by octant (RenderSettings::octant_culling).
enum class OctantCulling { Auto, On, Off };
// The form of the top level's binary BVH walk (RenderSettings::bvh_walk).
enum class BvhWalk { Auto, OneLoop, WhileWhile };
// Whether camera rays take their hits from the camera's tiles (RenderSettings::camera_tiles).
enum class CameraTiles { Auto, On, Off };
// Whether the tail stage takes its level's paths from a counter (RenderSettings::tail_fetch).
enum class TailFetch { Auto, On, Off };

struct RenderSettings {
  Accel accel = Accel::Octree;
  Precision precision = Precision::FP32;
  // false: the pipeline is specialised to the scene's features (`auto`);
  // true: the general pipeline with every effect (`all`).
  bool all_effects = false;
  OctreeParams octree;
  int width = 1200;
  int height = 800;
  uint32_t spp = 10;
  // The first sample index of this render: runs with disjoint ranges of
  // sample indices (on other devices or machines) merge into one render.
  uint32_t first_sample = 0;
  // Per pass (PassSettings), given here for a whole render:
  uint32_t bounce_limit = 50;  // a path that reaches it contributes 0
  uint32_t sample_seed = 1;
  // Russian roulette from this bounce on (0: off): a path survives with
  // probability p = min(max throughput, 0.95) and carries 1/p more, so the
  // expectation is unchanged and the noise grows; paths end sooner.
  uint32_t rr_depth = 0;
  // Next-event estimation with MIS (shaders/shading/lights.glsl): at each
  // lambertian or pbr vertex a light of the scene is sampled. Off, the
  // integrator finds light only by hitting it (bit for bit the one before
  // light sampling), and punctual lights, which no ray can hit, add nothing.
  bool nee = true;
  // Samples one dispatch adds (each invocation loops over them for its
  // pixel); 0: every pass of a batch in one dispatch. The image is the same
  // whatever the value; only the time changes (docs/performance.md).
  uint32_t samples_per_dispatch = 0;
  // Invocations that share a pixel's samples in a dispatch: 1, 2, 4 or 8; 0:
  // auto (4; 8 with triangles in whole paths, without the tail queue;
  // render/path_tracer.cpp). The image is the
  // same whatever the value (shaders/path_trace.comp).
  uint32_t sample_lanes = 0;
  // Octant culling in the octree walk (shaders/accel/octree_walk.glsl): a
  // node's children in octants the ray cannot reach before its nearest hit
  // are skipped. The image is the same either way; only the time changes:
  // 1.5-8.6% faster on the H100 (optimisation log 29), 10-11% faster on
  // lavapipe on the 2-core machine of log 34 (3.5% slower on the one of 29),
  // 44% on Debian 12's lavapipe (Mesa 22.3.6); but 6-7% slower on scenes of
  // spheres with Mesa 25.0.7's lavapipe (log 106). Auto: off for a scene
  // without triangles on lavapipe from Mesa 25 (default_octant_culling), on
  // otherwise.
  OctantCulling octant_culling = OctantCulling::Auto;
  // The top level's binary BVH walk (`--accel bvh`; shaders/accel/bvh_walk.glsl):
  // one loop whose every step is a node or a leaf, or while-while (node
  // steps until the invocation holds a leaf, then the leaf, so that a
  // subgroup tests its leaves together). The image is the same either way.
  // Auto: while-while on a GPU where the top level's leaves hold at least
  // kBvhWhileRefsPerLeaf references on average (render/path_tracer.h
  // default_bvh_top_while), one loop otherwise.
  BvhWalk bvh_walk = BvhWalk::Auto;
  // Where the octree walks test a tree's big list (primitives too large for
  // its cells; shaders/accel/octree_walk.glsl): as the walk's first leaf, or
  // in a loop of the caller's. The image is the same either way. Auto: its
  // own loop on GPUs for pipelines with triangles (a scene with meshes, or
  // `--effects all`: the NVIDIA compiler gives them fewer registers, 6%
  // faster on the engine, optimisation log 41); the first leaf otherwise
  // (llvmpipe compiles the leaf's test, a mesh's whole walk, once instead
  // of twice: log 39).
  BigList big_list = BigList::Auto;
  // What the octree walk does with the nearest child the ray meets of a
  // node (shaders/accel/octree_descend.glsl): pushes it with the others and
  // pops it straight back, or holds it in registers and visits it next. The
  // image is the same either way. Auto: held on software devices (lavapipe
  // runs a loop until its last SIMD lane is done, and holding takes a trip
  // per node instead of one per push: the default scene 5-10% faster, the
  // engine and 8,000 spheres 12-13%), pushed on GPUs (held is 3-5% slower
  // on the H200; optimisation log 60).
  NearestChild nearest_child = NearestChild::Auto;
  // Count what the walks do (RenderResult::walk): queries, nodes expanded,
  // leaves, box and primitive tests, mesh instances entered. The image is the
  // same; the counting (atomics) costs time, so timings with it on are not
  // the renderer's. Off, it compiles out of the pipeline.
  bool walk_stats = false;
  // Time every dispatch of the passes on the device (RenderResult::
  // dispatches): a timestamp after each (the camera's tiles, the whole
  // paths or the head, each tail level and its subgroup stage, the sum),
  // so that each dispatch's time runs from the end of the one before. The
  // same image; the passes' own times stay those of the whole batch.
  bool dispatch_times = false;
  // The tail queue (shaders/path_trace.comp): a dispatch traces every path
  // up to this bounce, and the paths still going on there are finished in a
  // dispatch of their own, one per invocation, so that a few long paths do
  // not hold warps of short ones. The image is the same, bit for bit.
  // kTailAuto: kTailDepthDefault on GPUs, and on software devices above
  // kCpuWholePathBounces bounces; up to it the head and the sum without a
  // queue there (render/path_tracer.cpp); 0: off (the whole paths in one
  // pass).
  uint32_t tail_depth = kTailAuto;
  static constexpr uint32_t kTailAuto = UINT32_MAX;
  // Paths the tail queue holds per dispatch (0: auto, tail_queue_entries
  // in render/path_tracer.h: on a GPU up to half the dispatch's paths); a
  // path past it finishes in the head. The image is the same; tests use a
  // small one.
  uint32_t tail_queue_entries = 0;
  // Tail levels (shaders/path_trace.comp tail_pass): the first tail
  // dispatch traces its paths this many bounces on, each next one twice as
  // many as the one before, and each queues the paths still going for the
  // next (at most kMaxTailLevels levels; the last finishes them), so that a
  // warp of the tail holds its paths for a few bounces, not until the
  // longest ends. 0: one tail finishes them all. kTailAuto: kTailStepDefault
  // on software devices and for scenes of spheres alone, and with
  // triangles where a fill applies (tail_fill, below), else 0. The image
  // is the same, bit for bit.
  uint32_t tail_step = kTailAuto;
  // With tail levels: a level that takes fewer paths than this finishes
  // them instead of queuing its survivors for the next, because packed
  // into fewer warps than the GPU holds a few long paths run each bounce at
  // the pace of the slowest of 32 (optimisation log 64). 0: every level but
  // the last queues its survivors. kTailAuto: the subgroup stage's
  // threshold where there is one (tail_subgroup, below), so that levels go
  // on packing their paths until the stage can take them; else the
  // threads the device holds resident at once where its driver says
  // (DeviceInfo::resident_threads), else 0. The image is the same, bit for
  // bit.
  uint32_t tail_fill = kTailAuto;
  // With a tail queue: a tail level that takes fewer paths than this gives
  // each its own subgroup, whose lanes share the octree walks' leaf tests
  // and a node's child box tests (shaders/path_trace.comp
  // tail_subgroup_pass): a path's bounce then waits on one round of reads
  // a leaf, not one a reference, and one a node, not one a child. 0: off.
  // kTailAuto: with tail levels, the octree and triangles in the scene
  // (spheres alone keep the tail of before), kTailSubgroupPaths paths for
  // each subgroup the device holds resident at once, where its driver says
  // how many threads that is (on an H100 4 x 270,336 / 32 = 33,792) and
  // its subgroups have 8 to 64 lanes (fits_tail_subgroup), else 0.
  // Off with walk_stats, whose counts are of one walk a path. The image is
  // the same, bit for bit.
  uint32_t tail_subgroup = kTailAuto;
  // With a tail queue: the tail stage's invocations take their level's
  // paths from a counter, a bounce at a time, so that one whose path ended
  // (or reached the level's last bounce) takes the next at once instead of
  // idling until its warp's longest path is done (shaders/path_trace.comp
  // tail_fetch_paths; optimisation log 152). On: wherever there is a tail
  // stage, but not on a CPU device (SettingError: llvmpipe ends a loop
  // after 65,535 iterations counted over the whole invocation, and loses
  // the paths of one that takes many). Auto: on a GPU for scenes with
  // triangles, and for spheres alone from kTailFetchSpheresOctree spheres
  // with the octree, kTailFetchSpheresBvh with the BVH (on the H100 the
  // peer's scene and 488 spheres were 0.8-2.7% slower with it, larger
  // fields up to 6% faster, the BVH's from about 5,000). The image is the
  // same, bit for bit.
  TailFetch tail_fetch = TailFetch::Auto;
  // Camera rays tested against their 8x8-pixel tile's list of the spheres
  // they can meet, made on the device before a batch's passes where its
  // camera or size is not the last batch's (shaders/camera_tiles.comp),
  // instead of walking the tree; a tile
  // that more than 32 spheres reach walks. For scenes of spheres alone,
  // with the octree or the BVH. On: wherever that
  // holds (SettingError elsewhere). Auto: where it holds and the scene has
  // at most default_camera_tiles' spheres for the device (the lists cost
  // each batch a test of every sphere for each tile). The image is the
  // same, bit for bit.
  CameraTiles camera_tiles = CameraTiles::Auto;
};

// The bounce at which RenderSettings::tail_depth's auto queues paths on a
// GPU (optimisation log 49: of 2, 3 and 4 on the H200, 2 was the fastest on
// the sphere fields and the peer's scene, 3 and 4 on the engine).
constexpr uint32_t kTailDepthDefault = 2;
// RenderSettings::tail_depth's auto on a CPU device: whole paths (no
// queue) up to this bounce limit, the tail levels above it. llvmpipe ends
// every loop of an invocation after 65,535 iterations of all its loops
// together; render_test's light trap (20,000 spheres in a mirror sphere)
// cut paths short from about 200 bounces with whole paths, none at 150
// (optimisation log 157).
constexpr uint32_t kCpuWholePathBounces = 64;
// RenderSettings::tail_step's auto, and the most tail levels a dispatch
// runs (gpu::MAX_TAIL_LEVELS).
constexpr uint32_t kTailStepDefault = 1;
constexpr uint32_t kMaxTailLevels = 16;
// RenderSettings::tail_subgroup's auto: this many paths for each subgroup
// the device holds resident at once (optimisation log 141).
constexpr uint32_t kTailSubgroupPaths = 4;
// RenderSettings::tail_fetch's auto for scenes of spheres alone: on from
// this many spheres, with the BVH and otherwise (the octree; brute force,
// not measured) (optimisation logs
// 152 and 155: on the H100 the octree's passes 1.008x at 488 spheres,
// 0.992x at 1,000, 0.968x at 4,000; the BVH's 1.008x at 4,000, 0.988x at
// 6,000, 0.990x at 8,000, and a gain at 1M with both).
constexpr uint64_t kTailFetchSpheresOctree = 1000;
constexpr uint64_t kTailFetchSpheresBvh = 4096;

// Checks sizes and counts, and the octree's limits (check_octree_params);
// throws SettingError naming the setting ("size 0x10: width and height
// must be >= 1").
void validate_settings(const RenderSettings& settings);

}  // namespace octrace
