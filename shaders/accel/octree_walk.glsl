// One octree walk, included once per level (no include guard): the includer
// defines OCTREE_WALK_NAME (the function's name), OCTREE_BVH_WIDE (which BVH
// walk, below), OCTREE_CHILD_PAIRS (a constant expression: whether the
// octree's node step tests its children two a trip; accel/octree_descend.glsl),
// OCTREE_LEAF(k) (how the
// reference in slot k of the refs array is tested; it may use the walk's
// parameters and its slab terms `sr`) and
// OCTREE_SLAB / OCTREE_SLAB_MAKE (the slab test's per-ray type and what
// makes it: accel/octree.glsl), and OCTREE_SPLIT (a constant expression:
// whether the subgroup's lanes, all walking this ray, split each leaf's
// references, lane l testing l, l + the subgroup's size, ..., and then agree
// on the nearest hit: accel/closest_hit.glsl agree_on_hit; and each node
// step's child box tests, a child a lane: accel/octree_descend.glsl), then undefines
// them. The walk is the same
// at both levels; only the leaf and the slab test's form differ.
// With ACCEL == ACCEL_BVH the arrays hold a BVH, which accel/bvh_walk.glsl
// walks, binary where the includer's OCTREE_BVH_WIDE (a constant
// expression) is false, four-wide where true (BVH_TOP_WIDE for the top
// level, BVH_MESH_WIDE for the meshes; renderer/accel/bvh.h says which and
// why).
// refs[big_first, big_end) are the primitives too large for the octree's
// cells (the tree's big list): with BIG_LEAF the walk tests them as its
// first leaf; without, its caller tests them before the walk
// (accel/closest_hit.glsl). A BVH has no big list (accel/bvh.h:
// big_count = 0), so its walk takes none.
void OCTREE_WALK_NAME(uint root_index, uint big_first, uint big_end, Ray ray, RayShear sh, uint from_prim,
                      bool into_from, InstanceRef ir, inout Hit hit) {
  if (ACCEL == ACCEL_BVH) {
    if (OCTREE_BVH_WIDE) {
#define BVH_WALK_WIDE 1
#include "accel/bvh_walk.glsl"
#undef BVH_WALK_WIDE
    } else {
#define BVH_WALK_WIDE 0
#include "accel/bvh_walk.glsl"
#undef BVH_WALK_WIDE
    }
    return;
  }
  // The leaf loops' first reference and stride (OCTREE_SPLIT). Split, every
  // lane makes the same trips, a lane past the leaf's end skipping the test
  // in its last, so that the lanes leave the loop together for
  // agree_on_hit's subgroup operations (structured control flow reconverges
  // at its merge on the drivers measured, lavapipe's and NVIDIA's; Vulkan
  // guarantees it only with maximal reconvergence; the split node step's
  // ballot after its lanes' own box tests relies on the same).
  const uint leaf_lane = OCTREE_SPLIT ? gl_SubgroupInvocationID : 0u;
  const uint leaf_lanes = OCTREE_SPLIT ? gl_SubgroupSize : 1u;
  OCTREE_SLAB sr = OCTREE_SLAB_MAKE(ray);
  vec3 inv_dir = sr.inv;
  uint sign_mask = (floatBitsToUint(ray.dir.x) >> 31) | ((floatBitsToUint(ray.dir.y) >> 31) << 1) |
                   ((floatBitsToUint(ray.dir.z) >> 31) << 2);
  // (node, bits of where the ray enters the node's box): one array of pairs,
  // so a push or pop is one 8-byte access to local memory, not two of 4
  // (optimisation log 40: 1-2% faster on the H200 than two arrays).
  uvec2 stack[STACK_SIZE];
  uint sp = 0;
  float t_entry;
  GpuOctreeNode root = node_at(root_index);
  if (WALK_STATS) ++walk_boxes;
  if (hit_box(root.lo, root.hi, sr, hit.t, t_entry)) {
    stack[0] = uvec2(root_index, floatBitsToUint(t_entry));
    sp = 1;
  }

  // While-while (Aila & Laine 2009, "Understanding the efficiency of ray
  // traversal on GPUs"): the inner loop (accel/octree_descend.glsl) walks
  // internal nodes until this invocation reaches a leaf (or its stack
  // empties), and the leaf is tested after it, so the invocations of a
  // subgroup test their leaves together instead of each step running the
  // leaf branch for some and the child loop for others. The same nodes in
  // the same order as one loop would visit. Kept for the octree walks only
  // (optimisation log 38): in the BVH walk, whose leaves hold one or two
  // primitives, it was slower on the sphere field and the engine.
  // Two forms of the outer loop (BIG_LEAF, accel/octree.glsl). With it, the
  // big list is the first leaf, so that the leaf's test (at the top level, a
  // mesh instance's whole walk) is compiled once per walk (log 39). Without
  // it, the caller has tested the big list in a loop of its own and the walk
  // ignores [big_first, big_end): the form before log 39, which the NVIDIA
  // compiler turns into fewer registers for the meshes (log 41).
  if (BIG_LEAF) {
    uint leaf_first = big_first, leaf_end = big_end;
    while (true) {
      if (WALK_STATS && leaf_end > leaf_first) ++walk_leaves;
      for (uint first = leaf_first; first < leaf_end; first += leaf_lanes)
        if (!OCTREE_SPLIT || first + leaf_lane < leaf_end) OCTREE_LEAF(first + leaf_lane);
      if (OCTREE_SPLIT && leaf_end > leaf_first) agree_on_hit(hit);
      if (sp == 0u) break;
      leaf_first = 0u;
      leaf_end = 0u;
#include "accel/octree_descend.glsl"
    }
  } else {
    while (sp > 0) {
      uint leaf_first = 0u, leaf_end = 0u;
#include "accel/octree_descend.glsl"
      if (WALK_STATS && leaf_end > leaf_first) ++walk_leaves;
      for (uint first = leaf_first; first < leaf_end; first += leaf_lanes)
        if (!OCTREE_SPLIT || first + leaf_lane < leaf_end) OCTREE_LEAF(first + leaf_lane);
      if (OCTREE_SPLIT && leaf_end > leaf_first) agree_on_hit(hit);
    }
  }
}
