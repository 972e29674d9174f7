// The BVH walks (renderer/accel/bvh.h has the encoding): the body of the
// walk for ACCEL == ACCEL_BVH, included at the top of accel/octree_walk.glsl
// inside `if (ACCEL == ACCEL_BVH) { ... return; }`, once with BVH_WALK_WIDE
// 0 (binary trees: by default a top level with spheres, and every tree on a
// CPU device) and once with 1 (four-wide trees: by default on a GPU the
// meshes, and a top level over instances only), under the includer's
// OCTREE_BVH_WIDE; so that both take the walk's parameters and
// OCTREE_LEAF(k), and a pipeline specialised to one structure and width
// compiles only its walk. The four-wide walk takes binary trees too, but
// slower than the binary walk (optimisation log 54).
//
// Stack-based, front to back: of an internal node's children, those whose
// box the ray meets before the nearest hit are visited nearest (by entry
// distance) first. The four-wide walk pushes them, the farthest first, with
// their entry distances, and skips a popped node whose box starts beyond the
// nearest hit found since it was pushed (the early exit), with the same
// widening as the octree's. The binary walk descends into the nearer child
// and pushes only the farther, without its distance (below). Stack bounds:
// BVH_STACK_SIZE and BVH_WIDE_STACK_SIZE (accel/octree.glsl).
//
// The four-wide walk's order (two to BVH_WIDTH = 4 consecutive children): a
// child's key is the bits of its entry distance with the low two replaced
// by its place among the children, a miss's key 0xffffffff; five
// compare-exchanges sort the four keys (a sorting network). Entry distances
// are >= 0, so their bits order as the floats do, and every hit's key
// (<= 0x7fffffff) comes before every miss. The entry pushed is the key's
// distance with those two bits cleared: at most 3 ulps below the computed
// one, still a lower bound of where the ray enters, so the early exit stays
// safe; children whose entries differ by less go in the order of their places.
OCTREE_SLAB sr = OCTREE_SLAB_MAKE(ray);  // named as the octree walk's: OCTREE_LEAF may use it
float bvh_t;
GpuOctreeNode bvh_root = node_at(root_index);
if (WALK_STATS) ++walk_boxes;
#if BVH_WALK_WIDE
uvec2 bvh_stack[BVH_WIDE_STACK_SIZE];  // (node, bits of its entry distance), as the octree walk's stack
uint bvh_sp = 0;
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
  uint bvh_n = bitCount(node.count_or_mask & 0xfu);
  if (WALK_STATS) {
    ++walk_nodes;
    walk_node_slots += walk_slots();
    walk_boxes += bvh_n;
  }
  uint bvh_k0, bvh_k1, bvh_k2, bvh_k3;
  BVH_CHILD_KEY(0u, bvh_k0)
  BVH_CHILD_KEY(1u, bvh_k1)
  BVH_CHILD_KEY(2u, bvh_k2)
  BVH_CHILD_KEY(3u, bvh_k3)
  BVH_ORDER(bvh_k0, bvh_k1)
  BVH_ORDER(bvh_k2, bvh_k3)
  BVH_ORDER(bvh_k0, bvh_k2)
  BVH_ORDER(bvh_k1, bvh_k3)
  BVH_ORDER(bvh_k1, bvh_k2)
  BVH_PUSH(bvh_k3)
  BVH_PUSH(bvh_k2)
  BVH_PUSH(bvh_k1)
  BVH_PUSH(bvh_k0)
}
#else
// The binary walk keeps the node it visits in registers as its header
// (first, count_or_mask): a child's header comes with the 32 bytes of its
// box, so descending into the nearer child loads nothing more, and a pop
// gives the next node's header at once. Only the farther child is pushed,
// as its header, without its entry distance: no early exit on a pop (the
// CUDA peer's form). On the H200 2-5% faster than a stack of (node, entry)
// pairs with the early exit, though it tests more primitives (optimisation
// log 59); its image is the same, since every primitive the nearest hit
// could be is still tested and the hit's choice does not depend on the order.
uvec2 bvh_stack[BVH_STACK_SIZE];
uint bvh_sp = 0;
uint bvh_first = bvh_root.first, bvh_count = bvh_root.count_or_mask;
bool bvh_have = hit_box(bvh_root.lo, bvh_root.hi, sr, hit.t, bvh_t);
// One node step (bvh_first, bvh_count an internal node): the nearer child
// met becomes the node, the farther is pushed; where neither is met the
// next node is popped, and where the stack is empty the walk ends
// (bvh_have false, then `break`).
#define BVH_BINARY_NODE_STEP                                                                                  \
  if (WALK_STATS) {                                                                                           \
    ++walk_nodes;                                                                                             \
    walk_node_slots += walk_slots();                                                                          \
    walk_boxes += 2u;                                                                                         \
  }                                                                                                           \
  GpuOctreeNode left = node_at(bvh_first);                                                                    \
  GpuOctreeNode right = node_at(bvh_first + 1u);                                                              \
  float t_left, t_right;                                                                                      \
  bool hit_left = hit_box(left.lo, left.hi, sr, hit.t, t_left);                                               \
  bool hit_right = hit_box(right.lo, right.hi, sr, hit.t, t_right);                                           \
  if (hit_left && hit_right) {                                                                                \
    /* The farther pushed; equal entries keep the left child nearer. */                                       \
    bool right_first = t_right < t_left;                                                                      \
    bvh_stack[bvh_sp] = right_first ? uvec2(left.first, left.count_or_mask) : uvec2(right.first, right.count_or_mask); \
    ++bvh_sp;                                                                                                 \
  }                                                                                                           \
  if (hit_left || hit_right) {                                                                                \
    bool bvh_right = hit_right && (!hit_left || t_right < t_left);                                            \
    bvh_first = bvh_right ? right.first : left.first;                                                         \
    bvh_count = bvh_right ? right.count_or_mask : left.count_or_mask;                                         \
  } else {                                                                                                    \
    if (bvh_sp == 0u) {                                                                                       \
      bvh_have = false;                                                                                       \
      break;                                                                                                  \
    }                                                                                                         \
    --bvh_sp;                                                                                                 \
    bvh_first = bvh_stack[bvh_sp].x;                                                                          \
    bvh_count = bvh_stack[bvh_sp].y;                                                                          \
  }
