// A binned-SAH bounding volume hierarchy: the field's standard structure,
// beside the octree (`--accel bvh`) so that what the octree costs or saves
// can be measured. Boxes in, node arrays out, like accel/octree.h, and into
// the SAME arrays (GpuOctreeNode, refs): buffers, bindings, the two levels
// and the upload stay as they are, only the shader walk differs
// (shaders/accel/bvh_walk.glsl).
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
//   count_or_mask   internal node: OCTREE_INTERNAL | 0x3 (two children, as if
//                   an octree node had octants 0 and 1), leaf: the number of
//                   references (0 only for the root of an empty tree, whose
//                   box is the point lo = hi = 0).
//   first           internal node: index of its left child; the right child
//                   is first + 1. leaf: index of its first reference in refs.
//
//     nodes: ... [ node | first = c | INTERNAL|3 ] ... [ left ][ right ] ...
//                                                      ^ c     c + 1
//
//   Every primitive is referenced exactly once (no duplicates, no big list:
//   big_count = 0), so a tree over n primitives has at most 2n - 1 nodes.
//   Nodes are in depth-first order (left subtree before right) below the
//   pair of siblings, which keeps a pair in one 64-byte line.
//
// How it is built (Wald 2007, "On fast construction of SAH-based bounding
// volume hierarchies", binned SAH): a node's primitive centroids are binned
// into kBvhBins equal bins along each axis of the centroids' box; for each of
// the kBvhBins - 1 planes between bins the surface area heuristic cost
//   C = kBvhNodeCost + (A_left * N_left + A_right * N_right) / A
// (MacDonald and Booth 1990; A = half area of a box, a primitive test costs 1)
// is evaluated by a sweep over the bins, and the cheapest plane over the
// three axes wins (ties: lower axis, then lower plane). The node is a leaf
// when it holds at most kBvhMinLeaf primitives, or when the cheapest split
// costs no less than testing all of them (C >= N) and N <= kBvhMaxLeaf. Where
// no plane separates the centroids (coincident centroids), the node splits
// at the median of the primitive ids instead. Depth is capped at
// kMaxBvhDepth (a deeper node becomes a leaf), which bounds the shader's
// stack. Single-threaded and deterministic: the result depends only on the
// input.
// ---------------------------------------------------------------------------
inline constexpr uint32_t kBvhBins = 16;
inline constexpr uint32_t kBvhMinLeaf = 1;
inline constexpr uint32_t kBvhMaxLeaf = 8;
inline constexpr uint32_t kMaxBvhDepth = gpu::BVH_MAX_DEPTH;  // bounds the shader walk's stack
inline constexpr double kBvhNodeCost = 1.0;   // a node visit (two box tests) in primitive tests

// Builds the BVH over `boxes` (finite; primitive i is boxes[i]). Returns the
// octree's struct: the same arrays, big_count = 0, and the same statistics
// (big_primitives 0, refs_per_primitive 1).
Octree build_bvh(std::span<const Aabb> boxes);

}  // namespace octrace
