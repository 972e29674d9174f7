// The inner loop of the octree walk (accel/octree_walk.glsl includes it in
// both of its forms; no include guard): it visits nodes until the invocation
// holds a leaf, whose references it leaves in [leaf_first, leaf_end), or its
// stack is empty (the range is then empty). It uses the walk's stack, sp,
// ray, sr, inv_dir, sign_mask, t_entry, hit and leaf_lane, and the
// includer's OCTREE_CHILD_PAIRS and OCTREE_SPLIT.
//
// Two forms of the loop, the same nodes in the same order (HOLD_NEAREST,
// accel/octree.glsl; the host picks per device, RenderSettings::
// nearest_child; a split walk, OCTREE_SPLIT, always takes the pushed
// form). Pushed: every child the ray meets is pushed, farthest
// first, and the loop pops the nearest straight back. Held: the nearest is
// kept in registers and visited next, the others pushed; a pop comes only
// where a node's children all miss. On lavapipe, which runs a loop until
// its last SIMD lane is done, that is a trip per node instead of one per
// entry: the default scene 5-10% faster, the engine 12%; on the H200 3-5%
// slower (optimisation log 60). Either way a popped node whose box starts
// beyond a nearer hit found since it was pushed is skipped (the early
// exit); the held child's entry was tested against the nearest hit of the
// moment, so the skip could not have taken it.
if (HOLD_NEAREST && !OCTREE_SPLIT) {
  uint cur_node = 0u;
  float cur_entry = 0.0;
  bool go = false;
  while (sp > 0) {
    --sp;
    uvec2 top = stack[sp];
    if (!(uintBitsToFloat(top.y) > hit.t * WIDEN)) {  // as the pushed form's skip, NaN included
      cur_node = top.x;
      cur_entry = uintBitsToFloat(top.y);
      go = true;
      break;
    }
  }
  while (go) {
    GpuOctreeNode node = node_at(cur_node);
    if (node.count_or_mask < OCTREE_INTERNAL) {
      leaf_first = node.first;
      leaf_end = node.first + node.count_or_mask;
      break;
    }
    if (WALK_STATS) {
      ++walk_nodes;
      walk_node_slots += walk_slots();
    }
    uint present = node.count_or_mask & 0xffu;
    uint ordered = octree_children_order(node, cur_entry, ray.origin, inv_dir, sign_mask, hit.t);
    bool have = false;
    while (ordered != 0u) {
      uint child = take_child(ordered, present, node.first, sign_mask);
      GpuOctreeNode c = node_at(child);
      if (WALK_STATS) ++walk_boxes;
      if (hit_box(c.lo, c.hi, sr, hit.t, t_entry)) {
        if (have) {
          stack[sp] = uvec2(cur_node, floatBitsToUint(cur_entry));
          ++sp;
        }
        cur_node = child;
        cur_entry = t_entry;
        have = true;
      }
    }
    if (!have) {
      go = false;
      while (sp > 0) {
        --sp;
        uvec2 top = stack[sp];
        if (!(uintBitsToFloat(top.y) > hit.t * WIDEN)) {
          cur_node = top.x;
          cur_entry = uintBitsToFloat(top.y);
          go = true;
          break;
        }
      }
    }
  }
} else {
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
    if (WALK_STATS) {
      ++walk_nodes;
      walk_node_slots += walk_slots();
    }
    uint present = node.count_or_mask & 0xffu;  // children's octants; child index = rank in it
    uint ordered = octree_children_order(node, top_entry, ray.origin, inv_dir, sign_mask, hit.t);
    if (OCTREE_SPLIT) {
      // Split (the walk's OCTREE_SPLIT: every lane walks this ray): lane j
      // of the first eight tests the child at bit j of the visit order, and
      // every lane pushes the children met, the highest bit first, each
      // entry distance from its lane (a ballot, then a shuffle a child), so
      // the stacks hold what the one-lane loop below pushes, in its order.
      // The held form above is not taken when split (the same nodes in the
      // same order either way). The ballot after the lanes' own tests needs
      // them reconverged, as agree_on_hit does (accel/octree_walk.glsl).
      // On the H100 the engine 0.990x, the balloon 0.948x (optimisation
      // log 142).
      bool mine = leaf_lane < 8u && ((ordered >> leaf_lane) & 1u) != 0u;
      float t_mine = 0.0;
      bool met = false;
      if (mine) {
        GpuOctreeNode c = node_at(visit_child(leaf_lane, present, node.first, sign_mask));
        met = hit_box(c.lo, c.hi, sr, hit.t, t_mine);
      }
      if (WALK_STATS) walk_boxes += bitCount(ordered);
      uint met_mask = subgroupBallot(met).x & 0xffu;
      while (met_mask != 0u) {
        uint j = uint(findMSB(met_mask));
        met_mask ^= 1u << j;
        stack[sp] = uvec2(visit_child(j, present, node.first, sign_mask), floatBitsToUint(subgroupShuffle(t_mine, j)));
        ++sp;
      }
    } else if (OCTREE_CHILD_PAIRS) {
      // The meshes' walk: two children a trip, in the order one at a time
      // takes them, the second's load issued beside the first's (a lone
      // last child loads its node twice and drops the second result), so
      // the same pushes in the same order: a warp runs half the trips of
      // its busiest invocation. On the H200 the engine 5.7% and the balloon
      // 3.1% faster, the sphere fields the same or 0.7% slower
      // (optimisation log 81), so the top level tests one child a trip.
      while (ordered != 0u) {
        uint child = take_child(ordered, present, node.first, sign_mask);
        bool two = ordered != 0u;
        uint child2 = child;
        if (two) child2 = take_child(ordered, present, node.first, sign_mask);
        GpuOctreeNode c = node_at(child);
        GpuOctreeNode c2 = node_at(child2);
        if (WALK_STATS) walk_boxes += two ? 2u : 1u;
        float t_entry2;
        bool hit1 = hit_box(c.lo, c.hi, sr, hit.t, t_entry);
        bool hit2 = hit_box(c2.lo, c2.hi, sr, hit.t, t_entry2) && two;
        if (hit1) {
          stack[sp] = uvec2(child, floatBitsToUint(t_entry));
          ++sp;
        }
        if (hit2) {
          stack[sp] = uvec2(child2, floatBitsToUint(t_entry2));
          ++sp;
        }
      }
    } else {
      while (ordered != 0u) {
        uint child = take_child(ordered, present, node.first, sign_mask);
        GpuOctreeNode c = node_at(child);
        if (WALK_STATS) ++walk_boxes;
        if (hit_box(c.lo, c.hi, sr, hit.t, t_entry)) {
          stack[sp] = uvec2(child, floatBitsToUint(t_entry));
          ++sp;
        }
      }
    }
  }
}