// The leaf (bvh_first, bvh_count) tested, then the next node popped; where
// the stack is empty the walk ends (`break`).
#define BVH_BINARY_LEAF                                              \
  if (WALK_STATS && bvh_count > 0u) ++walk_leaves;                   \
  for (uint k = bvh_first; k < bvh_first + bvh_count; ++k)           \
    OCTREE_LEAF(k);                                                  \
  if (bvh_sp == 0u) break;                                           \
  --bvh_sp;                                                          \
  bvh_first = bvh_stack[bvh_sp].x;                                   \
  bvh_count = bvh_stack[bvh_sp].y;
if (OCTREE_BVH_WHILE) {
  // While-while (Aila & Laine 2009, as the octree walks since log 38): the
  // inner loop steps through internal nodes until this invocation holds a
  // leaf, and the leaf is tested after it, so the invocations of a
  // subgroup test their leaves together. The same nodes in the same order
  // as the one loop below. Where leaves hold many primitives (the dense
  // sphere fields) it is the faster form; where they hold one or two, the
  // one loop (optimisation log 123; RenderSettings::bvh_walk).
  while (bvh_have) {
    while (bvh_count >= OCTREE_INTERNAL) {
      BVH_BINARY_NODE_STEP
    }
    if (!bvh_have) break;
    BVH_BINARY_LEAF
  }
} else {
  // One loop: a step is either a leaf or a node.
  while (bvh_have) {
    if (bvh_count < OCTREE_INTERNAL) {
      BVH_BINARY_LEAF
      continue;
    }
    BVH_BINARY_NODE_STEP
  }
}
#undef BVH_BINARY_NODE_STEP
#undef BVH_BINARY_LEAF
#endif
