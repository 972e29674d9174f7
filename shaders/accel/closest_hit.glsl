// Closest hit against the scene: the one function the path tracer calls to
// find what a ray meets. The acceleration structure (specialization constant
// ACCEL) lives behind it. The includer declares `params`, `spheres`,
// `octree_nodes` and `octree_refs`.
#ifndef OCTRACE_SCENE_HIT_GLSL
#define OCTRACE_SCENE_HIT_GLSL

#include "geometry/sphere.glsl"

layout(constant_id = SPEC_ACCEL) const uint ACCEL = ACCEL_OCTREE;

struct Hit {
  float t;
  uint sphere;
};

const uint NO_SPHERE = 0xffffffffu;

// Tests sphere i and keeps it in `hit` if it is the nearest so far.
// `from_sphere`: the sphere the ray was spawned on (NO_SPHERE for camera
// rays); `into_from`: whether the ray enters that sphere (see intersect_sphere).
void test_sphere(Ray ray, uint i, uint from_sphere, bool into_from, inout Hit hit) {
  bool self = i == from_sphere;
  GpuSphere s = spheres[i];
  // t_max is hit.t widened by one ulp so that a sphere at exactly the same
  // distance is seen; the tie then goes to the lower index. The result is
  // independent of the order spheres are tested in (octree == brute force).
  float t = intersect_sphere(ray, s.center, s.radius, uintBitsToFloat(floatBitsToUint(hit.t) + 1u),
                             self && into_from, self && !into_from);
  if (t < hit.t || (t == hit.t && t != INF && i < hit.sphere)) {
    hit.t = t;
    hit.sphere = i;
  }
}

// 1/dir without infinities: a component of +0 or -0 becomes +-FLT_MAX, so a
// slab distance (plane - origin) * inv is never 0 * inf = NaN; it is +-inf
// (overflow) or 0 when the origin lies on the plane, and both keep the slab
// test right (the ray runs parallel inside or outside the slab).
vec3 safe_inverse(vec3 d) {
  const float BIG = 3.402823466e38;
  return vec3(d.x == 0.0 ? (floatBitsToUint(d.x) != 0u ? -BIG : BIG) : 1.0 / d.x,
              d.y == 0.0 ? (floatBitsToUint(d.y) != 0u ? -BIG : BIG) : 1.0 / d.y,
              d.z == 0.0 ? (floatBitsToUint(d.z) != 0u ? -BIG : BIG) : 1.0 / d.z);
}

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

bool closest_hit(Ray ray, uint from_sphere, bool into_from, out Hit hit) {
  hit.t = INF;
  hit.sphere = NO_SPHERE;
  if (ACCEL == ACCEL_BRUTE) {
    for (uint i = 0; i < params.sphere_count; ++i) test_sphere(ray, i, from_sphere, into_from, hit);
    return hit.sphere != NO_SPHERE;
  }

  // Spheres too large for the octree's cells are tested first.
  for (uint i = 0; i < params.big_count; ++i) test_sphere(ray, octree_refs[i], from_sphere, into_from, hit);

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
        test_sphere(ray, octree_refs[k], from_sphere, into_from, hit);
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
  return hit.sphere != NO_SPHERE;
}

#endif
