// A binned-SAH bounding volume hierarchy: the field's standard structure,
// beside the octree (`--accel bvh`) so that what the octree costs or saves
// can be measured. Boxes in, node arrays out, like accel/octree.h, and into
// the SAME arrays (GpuOctreeNode, refs): buffers, bindings, the two levels
// and the upload stay as they are, only the shader walk differs
// (shaders/accel/bvh_walk.glsl, in a binary and a four-wide form).
#pragma once

#include <cstdint>
#include <span>

#include "accel/aabb.h"
#include "accel/octree.h"

namespace octrace {

// ---------------------------------------------------------------------------
// Encoding (32 bytes per node, 4 bytes per reference; GpuOctreeNode)
//
//   lo, hi          the node's box: the union of its primitives' AABBs (so a
//                   child's box lies inside its parent's; siblings may overlap).
//   count_or_mask   internal node: OCTREE_INTERNAL | (2^n - 1) for its n
//                   children, 2 <= n <= kBvhWidth (as if an octree node had
//                   octants 0 .. n-1), leaf: the number of references (0
//                   only for the root of an empty tree, whose box is the
//                   point lo = hi = 0).
//   first           internal node: index of its first child; the others
//                   follow it (first + 1 .. first + n - 1). leaf: index of
//                   its first reference in refs.
//
//     nodes: ... [ node | first = c | INTERNAL|0xf ] ... [ c ][ c+1 ][ c+2 ][ c+3 ] ...
//
//   No big list (big_count = 0). Built over boxes alone (a top level), every
//   primitive is referenced exactly once, so a tree over n primitives has at
//   most 2n - 1 nodes; built with the primitives' shapes (a ClipFn: the
//   meshes' trees), spatial splits reference a triangle in every leaf that
//   holds a part of it, at most kBvhSpatialRefs references per triangle in
//   all. Nodes are in depth-first order below each group of siblings, which
//   keeps four siblings in two 64-byte lines.
//
// How it is built: a binary tree first (Wald 2007, "On fast construction of
// SAH-based bounding volume hierarchies", binned SAH): a node's primitive
// centroids are binned
// into kBvhBins equal bins along each axis of the centroids' box; for each of
// the kBvhBins - 1 planes between bins the surface area heuristic cost
//   C = node_cost + (A_left * N_left + A_right * N_right) / A
// (MacDonald and Booth 1990; A = half area of a box, a primitive test costs 1;
// node_cost: kBvhNodeCost or kBvhTopNodeCost below)
// is evaluated by a sweep over the bins, and the cheapest plane over the
// three axes wins (ties: lower axis, then lower plane). With the shapes
// (a ClipFn), where the best such split leaves its two sides overlapping by
// more than kBvhSpatialOverlap of the root's area, a spatial split is
// weighed too (Stich, Friedrich and Dietrich 2009, "Spatial splits in
// bounding volume hierarchies"): kBvhBins equal bins of the node's box per
// axis, a primitive counted where it enters and where it leaves and growing
// each bin it spans by its box clamped to the bin; the split made clips each
// triangle that straddles the plane to each side (accel/clip.h), and each
// part goes to its side with the box of that part. The cheaper of the two
// wins while the node's budget of added references lasts: the root's is
// (kBvhSpatialRefs - 1) n, and a split passes what it did not use on to its
// children in proportion to their references (optimisation log 75). The node is a leaf
// when it holds at most kBvhMinLeaf primitives, or when the cheapest split
// costs no less than testing all of them (C >= N) and N <= kBvhMaxLeaf. Where
// no plane separates the centroids (coincident centroids), the node splits
// at the median of the primitive ids instead. Depth is capped at
// kMaxBvhDepth (a deeper node becomes a leaf), which bounds the shader's
// stack. Then the binary tree is collapsed to kBvhWidth children per node
// (Wald, Benthin and Boulos 2008, "Getting rid of packets"; Dammertz et al.
// 2008, "Shallow bounding volume hierarchies"): an internal node's children
// start as its two, and the internal child of the largest box (ties: the
// one fewer binary levels below the node, then the first, so that equal
// boxes open evenly) is replaced by its own two children, in place, until there are
// kBvhWidth or all are leaves. Leaves and references are the binary tree's;
// a wide node's depth is at most its binary depth. A wide walk step tests a
// node's children together, so a ray takes about half the steps; which
// level is built how wide: default_bvh_widths below. The top levels'
// subtrees build on threads of their own (kBvhParallelDepth), each into
// arrays appended in the order one thread would have written them: the
// result depends only on the input.
// ---------------------------------------------------------------------------
inline constexpr uint32_t kBvhBins = 16;
inline constexpr uint32_t kBvhMinLeaf = 1;
inline constexpr uint32_t kBvhMaxLeaf = 8;
inline constexpr uint32_t kMaxBvhDepth = gpu::BVH_MAX_DEPTH;  // bounds the shader walk's stack
inline constexpr uint32_t kBvhWidth = gpu::BVH_WIDTH;          // children per internal node, at most
// The widths a scene's trees are built with by default (OctreeParams::
// bvh_width 0; render/gpu_scene.cpp applies them and sets the pipeline's
// SPEC_BVH_TOP_WIDE and SPEC_BVH_MESH_WIDE, which pick the binary or the
// four-wide form of accel/bvh_walk.glsl per level). On a GPU: the meshes' trees four-wide; the top level four-wide
// over instances only, binary where it holds spheres. On a CPU device
// (lavapipe): every tree binary. Why (optimisation log 54, against the
// binary trees): on the H200, four-wide, the engine (instances of meshes)
// rendered 8-9% faster and the balloon (one instance) 5%, the meshes' own
// trees giving about 5% of that; but the sparse sphere fields 1-6% slower
// (488 and 8000 spheres, the CUDA peer's scene: a ray finds its sphere
// within a few steps, and a wide node tests at once the boxes a binary
// walk would have culled), though the dense 1M field 11% faster; binary
// trees through the four-wide walk were 28% slower than through the binary
// walk. On llvmpipe the four-wide meshes were 28-31% slower (the engine,
// the balloon).
struct BvhWidths {
  uint32_t top, meshes;
};
inline constexpr BvhWidths default_bvh_widths(bool software, bool has_spheres) {
  return software ? BvhWidths{2, 2} : BvhWidths{has_spheres ? 2 : kBvhWidth, kBvhWidth};
}
// A binary node's visit (two box tests) in primitive tests, the SAH's
// node cost: 1 for triangles (the meshes' trees), 2 for the top level
// (spheres and instances), whose sphere test is the cheaper. Why (log 107,
// H100, the top level's cost alone varied): 2 took 2.0% off the peer's
// scene and 1.8% off 488 spheres, left 1M spheres as they were and cost
// 8,000 spheres 0.6%; 3 gained a little more on the sparse fields and cost
// 8,000 spheres 2.4%. Over triangles 2 cost the balloon 2.5% and the
// engine 0.3%. On llvmpipe every value from 0.5 to 2 was within the spreads.
inline constexpr double kBvhNodeCost = 1.0;
inline constexpr double kBvhTopNodeCost = 2.0;
// Spatial splits (with a ClipFn): looked for where the object split's
// children overlap by more than this fraction of the root's area (Stich et
// al. 2009's alpha), while the references stay within kBvhSpatialRefs per
// primitive.
inline constexpr double kBvhSpatialOverlap = 1e-5;
inline constexpr double kBvhSpatialRefs = 1.5;
static_assert(OctreeParams{}.bvh_spatial_refs == kBvhSpatialRefs);
// Nodes this shallow and this large build their two subtrees on two
// threads (up to 2^depth at once); the result is the same. The depth
// (default_bvh_parallel_depth): enough levels for one subtree per hardware
// thread, at least kBvhParallelDepth, since the subtrees finish unevenly.
// Deeper costs memory (each subtree's arrays are copied into its parent's
// at every level): on a 1M-triangle sheet (tools/make_grid_glb.py 708) the
// 2-core machine's peak was 373 MB on one thread, 480 MB at depth 2 and
// 580 MB at depth 4, each building in 0.70 s (1.07 s on one thread). On
// the 16-thread GPU machine (log 105) depth 4 built the engine in 0.47x
// and the sheet in 0.62x of depth 2's time, for 14% and 18% more peak
// memory; depths 5 and 6 gained no more, for 23% and more.
inline constexpr uint32_t kBvhParallelDepth = 2;
inline constexpr size_t kBvhParallelItems = 4096;
// The smallest depth whose 2^depth subtrees are at least `threads`, and at
// least kBvhParallelDepth.
inline constexpr uint32_t bvh_parallel_depth(uint32_t threads) {
  uint32_t depth = kBvhParallelDepth;
  while (depth < 31 && (uint32_t(1) << depth) < threads) ++depth;
  return depth;
}
// bvh_parallel_depth of this host's hardware threads.
uint32_t default_bvh_parallel_depth();

// Builds the BVH over `boxes` (finite; primitive i is boxes[i]). Returns the
// octree's struct: the same arrays, big_count = 0, and the same statistics
// (big_primitives 0; refs_per_primitive 1 without `clip`).
// `width`: children per internal node, at most (2: the binary tree itself;
// 2 <= width <= kBvhWidth; a scene's levels: default_bvh_widths).
// `clip` (octree.h ClipFn; may be empty): the primitives' shapes, which
// allow spatial splits, up to `spatial_refs` references per primitive in all
// (1: none; OctreeParams::bvh_spatial_refs).
// `node_cost`: the SAH's cost of a node's visit in primitive tests
// (kBvhNodeCost for triangles, kBvhTopNodeCost for the top level).
// `parallel_depth`: the levels whose nodes build their two subtrees on two
// threads (0: all on the calling thread); the tree is the same (bvh_test).
Octree build_bvh(std::span<const Aabb> boxes, uint32_t width = kBvhWidth, const ClipFn& clip = {},
                 double spatial_refs = kBvhSpatialRefs, double node_cost = kBvhNodeCost,
                 uint32_t parallel_depth = default_bvh_parallel_depth());

}  // namespace octrace
