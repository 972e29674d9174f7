// The binary BVH walk (renderer/accel/bvh.h has the encoding): the body of
// the walk for ACCEL == ACCEL_BVH where OCTREE_BVH_WIDE is false (a binary
// tree: by default a top level with spheres, and every tree on a CPU
// device), included at the top of
// accel/octree_walk.glsl inside `if (ACCEL == ACCEL_BVH) { ... return; }`,
// so that it takes the walk's parameters and OCTREE_LEAF(k); a pipeline
// specialised to one structure compiles only its walks.
//
// Stack-based, front to back: of an internal node's two children, those
// whose box the ray meets before the nearest hit are pushed, the farther
// first, so the nearer (by entry distance) is popped next. A popped node
// whose box starts beyond the nearest hit found since it was pushed is
// skipped (the early exit), with the same widening as the octree's.
// Stack bound: each level leaves at most one entry behind (the farther
// child), so a tree of depth BVH_MAX_DEPTH (shared.h) needs BVH_MAX_DEPTH + 1.
OCTREE_SLAB sr = OCTREE_SLAB_MAKE(ray);  // named as the octree walk's: OCTREE_LEAF may use it
uvec2 bvh_stack[BVH_STACK_SIZE];  // (node, bits of its entry distance), as the octree walk's stack
uint bvh_sp = 0;
float bvh_t;
GpuOctreeNode bvh_root = node_at(root_index);
if (WALK_STATS) ++walk_boxes;
if (hit_box(bvh_root.lo, bvh_root.hi, sr, hit.t, bvh_t)) {
  bvh_stack[0] = uvec2(root_index, floatBitsToUint(bvh_t));
  bvh_sp = 1;
}
while (bvh_sp > 0) {
  --bvh_sp;
  uvec2 bvh_top = bvh_stack[bvh_sp];
  if (uintBitsToFloat(bvh_top.y) > hit.t * WIDEN) continue;
  GpuOctreeNode node = node_at(bvh_top.x);
  if (node.count_or_mask < OCTREE_INTERNAL) {
    if (WALK_STATS && node.count_or_mask > 0u) ++walk_leaves;
    for (uint k = node.first; k < node.first + node.count_or_mask; ++k)
      OCTREE_LEAF(k);
    continue;
  }
  if (WALK_STATS) {
    ++walk_nodes;
    walk_boxes += 2u;
  }
  GpuOctreeNode left = node_at(node.first);
  GpuOctreeNode right = node_at(node.first + 1u);
  float t_left, t_right;
  bool hit_left = hit_box(left.lo, left.hi, sr, hit.t, t_left);
  bool hit_right = hit_box(right.lo, right.hi, sr, hit.t, t_right);
  if (hit_left && hit_right) {
    // Farther first; equal entries keep the left child nearer.
    bool right_first = t_right < t_left;
    bvh_stack[bvh_sp] =
        uvec2(right_first ? node.first : node.first + 1u, floatBitsToUint(right_first ? t_left : t_right));
    bvh_stack[bvh_sp + 1u] =
        uvec2(right_first ? node.first + 1u : node.first, floatBitsToUint(right_first ? t_right : t_left));
    bvh_sp += 2u;
  } else if (hit_left || hit_right) {
    bvh_stack[bvh_sp] =
        uvec2(hit_left ? node.first : node.first + 1u, floatBitsToUint(hit_left ? t_left : t_right));
    ++bvh_sp;
  }
}
