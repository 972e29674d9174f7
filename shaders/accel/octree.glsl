// Octree traversal (renderer/accel/octree.h has the node encoding): the box
// test and the stack bound here; the walk itself in accel/octree_walk.glsl,
// once for the top level and once for the meshes' own octrees.
#ifndef OCTRACE_OCTREE_GLSL
#define OCTRACE_OCTREE_GLSL

#include "geometry/ray.glsl"

// Slab tests. Two forms of one test, each walk naming its own
// (OCTREE_SLAB in accel/octree_walk.glsl): the per-ray part is worked out
// once per walk (slab_ray, fused_slab_ray), and hit_box returns whether the
// ray meets the box before t_max, and where it enters (>= 0).
// The exit distance is widened by 1 + 2 gamma(3) (pbrt-v4, "Robust
// Ray-Bounds Intersections"): the rounding of (plane - origin) * inv could
// otherwise make a ray that grazes a face miss the box. The same widening
// applies to comparisons of an entry distance with the nearest hit: the
// computed entry may lie a few ulps past the true one.
// Octant culling in the walk (accel/octree_walk.glsl; SPEC_OCTANT_CULLING).
layout(constant_id = SPEC_OCTANT_CULLING) const bool OCTANT_CULLING = true;
// Where the walks test a tree's big list (accel/octree_walk.glsl): as the
// walk's first leaf, or (false) in a loop of the caller's. The host chooses
// (render/path_tracer.cpp, BigList): the image is the same either way.
layout(constant_id = SPEC_BIG_LEAF) const bool BIG_LEAF = true;
// Whether the octree walk keeps a node's nearest child in registers instead
// of pushing it (accel/octree_descend.glsl; the host chooses per device,
// RenderSettings::nearest_child): the image is the same either way.
layout(constant_id = SPEC_OCTREE_HOLD_NEAREST) const bool HOLD_NEAREST = false;
// Whether the BVH's top level and its meshes' trees are four-wide
// (SPEC_BVH_TOP_WIDE, SPEC_BVH_MESH_WIDE): which walk accel/octree_walk.glsl
// takes at each level.
layout(constant_id = SPEC_BVH_TOP_WIDE) const bool BVH_TOP_WIDE = false;
layout(constant_id = SPEC_BVH_MESH_WIDE) const bool BVH_MESH_WIDE = false;
// Whether the top level's binary BVH walk is in while-while form
// (SPEC_BVH_TOP_WHILE; accel/bvh_walk.glsl).
layout(constant_id = SPEC_BVH_TOP_WHILE) const bool BVH_TOP_WHILE = false;

const float WIDEN = 1.0 + 2.0 * (3.0 * 5.96046448e-8) / (1.0 - 3.0 * 5.96046448e-8);

// The top-level walk's form: a subtraction and a multiplication per plane.
struct SlabRay {
  vec3 origin;
  vec3 inv;
};

SlabRay slab_ray(Ray ray) { return SlabRay(ray.origin, safe_inverse(ray.dir)); }

bool hit_box(vec3 lo, vec3 hi, SlabRay r, float t_max, out float t_entry) {
  vec3 t0 = (lo - r.origin) * r.inv;
  vec3 t1 = (hi - r.origin) * r.inv;
  vec3 near_t = min(t0, t1);
  vec3 far_t = max(t0, t1);
  t_entry = max(max(near_t.x, near_t.y), max(near_t.z, 0.0));
  float t_exit = min(min(far_t.x, far_t.y), far_t.z) * WIDEN;
  return t_entry <= t_exit && t_entry <= t_max * WIDEN;
}

// The mesh walk's form: one multiply-add per plane, plane * inv + ood with
// ood = -origin * inv. Vulkan lets fma() round like a multiplication
// followed by an addition, so take that case: the product's rounding is at
// most u (|t| + |ood|) and ood's own u |ood| (u = 2^-24), an error no longer
// relative to the distance t alone (it does not shrink as the plane nears
// the origin). `err` = 2^-22 max |ood_a| bounds the part in |ood| with a
// factor 2 to spare, and the test widens by it: entry - err and exit + err.
// WIDEN covers the relative rest (inv's, the product's and the sum's
// roundings: 3 u, as in the subtract-multiply form). So, as there, no box
// the exact ray meets is rejected, and the entry returned is a lower bound
// of where the exact ray enters: the walk's early exit and the octant
// culling (which widen it by WIDEN) stay safe. An axis the ray does not
// move along has inv = +-2^64 (ray.glsl, safe_inverse): origin * 2^64 and
// plane * 2^64 are exact (a power of two; finite for |origin| < 2^64), so
// that axis adds nothing to err and its distances keep exact signs.
// Why only there (optimisation log 37): on the H200 it takes the mesh
// pipeline from 126 to 96 registers and the engine 8% faster, and changes
// nothing on the balloon; in the top-level walk the one margin for every
// axis loosens the boxes of dense sphere fields (+10% at 1M spheres), and a
// margin per axis, folded into two offsets, gains nothing (log 35).
struct FusedSlabRay {
  vec3 inv;
  vec3 ood;
  float err;
};

