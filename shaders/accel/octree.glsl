// Octree traversal (renderer/accel/octree.h has the node encoding). The
// includer defines test_primitive(ray, shear, ref, origin_prim, into_origin, hit)
// (accel/closest_hit.glsl) and declares `octree_nodes`.
#ifndef OCTRACE_OCTREE_GLSL
#define OCTRACE_OCTREE_GLSL

#include "geometry/ray.glsl"

// Slab test. The exit distance is widened by 1 + 2 gamma(3) (pbrt-v4,
// "Robust Ray-Bounds Intersections"): the rounding of (plane - origin) * inv
// could otherwise make a ray that grazes a face miss the box. Returns whether
// the ray meets the box before t_max, and where it enters (>= 0).
// The same widening applies to comparisons of an entry distance with the
// nearest hit: the computed entry may lie a few ulps past the true one.
const float WIDEN = 1.0 + 2.0 * (3.0 * 5.96046448e-8) / (1.0 - 3.0 * 5.96046448e-8);

bool hit_box(vec3 lo, vec3 hi, vec3 origin, vec3 inv_dir, float t_max, out float t_entry) {
  vec3 t0 = (lo - origin) * inv_dir;
  vec3 t1 = (hi - origin) * inv_dir;
  vec3 near_t = min(t0, t1);
  vec3 far_t = max(t0, t1);
  t_entry = max(max(near_t.x, near_t.y), max(near_t.z, 0.0));
  float t_exit = min(min(far_t.x, far_t.y), far_t.z) * WIDEN;
  return t_entry <= t_exit && t_entry <= t_max * WIDEN;
}

// Octree traversal, front to back with a stack of (node, entry distance). Children are
// visited in octant order XOR the ray's sign mask: for the disjoint boxes of
// one node's children this is an order in which no child can be entered
// after one listed later (Revelles et al. 2000, "An efficient parametric
// algorithm for octree traversal", first-node/next-node ordering by octant).
// Popping a node whose box starts beyond the nearest hit found so far skips
// it (the early exit). Spheres that straddle cells sit in several leaves;
// taking the minimum over every test finds the nearest one once and right.
//
// Stack bound: a ray meets at most 8 children of a node (4 in general, up to
// 8 when it runs exactly along split planes), so each level leaves at most 7
// entries behind: 7 * 20 + 1 entries for the deepest octree (depth 20).
const uint STACK_SIZE = 141u;

void traverse_octree(Ray ray, RayShear sh, uint from_prim, bool into_from, inout Hit hit) {
  vec3 inv_dir = safe_inverse(ray.dir);
  uint sign_mask = (floatBitsToUint(ray.dir.x) >> 31) | ((floatBitsToUint(ray.dir.y) >> 31) << 1) |
                   ((floatBitsToUint(ray.dir.z) >> 31) << 2);
  uint stack_node[STACK_SIZE];
  float stack_entry[STACK_SIZE];  // where the ray enters the node's box
  uint sp = 0;
  float t_entry;
  GpuOctreeNode root = octree_nodes[0];
  if (hit_box(root.lo, root.hi, ray.origin, inv_dir, hit.t, t_entry)) {
    stack_node[0] = 0u;
    stack_entry[0] = t_entry;
    sp = 1;
  }

  while (sp > 0) {
    --sp;
    // The node was pushed when its box was met before the nearest hit of that
    // moment; a nearer hit found since rules it out (the early exit).
    if (stack_entry[sp] > hit.t * WIDEN) continue;
    GpuOctreeNode node = octree_nodes[stack_node[sp]];
    if (node.count_or_mask < OCTREE_INTERNAL) {
      for (uint k = node.first; k < node.first + node.count_or_mask; ++k)
        test_primitive(ray, sh, octree_refs[k], from_prim, into_from, hit);
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
      GpuOctreeNode c = octree_nodes[child];
      if (hit_box(c.lo, c.hi, ray.origin, inv_dir, hit.t, t_entry)) {
        stack_node[sp] = child;
        stack_entry[sp] = t_entry;
        ++sp;
      }
    }
  }
}

#endif
