// One octree walk, included once per level (no include guard): the includer
// defines OCTREE_WALK_NAME (the function's name) and OCTREE_LEAF(ref) (what a
// leaf's reference is tested with; it may use the walk's parameters), then
// undefines them. The walk is the same at both levels; only the leaf differs.
// With ACCEL == ACCEL_BVH the arrays hold a BVH and accel/bvh_walk.glsl walks it.
void OCTREE_WALK_NAME(uint root_index, Ray ray, RayShear sh, uint from_prim, bool into_from, InstanceRef ir,
                      inout Hit hit) {
  if (ACCEL == ACCEL_BVH) {
#include "accel/bvh_walk.glsl"
    return;
  }
  vec3 inv_dir = safe_inverse(ray.dir);
  uint sign_mask = (floatBitsToUint(ray.dir.x) >> 31) | ((floatBitsToUint(ray.dir.y) >> 31) << 1) |
                   ((floatBitsToUint(ray.dir.z) >> 31) << 2);
  uint stack_node[STACK_SIZE];
  float stack_entry[STACK_SIZE];  // where the ray enters the node's box
  uint sp = 0;
  float t_entry;
  GpuOctreeNode root = node_at(root_index);
  if (hit_box(root.lo, root.hi, ray.origin, inv_dir, hit.t, t_entry)) {
    stack_node[0] = root_index;
    stack_entry[0] = t_entry;
    sp = 1;
  }

  while (sp > 0) {
    --sp;
    // The node was pushed when its box was met before the nearest hit of that
    // moment; a nearer hit found since rules it out (the early exit).
    if (stack_entry[sp] > hit.t * WIDEN) continue;
    GpuOctreeNode node = node_at(stack_node[sp]);
    if (node.count_or_mask < OCTREE_INTERNAL) {
      for (uint k = node.first; k < node.first + node.count_or_mask; ++k)
        OCTREE_LEAF(ref_at(k));
      continue;
    }
    uint mask = node.count_or_mask & 0xffu;
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
      uint child = node.first + bitCount(mask & ((1u << octant) - 1u));
      GpuOctreeNode c = node_at(child);
      if (hit_box(c.lo, c.hi, ray.origin, inv_dir, hit.t, t_entry)) {
        stack_node[sp] = child;
        stack_entry[sp] = t_entry;
        ++sp;
      }
    }
  }
}