FusedSlabRay fused_slab_ray(Ray ray) {
  FusedSlabRay r;
  r.inv = safe_inverse(ray.dir);
  r.ood = -ray.origin * r.inv;
  vec3 e = mix(abs(r.ood), vec3(0.0), equal(ray.dir, vec3(0.0)));
  r.err = max(max(e.x, e.y), e.z) * 2.3841858e-7;  // 2^-22
  return r;
}

bool hit_box(vec3 lo, vec3 hi, FusedSlabRay r, float t_max, out float t_entry) {
  vec3 t0 = fma(lo, r.inv, r.ood);
  vec3 t1 = fma(hi, r.inv, r.ood);
  vec3 near_t = min(t0, t1);
  vec3 far_t = max(t0, t1);
  t_entry = max(max(max(near_t.x, near_t.y), near_t.z) - r.err, 0.0);
  float t_exit = min(min(min(far_t.x, far_t.y), far_t.z) + r.err, t_max) * WIDEN;
  return t_entry <= t_exit;
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

// The children of an internal octree node that the walk visits, as a mask
// in visit order (bit j: octant j XOR sign_mask; accel/octree_descend.glsl
// walks it from the highest bit, the farthest child, down), given where the
// ray enters the node (entry) and the nearest hit so far (t_hit).
//
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
//
// Visit order j = octant XOR sign_mask: the child mask permuted into that
// order (XOR of the index by the sign bits swaps bits, pairs and nibbles),
// so the walk's loop takes only the present children, not 8 trips.
uint octree_children_order(GpuOctreeNode node, float entry, vec3 origin, vec3 inv_dir, uint sign_mask, float t_hit) {
  uint present = node.count_or_mask & 0xffu;  // children's octants; child index = rank in it
  uint mask = present;
  if (OCTANT_CULLING) {
    vec3 mid = node.lo + 0.5 * (node.hi - node.lo);
    vec3 t_mid = (mid - origin) * inv_dir;
    float t_in = entry / WIDEN;
    float t_out = t_hit * WIDEN;
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
  uint ordered = mask;
  if ((sign_mask & 1u) != 0u) ordered = ((ordered & 0x55u) << 1) | ((ordered >> 1) & 0x55u);
  if ((sign_mask & 2u) != 0u) ordered = ((ordered & 0x33u) << 2) | ((ordered >> 2) & 0x33u);
  if ((sign_mask & 4u) != 0u) ordered = ((ordered & 0x0fu) << 4) | ((ordered >> 4) & 0x0fu);
  return ordered;
}

// The child at bit j of a node's visit order (octree_children_order's
// `ordered`): the child in octant j XOR sign_mask, whose index is `first`
// plus its rank among the `present` octants.
uint visit_child(uint j, uint present, uint first, uint sign_mask) {
  return first + bitCount(present & ((1u << (j ^ sign_mask)) - 1u));
}

// The next child of a node's visit order: its highest bit, taken out of
// `ordered`.
uint take_child(inout uint ordered, uint present, uint first, uint sign_mask) {
  uint j = uint(findMSB(ordered));
  ordered ^= 1u << j;
  return visit_child(j, present, first, sign_mask);
}

// The BVH walks' stacks (accel/bvh_walk.glsl, binary and four-wide): a
// visit pops one entry (the binary walk: or descends) and pushes at most a
// node's children (the binary walk: the farther one), so each level leaves
// at most one fewer than a node's children behind; and the root.
const uint BVH_STACK_SIZE = BVH_MAX_DEPTH + 1u;
const uint BVH_WIDE_STACK_SIZE = (BVH_WIDTH - 1u) * BVH_MAX_DEPTH + 1u;

// The four-wide BVH walk's steps on a node's children (accel/bvh_walk.glsl
// has the keys and their order): the key of child c (< bvh_n; a node has at least
// two, so the test folds away for c = 0 and 1) of `node`, a
// compare-exchange of two keys, and the push of a key's child (none for a
// miss). Macros, because the walk is the body of two functions whose slab
// terms `sr` differ in type.
const uint BVH_MISS = 0xffffffffu;
#define BVH_CHILD_KEY(c, key)                                               \
  key = BVH_MISS;                                                           \
  if (c < 2u || c < bvh_n) {                                                \
    GpuOctreeNode bvh_child = node_at(node.first + c);                      \
    if (hit_box(bvh_child.lo, bvh_child.hi, sr, hit.t, bvh_t))              \
      key = (floatBitsToUint(bvh_t) & ~3u) | c;                             \
  }
#define BVH_ORDER(a, b) \
  {                     \
    uint bvh_lo = min(a, b); \
    b = max(a, b);      \
    a = bvh_lo;         \
  }
#define BVH_PUSH(key)                                                     \
  if (key != BVH_MISS) {                                                  \
    bvh_stack[bvh_sp] = uvec2(node.first + (key & 3u), key & ~3u);        \
    ++bvh_sp;                                                             \
  }

#endif
