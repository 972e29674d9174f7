// One octree walk, included once per level (no include guard): the includer
// defines OCTREE_WALK_NAME (the function's name), OCTREE_LEAF(ref) (what a
// leaf's reference is tested with; it may use the walk's parameters) and
// OCTREE_SLAB / OCTREE_SLAB_MAKE (the slab test's per-ray type and what
// makes it: accel/octree.glsl), then undefines them. The walk is the same
// at both levels; only the leaf and the slab test's form differ.
// With ACCEL == ACCEL_BVH the arrays hold a BVH and accel/bvh_walk.glsl walks it.
// refs[big_first, big_end) are the primitives too large for the octree's
// cells (the tree's big list): the walk tests them as its first leaf. A BVH
// has no big list (accel/bvh.h: big_count = 0), so its walk takes none.
void OCTREE_WALK_NAME(uint root_index, uint big_first, uint big_end, Ray ray, RayShear sh, uint from_prim,
                      bool into_from, InstanceRef ir, inout Hit hit) {
  if (ACCEL == ACCEL_BVH) {
#include "accel/bvh_walk.glsl"
    return;
  }
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
  if (hit_box(root.lo, root.hi, sr, hit.t, t_entry)) {
    stack[0] = uvec2(root_index, floatBitsToUint(t_entry));
    sp = 1;
  }

  // While-while (Aila & Laine 2009, "Understanding the efficiency of ray
  // traversal on GPUs"): the inner loop walks internal nodes until this
  // invocation reaches a leaf (or its stack empties), and the leaf is tested
  // after it, so the invocations of a subgroup test their leaves together
  // instead of each step running the leaf branch for some and the child loop
  // for others. The same nodes in the same order as one loop would visit.
  // Kept for the octree walks only (optimisation log 38): in the BVH walk,
  // whose leaves hold one or two primitives, it was slower on the sphere
  // field and the engine. The big list is the first leaf, so that the leaf's
  // test (at the top level, a mesh instance's whole walk) is compiled once
  // per walk, not once more for a loop of its own (log 39).
  uint leaf_first = big_first, leaf_end = big_end;
  while (true) {
    for (uint k = leaf_first; k < leaf_end; ++k) OCTREE_LEAF(ref_at(k));
    if (sp == 0u) break;
    leaf_first = 0u;
    leaf_end = 0u;
    while (sp > 0) {
      --sp;
      // The node was pushed when its box was met before the nearest hit of that
      // moment; a nearer hit found since rules it out (the early exit).
      uvec2 top = stack[sp];
      float top_entry = uintBitsToFloat(top.y);
      if (top_entry > hit.t * WIDEN) continue;
      GpuOctreeNode node = node_at(top.x);
      if (node.count_or_mask < OCTREE_INTERNAL) {
        leaf_first = node.first;
        leaf_end = node.first + node.count_or_mask;
        break;
      }
      uint present = node.count_or_mask & 0xffu;  // children's octants; child index = rank in it
      uint mask = present;
      // Octant culling: the build split this node at the middle of its own box
      // (renderer/accel/octree.cpp, plan_split: lo + 0.5 (hi - lo), the same
      // float operations), and each child's box lies in its octant (a
      // primitive that reaches the plane goes to the upper side). Along the
      // ray, between where it enters the node and the nearest hit so far, it
      // is below the middle on axis a before (or after, going down) t_a, the
      // plane's crossing, and above it after (before). A child whose octant
      // takes a side the ray never reaches there cannot hold a nearer hit and
      // is not tested. Per axis, not per octant sequence: the set kept is a
      // superset of the octants pierced. An axis that was not split (the
      // build's middle is +inf there: every child is on the lower side) is
      // skipped: its children lie anywhere along it. t_a's sign is exact (a
      // rounded difference keeps its sign); its size and the entry are
      // widened as in hit_box. A ray in the plane (t_a = 0) keeps both sides.
      // On by default (OCTANT_CULLING; `--octant-culling off`: the same image).
      if (OCTANT_CULLING) {
        vec3 mid = node.lo + 0.5 * (node.hi - node.lo);
        vec3 t_mid = (mid - ray.origin) * inv_dir;
        float t_in = top_entry / WIDEN;
        float t_out = hit.t * WIDEN;
        for (uint a = 0u; a < 3u; ++a) {
          uint lower = a == 0u ? 0x55u : (a == 1u ? 0x33u : 0x0fu);  // octants below the middle on a
          if ((present & ~lower) == 0u) continue;                     // not split on a
          float ta = t_mid[a];
          bool down = ((sign_mask >> a) & 1u) != 0u;
          bool before = t_in <= ta * WIDEN || ta == 0.0;  // some of [t_in, t_out] is before t_a
          bool after = t_out >= ta / WIDEN || ta == 0.0;  // some of it is after t_a
          bool below = down ? after : before;
          bool above = down ? before : after;
          mask &= (below ? lower : 0u) | (above ? ~lower & 0xffu : 0u);
        }
      }
      // Visit order j = octant XOR sign_mask. Permute the child mask into that
      // order (XOR of the index by the sign bits swaps bits, pairs and nibbles),
      // then walk only the present children, farthest first so the nearest is
      // pushed last and popped next: a loop of as many trips as children, not 8.
      uint ordered = mask;
      if ((sign_mask & 1u) != 0u) ordered = ((ordered & 0x55u) << 1) | ((ordered >> 1) & 0x55u);
      if ((sign_mask & 2u) != 0u) ordered = ((ordered & 0x33u) << 2) | ((ordered >> 2) & 0x33u);
      if ((sign_mask & 4u) != 0u) ordered = ((ordered & 0x0fu) << 4) | ((ordered >> 4) & 0x0fu);
      while (ordered != 0u) {
        uint j = uint(findMSB(ordered));
        ordered ^= 1u << j;
        uint octant = j ^ sign_mask;
        uint child = node.first + bitCount(present & ((1u << octant) - 1u));
        GpuOctreeNode c = node_at(child);
        if (hit_box(c.lo, c.hi, sr, hit.t, t_entry)) {
          stack[sp] = uvec2(child, floatBitsToUint(t_entry));
          ++sp;
        }
      }
    }
  }
}

