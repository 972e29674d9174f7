// Octree traversal (renderer/accel/octree.h has the node encoding): the box
// test and the stack bound here; the walk itself in accel/octree_walk.glsl,
// once for the top level and once for the meshes' own octrees.
#ifndef OCTRACE_OCTREE_GLSL
#define OCTRACE_OCTREE_GLSL

#include "geometry/ray.glsl"

// Slab test. The exit distance is widened by 1 + 2 gamma(3) (pbrt-v4,
// "Robust Ray-Bounds Intersections"): the rounding of (plane - origin) * inv
// could otherwise make a ray that grazes a face miss the box. Returns whether
// the ray meets the box before t_max, and where it enters (>= 0).
// The same widening applies to comparisons of an entry distance with the
// nearest hit: the computed entry may lie a few ulps past the true one.
// Octant culling in the walk (accel/octree_walk.glsl; SPEC_OCTANT_CULLING).
layout(constant_id = SPEC_OCTANT_CULLING) const bool OCTANT_CULLING = true;

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

// The BVH walk's stack (accel/bvh_walk.glsl): one entry per level and the root.
const uint BVH_STACK_SIZE = BVH_MAX_DEPTH + 1u;

#endif
