// The octree: built on the CPU over primitive boxes, encoded as two flat
// arrays that are uploaded as they are (shaders/shared/shared.h GpuOctreeNode,
// a uint array of primitive ids). Boxes in, node arrays out: no Vulkan, no
// materials and no primitive kinds in here; a primitive is its box and its
// index in the span the build was given.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <span>

#include "accel/aabb.h"
#include "shared/shared.h"

namespace octrace {

// Defaults: tools/sweep_octree.sh found leaf sizes 1-16 within 4% of each
// other on spheres; on clipped triangle meshes 10 is as fast as 8 on the H100
// and keeps the octree under 48 bytes per triangle (docs/performance.md).
// Where a BVH over spheres alone has the device hold the spheres
// (OctreeParams::bvh_sphere_order, render/gpu_scene.cpp device_sphere_order):
// in the tree's reference order or the scene's; Auto, the tree's on a GPU and
// the scene's on a CPU device (optimisation log 61). The image is the same.
enum class SphereOrder { Auto, Tree, Scene };
// Which placements of a scene's meshes the device bakes into one
// world-space mesh (OctreeParams::instancing; render/gpu_scene.h
// device_meshes): Keep, those of meshes placed once (the others stay
// instanced: stored once, walked in object space); Bake, every one; Auto,
// every one where that at most doubles the triangles stored and adds at
// most kAutoBakeExtraTriangles, else Keep (optimisation log 68).
enum class Instancing { Auto, Keep, Bake };
// What the top level's boxes hold of a sphere that overlaps opaque ones
// (OctreeParams::hidden_parts): Cull, only the parts of its surface that no
// opaque sphere holds (accel/hidden_parts.h; the scene's camera must stay
// where it is: render/gpu_scene.cpp); Keep, the whole sphere. The image is
// the same but for a few values in millions in dense overlapping fields
// with glass, which cull changes (a ray that refracts into glass where it
// meets an opaque sphere starts 1e-5 inside the opaque one, by the
// origin's offset, and hits an inside no exact ray reaches; traced in
// optimisation log 125).
enum class HiddenParts { Cull, Keep };
// Whether the octree's top level follows the spheres' surfaces (accel/clip.h
// clip_sphere_surface) where HiddenParts::Cull shrank their boxes, which
// parts a dense field's top caps from its bottom ones (optimisation log
// 126): On, Off, or Auto: on for a GPU where the render is long enough for
// the faster passes to pay for the longer build, off for a CPU device, where
// the passes gained nothing at 1M and the build took twice as long
// (render/path_tracer.h default_surface_cells, log 127). The same image but
// where a ray starts inside an opaque sphere (log 125).
enum class SurfaceCells { Auto, On, Off };

// The leaf size of OctreeParams::leaf_size = 0 (auto) where the device's
// rule does not replace it (render/path_tracer.h default_octree_leaf).
inline constexpr uint32_t kOctreeLeaf = 10;
// The references per primitive of OctreeParams::max_refs = 0 (auto) where the
// device's rule does not replace it (render/path_tracer.h default_octree_refs).
inline constexpr uint32_t kOctreeRefs = 8;
// Issue 11's bound on an octree over meshes, in bytes a primitive (nodes and
// references): what a scene's tree with copy leaves is held to
// (OctreeParams::copy_leaf).
inline constexpr double kOctreeBytesBound = 48.0;
// OctreeParams::copy_leaf: the share of a node's extent along an axis that a
// reference must span to keep the node a leaf.
inline constexpr float kCopyLeafSpan = 0.75f;

struct OctreeParams {
  // A node with more references than this splits ... (0: auto, kOctreeLeaf
  // here; the tracer puts the device's rule in first)
  uint32_t leaf_size = 0;
  uint32_t max_depth = 16;  // ... while its tree depth (root = 0) is below this, 1..20
  // The BVH's (`--accel bvh`, accel/bvh.h) children per node, at most: 2 or
  // 4 for every tree of the scene, or 0 for the device's default
  // (render/gpu_scene.cpp bvh_widths). The image is the same either way.
  uint32_t bvh_width = 0;
  // The references per primitive, at most (1..kMaxOctreeRefs, or 0: auto,
  // kOctreeRefs here; the tracer puts the device's rule in first): along any
  // path from the root the product of the splits' duplication factors stays
  // within this (the split budget below). 8 kept the clipped meshes measured
  // under issue 11's 48 bytes per triangle; 16 took the engine's octree 13%
  // faster at 81 bytes (optimisation log 57), a trade left to the user
  // (`--octree-refs`); 12 with copy leaves of 20 keeps them under 48 and is
  // the GPU's auto for triangles (log 136).
  uint32_t max_refs = 0;
  // Copy leaves: a node of more than leaf_size and at most this many
  // references stays a leaf where one of its references spans more than
  // kCopyLeafSpan of the node's extent along an axis: splitting it would
  // copy that reference into most children (a long triangle among small
  // ones). Elsewhere the node splits as before. A scene's octree with copy
  // leaves (render/gpu_scene.cpp) of more than kOctreeBytesBound bytes a
  // primitive is built again with kOctreeRefs references and none, the
  // settings the bound was measured with. 0: none. Not a flag: the tracer's
  // auto for max_refs sets it (render/path_tracer.h default_copy_leaf).
  uint32_t copy_leaf = 0;
  // The order a BVH over spheres alone has the device hold the spheres in
  // (`--bvh-sphere-order`).
  SphereOrder bvh_sphere_order = SphereOrder::Auto;
  // The meshes' BVHs (`--accel bvh`): references per triangle, at most, that
  // spatial splits may make (`--bvh-spatial-refs`, 1..4; 1: none, the plain
  // binned SAH). accel/bvh.h kBvhSpatialRefs is the default.
  double bvh_spatial_refs = 1.5;
  // What the device stores of shared meshes (`--instancing`). Not a
  // property of the tree: it decides which triangles the trees are built
  // over, the same for every structure.
  Instancing instancing = Instancing::Auto;
  // What the top level's boxes hold of spheres inside opaque ones
  // (`--hidden-parts`). Not a property of the tree either: it decides the
  // boxes the tree is built over.
  HiddenParts hidden_parts = HiddenParts::Cull;
  // Whether the octree's top level follows the spheres' surfaces there
  // (`--octree-surfaces`; the tracer resolves Auto by device and samples).
  SurfaceCells surface_cells = SurfaceCells::Auto;
};

struct OctreeStats {
  double build_ms = 0;                // wall time of build_octree
  uint32_t nodes = 0;                 // nodes.size()
  uint32_t leaves = 0;                // nodes without OCTREE_INTERNAL (the root of an empty tree counts)
  uint32_t max_depth_reached = 0;     // depth of the deepest node, root = 0
  uint64_t refs = 0;                  // refs.size(): big primitives plus every leaf reference
  uint32_t big_primitives = 0;        // big_count
  double refs_per_primitive = 0;      // refs / primitive count (0 for an empty scene)
  double bytes_per_primitive = 0;     // bytes / primitive count (0 for an empty scene)
  uint64_t bytes = 0;                 // nodes * 32 + refs * 4: what the GPU holds for the octree
  uint32_t leaf_size = 0;             // the octree's OctreeParams::leaf_size as built (auto resolved); 0 for a BVH
  uint32_t max_refs = 0;              // the octree's OctreeParams::max_refs as built (auto resolved); 0 for a BVH
  uint32_t copy_leaf = 0;             // the octree's OctreeParams::copy_leaf as built; 0 for a BVH
  // A scene's octree with copy leaves built again within kOctreeBytesBound: the first
  // build's bytes a primitive (over kOctreeBytesBound); 0 where it was built
  // once. build_ms counts both builds.
  double first_bytes_per_primitive = 0;
  // A scene's BVH (render/gpu_scene.cpp): the most children a node of its
  // top level, and of its meshes' trees, may have (2 or 4); 0 otherwise.
  uint32_t bvh_top_width = 0, bvh_mesh_width = 0;
  // A BVH over spheres alone: whether the device holds the spheres in its
  // reference order (render/gpu_scene.cpp device_sphere_order).
  bool bvh_sphere_order = false;
  // A scene's tree (render/gpu_scene.cpp): the top level's leaves and
  // references (the meshes' trees come after them in the arrays).
  uint32_t top_leaves = 0;
  uint64_t top_refs = 0;
  // OctreeParams::hidden_parts = Cull (accel/hidden_parts.h): spheres whose
  // box shrank, spheres with nothing left, and the time it took (part of
  // build_ms).
  uint64_t spheres_clipped = 0, spheres_hidden = 0;
  double hidden_parts_ms = 0;
  // Whether the top level's octree followed the spheres' surfaces
  // (OctreeParams::surface_cells, resolved).
  bool surface_cells = false;
  // The top level's references per leaf (0 without a top level).
  double top_refs_per_leaf() const { return top_leaves ? double(top_refs) / top_leaves : 0.0; }
};

// ---------------------------------------------------------------------------
// Encoding (32 bytes per node, 4 bytes per reference)
//
//   GpuOctreeNode, std430, 32 bytes:
//   +------+------+------+-------+------+------+------+---------------+
//   | lo.x | lo.y | lo.z | first | hi.x | hi.y | hi.z | count_or_mask |
//   +------+------+------+-------+------+------+------+---------------+
//   0      4      8      12      16     20     24     28              32
//
//   lo, hi          the node's box: its cell clipped to the union of the AABBs
//                   of the primitives below it. Never outside the cell, so sibling
//                   boxes are disjoint (touching at most on the split planes).
//   count_or_mask   internal node: OCTREE_INTERNAL | child mask, bit k set when
//                   octant k has a child; octant k = (x >= mid.x)
//                   | (y >= mid.y) << 1 | (z >= mid.z) << 2.
//                   leaf: the number of references (< OCTREE_INTERNAL; 0 only
//                   for the root of a tree with no primitives in it, whose box
//                   is then the point lo = hi = 0).
//   first           internal node: index of its first child in `nodes`; the
//                   present children follow consecutively in octant order.
//                   leaf: index of its first reference in `refs`.
//
//   An internal node with children in octants 1, 4 and 6 (mask 0b01010010):
//
//     nodes: ... [ node  | first = c | INTERNAL|0x52 ] ... [ oct 1 ][ oct 4 ][ oct 6 ] ...
//                                 |                        ^ c      c + 1    c + 2
//                                 +------------------------+
//     child of octant k = first + popcount(mask & ((1 << k) - 1))
//
//   A leaf with 3 references:
//
//     nodes: ... [ leaf  | first = r | 3 ] ...
//     refs:  [ big 0 | .. | big B-1 | ... | s7 | s12 | s40 | ... ]
//                                         ^ r   (ascending primitive ids)
//
//   refs[0, big_count) are the "big" primitives, tested before traversal and not in
//   the tree; leaf ranges follow. A primitive is referenced by every leaf whose
//   cell its AABB overlaps, so no leaf has a capacity and the tree has no
//   primitive limit (the price is duplicated references, reported as
//   refs_per_primitive).
//
// Why this layout. Two 16-byte halves that each hold a vec3 and a uint match
// std430 with no padding, so one struct serves host and GLSL. The box is stored
// rather than derived from the parent's cell because a tight box culls empty
// space (a flat field of spheres fills a sliver of its cell) and because the
// traversal needs no stack of cells. An 8-bit mask plus one first-child index
// costs 4 bytes where 8 child indices would cost 32; empty octants cost nothing.
// Children in octant order make front-to-back order free: for a ray whose
// direction has sign bits s (bit a set when dir[a] < 0), visiting octants in the
// order k = 0..7 as k ^ s visits the near side of every split plane first
// (Revelles et al. 2000, "An efficient parametric algorithm for octree
// traversal"), because the siblings' boxes lie on their own side of the planes.
//
// How it is built. The root's cell is the AABB of the non-big primitives (from the
// scene, no constants). A node splits at the midpoint of its box into the
// octants its references' AABBs overlap: the low half [lo, mid] takes a primitive
// whose AABB has lo < mid, the high half [mid, hi] one whose AABB has hi >= mid
// (so every point of a primitive's AABB lies in a child that holds it). Splitting
// at the box rather than the cell midpoint skips the empty levels above a small
// cluster. An axis is split only if its box extent is at least half the largest
// one (a flat field of spheres is split like a quadtree; a zero extent never)
// and not every reference straddles its midpoint (that would only copy them);
// with `clip_straddled` (a ClipFn whose parts can be much smaller than the
// boxes: spheres' surfaces at the top level, optimisation log 126) a node
// whose split that rule narrowed is also planned with those axes split, and
// the plan of lower cost (below) is taken.
// A node splits while it holds more than leaf_size references and its depth is
// below max_depth (and, with copy_leaf, more than copy_leaf references or
// none that spans more than kCopyLeafSpan of the node's extent along an
// axis), and only if
//   - the split lowers the expected cost of a ray that meets the node:
//     sum over children of area_k * (count_k + 2) < area * count (surface area
//     heuristic, MacDonald and Booth 1990; 2 = a node visit in primitive tests).
//     This is what stops a split that makes no progress: when every child holds
//     all the references (coincident primitives) the children's areas add up to at
//     least the node's; and
//   - the references it creates stay within its budget: along any path from the
//     root the product of the splits' duplication factors (child references /
//     node references) is at most max_refs (8), so the references never exceed
//     max_refs per primitive, whatever the input (a hard bound, where the
//     heuristic is not).
// The top levels are split on the calling thread, the subtrees below them in
// parallel; the result depends only on the input.
//
// Big primitives. Sort by box size (the longest side), descending (ties by
// index). Primitive i of that order is big when its size exceeds half the
// largest extent of the AABB of all primitives after it in the order (one that
// would fill the whole tree of the rest, such as the rtiow ground sphere of
// radius 1000 next to a 22x22 field). The list stops at the first primitive
// that is not big, and at 16. With none after it, a primitive is big: a scene
// of one sphere is just that list.
// ---------------------------------------------------------------------------
struct Octree {
  std::vector<gpu::GpuOctreeNode> nodes;  // nodes[0] is the root, present even with no primitives
  std::vector<uint32_t> refs;             // refs[0, big_count): big primitives; then leaf ranges
  uint32_t big_count = 0;
  OctreeStats stats;
};

// Fills tree.stats' sizes from its arrays (nodes, refs, big primitives,
// bytes, and the per-primitive figures over `primitives`) and its build
// time: what every builder of these arrays (octree, BVH) reports.
void finish_tree_stats(Octree& tree, size_t primitives, double build_ms);

inline constexpr uint32_t kMaxBigPrimitives = 16;
inline constexpr uint32_t kMaxOctreeDepth = 20;  // 2^-20 of the root extent is near float resolution
inline constexpr uint32_t kMaxOctreeRefs = 64;   // OctreeParams::max_refs

// Optional knowledge of the primitives' shapes (split clipping): whether
// primitive `prim` reaches into `cell` (its closed box), and if so the box of
// the part inside, which may be larger than exact but must hold that part.
// Without it a primitive is its box: a long thin diagonal triangle is then
// referenced by every cell its box overlaps, most of which it only passes by.
// Called from several threads at once.
using ClipFn = std::function<bool(uint32_t prim, const Aabb& cell, Aabb& part)>;
// Optional with a ClipFn, for speed: primitive `prim`'s parts in the
// octants `candidates` (bit k: octant k) of `box` split at `mid`, all at
// once: parts[k] for each octant k it reaches, bit for bit what the ClipFn
// gives for that octant's cell (accel/clip.h clip_triangle_octants); returns
// the octants reached. Without it the build calls the ClipFn per octant; the
// tree is the same. Called from several threads at once.
using ClipOctantsFn =
    std::function<uint32_t(uint32_t prim, const Aabb& box, const glm::vec3& mid, uint32_t candidates, Aabb parts[8])>;

// Builds the octree over `boxes` (finite, non-empty; primitive i is boxes[i]).
// Uses the hardware threads; the result depends only on the input.
// Throws SettingError ("octree.max_depth", "octree.max_refs") for bad
// params (check_octree_params, which validate_settings calls too, so that
// a command refuses them before it makes a device); a leaf size of 0 builds
// with kOctreeLeaf, a max_refs of 0 with kOctreeRefs.
// `clip_straddled`: see "How it is built" (needs a ClipFn).
Octree build_octree(std::span<const Aabb> boxes, const OctreeParams& params, const ClipFn& clip = {},
                    const ClipOctantsFn& clip_octants = {}, bool clip_straddled = false);
void check_octree_params(const OctreeParams& params);

}  // namespace octrace
