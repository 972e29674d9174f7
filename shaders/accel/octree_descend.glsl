// The inner loop of the octree walk (accel/octree_walk.glsl includes it in
// both of its forms; no include guard): it pops nodes until the invocation
// holds a leaf, whose references it leaves in [leaf_first, leaf_end), or its
// stack is empty (the range is then empty). It uses the walk's stack, sp,
// ray, sr, inv_dir, sign_mask, t_entry and hit.
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
  if (WALK_STATS) ++walk_nodes;
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
    if (WALK_STATS) ++walk_boxes;
    if (hit_box(c.lo, c.hi, sr, hit.t, t_entry)) {
      stack[sp] = uvec2(child, floatBitsToUint(t_entry));
      ++sp;
    }
  }
}
