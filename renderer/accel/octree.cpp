// Octree build: encoding and rules in octree.h. The top of the tree is split on
// the calling thread until no pending subtree holds more than 1/16 of the
// references; the subtrees are then built in parallel, each into its own arrays,
// and concatenated in a fixed order, so the result does not depend on thread
// count or timing.
#include "accel/octree.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <numeric>
#include <string>

#include "accel/clip.h"
#include "core/clock.h"
#include "core/errors.h"
#include "core/parallel.h"

namespace octrace {
namespace {

using Box = Aabb;

// Half the surface area, in double: extents of 1e-3 at coordinates of 1e5 lose
// nothing to the products.
double half_area(const Box& b) {
  const glm::dvec3 e = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// A primitive reference as the build moves it around: its AABB travels with
// it so that splitting reads memory in order.
struct Ref {
  glm::vec3 lo;
  glm::vec3 hi;
  uint32_t prim;
};

// Octant sets: kLower[a] = the octants on the low side of axis a.
constexpr uint8_t kLower[3] = {0x55, 0x33, 0x0F};

// A node's split into octants, planned before any reference moves.
struct Split {
  uint32_t mask = 0;
  uint32_t count[8] = {};
  Box box[8];
  size_t total = 0;  // references in all children together
};

// The cost of visiting a node in primitive tests: a box test costs about what
// a sphere test does, and a node is twice a sphere's bytes. With 1 instead, the
// 1M-sphere rtiow field is cut to leaves of 4 copies of the same few spheres
// (58 bytes per sphere instead of 21).
constexpr double kNodeCost = 2.0;

// The build's view of a node: what its split depends on besides its
// references. `budget` bounds the references its subtree's leaves may hold:
// the root has OctreeParams::max_refs times its references; a split shares its
// budget among the children in proportion to their references, and may not
// produce more references than the budget.
struct BuildNode {
  Box box;
  uint32_t depth;
  double budget;
};

BuildNode child_node(const BuildNode& parent, const Split& split, int k) {
  return {split.box[k], parent.depth + 1, parent.budget * split.count[k] / static_cast<double>(split.total)};
}

// Whether one of the node's references spans more than kCopyLeafSpan of its
// extent along an axis (OctreeParams::copy_leaf): any split of that axis
// would copy it into most children.
bool copies_a_reference(const Ref* refs, size_t n, const glm::vec3& extent) {
  const glm::vec3 span = kCopyLeafSpan * extent;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 e = refs[i].hi - refs[i].lo;
    for (int a = 0; a < 3; ++a)
      if (extent[a] > 0.0f && e[a] > span[a]) return true;
  }
  return false;
}

// Decides whether the node (references `refs`, box and depth in `node`) splits (octree.h
// "How it is built"). If it does, fills `split` and the octant set of each
// reference in `octants`.
//
// With `clip`, a reference goes only to the octants its primitive reaches
// (not every octant its box overlaps), and carries into each the box of the
// part inside: `parts` receives those, reference by reference in octant order.
//
// `straddled`: whether an axis that every reference's box straddles may be
// split (build_octree's clip_straddled); `narrowed`, if given, receives
// whether the straddle rule left out an axis the rest would split. `cost`,
// if given, receives the plan's expected cost (below), also when it loses.
bool plan_split(const Ref* refs, size_t n, const BuildNode& node, const OctreeParams& params, const ClipFn& clip,
                const ClipOctantsFn& clip_octants, uint8_t* octants, std::vector<Ref>& parts, Split& split,
                bool straddled = false, bool* narrowed = nullptr, double* cost = nullptr) {
  if (narrowed) *narrowed = false;
  if (n <= params.leaf_size || node.depth >= params.max_depth) return false;
  const Box& box = node.box;
  const glm::vec3 extent = box.hi - box.lo;
  if (n <= params.copy_leaf && copies_a_reference(refs, n, extent)) return false;
  const float largest = std::max({extent.x, extent.y, extent.z});
  glm::vec3 mid = box.lo + 0.5f * extent;
  size_t straddling[3] = {};
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) straddling[a] += refs[i].lo[a] < mid[a] && refs[i].hi[a] >= mid[a];
  bool any = false;
  for (int a = 0; a < 3; ++a) {
    // An axis not split gets mid = +inf: every reference is on its low side.
    const bool splittable = extent[a] >= 0.5f * largest && box.lo[a] < mid[a] && mid[a] < box.hi[a];
    const bool split_axis = splittable && (straddled || straddling[a] < n);
    if (narrowed && splittable && !split_axis) *narrowed = true;
    if (!split_axis) mid[a] = std::numeric_limits<float>::infinity();
    any |= split_axis;
  }
  if (!any) return false;

  parts.clear();
  for (size_t i = 0; i < n; ++i) {
    const Ref& r = refs[i];
    uint32_t set = 0xFF;
    for (int a = 0; a < 3; ++a)
      set &= (r.lo[a] < mid[a] ? kLower[a] : 0u) | (r.hi[a] >= mid[a] ? ~kLower[a] & 0xFFu : 0u);
    if (clip && (set & (set - 1)) != 0) {  // more than one octant (std::popcount is a libgcc call on x86-64)
      const uint32_t candidates = set;
      set = 0;
      Box cut[8];
      uint32_t reached = 0;
      if (clip_octants) {
        reached = clip_octants(r.prim, box, mid, candidates, cut);
      } else {
        for (uint32_t s = candidates; s != 0; s &= s - 1) {
          const int k = std::countr_zero(s);
          if (clip(r.prim, octant_cell(box, mid, uint32_t(k)), cut[k])) reached |= 1u << k;
        }
      }
      for (uint32_t s = reached; s != 0; s &= s - 1) {
        const int k = std::countr_zero(s);
        Box part = cut[k];
        // Never larger than what the reference had: the part lies in both.
        part.lo = glm::max(part.lo, r.lo);
        part.hi = glm::min(part.hi, r.hi);
        set |= 1u << k;
        parts.push_back({part.lo, part.hi, r.prim});
        ++split.count[k];
        split.box[k].extend(part);
      }
      // The primitive reached none (rounding, for a part on an octant's
      // face): it keeps every octant its box overlaps, so it is never lost.
      if (set == 0) {
        for (uint32_t s = candidates; s != 0; s &= s - 1) {
          const int k = std::countr_zero(s);
          parts.push_back(r);
          ++split.count[k];
          split.box[k].extend({r.lo, r.hi});
        }
        set = candidates;
      }
    } else {
      for (uint32_t s = set; s != 0; s &= s - 1) {
        const int k = std::countr_zero(s);
        if (clip) parts.push_back(r);
        ++split.count[k];
        split.box[k].extend({r.lo, r.hi});
      }
    }
    octants[i] = static_cast<uint8_t>(set);
    split.mask |= set;
  }
  // Clip each child's union of AABBs to its octant of the node's box.
  for (int k = 0; k < 8; ++k) {
    if (split.count[k] == 0) continue;
    split.total += split.count[k];
    Box& b = split.box[k];
    for (int a = 0; a < 3; ++a) {
      const bool upper = (k >> a) & 1;
      b.lo[a] = std::max(b.lo[a], upper ? mid[a] : box.lo[a]);
      b.hi[a] = std::min(b.hi[a], upper ? box.hi[a] : std::min(mid[a], box.hi[a]));
    }
  }
  // Surface area heuristic (MacDonald and Booth 1990): a ray that meets the
  // node meets child k with probability area_k / area. Split only if that
  // lowers the expected work.
  double split_cost = 0.0;
  for (int k = 0; k < 8; ++k)
    if (split.count[k] != 0) split_cost += half_area(split.box[k]) * (split.count[k] + kNodeCost);
  if (cost) *cost = split_cost;
  return split_cost < half_area(box) * static_cast<double>(n) &&
         static_cast<double>(split.total) <= node.budget;
}

// plan_split, and with `clip_straddled` where the straddle rule left an
// axis out, the plan with those axes split too: the one of lower cost
// (build_octree's clip_straddled). `spare_*` are scratch of the caller's.
bool plan_best_split(const Ref* refs, size_t n, const BuildNode& node, const OctreeParams& params,
                     const ClipFn& clip, const ClipOctantsFn& clip_octants, bool clip_straddled, uint8_t* octants,
                     std::vector<Ref>& parts, Split& split, std::vector<uint8_t>& spare_octants,
                     std::vector<Ref>& spare_parts) {
  bool narrowed = false;
  double cost = std::numeric_limits<double>::infinity();
  const bool planned = plan_split(refs, n, node, params, clip, clip_octants, octants, parts, split, false,
                                  clip_straddled ? &narrowed : nullptr, &cost);
  if (!narrowed) return planned;
  if (spare_octants.size() < n) spare_octants.resize(n);
  Split wider;
  double wider_cost = std::numeric_limits<double>::infinity();
  if (!plan_split(refs, n, node, params, clip, clip_octants, spare_octants.data(), spare_parts, wider, true, nullptr,
                  &wider_cost) ||
      (planned && !(wider_cost < cost)))
    return planned;
  split = wider;
  std::copy(spare_octants.begin(), spare_octants.begin() + n, octants);
  parts.swap(spare_parts);
  return true;
}

// Copies each reference into the ranges of its octants, keeping their order
// (so leaf references stay in ascending primitive order). Child k's range starts
// at dst + offset[k]. With clipped `parts` (plan_split), those are copied instead.
void scatter(const Ref* refs, size_t n, const uint8_t* octants, const std::vector<Ref>& parts, const Split& split,
             Ref* dst) {
  size_t offset[8];
  size_t at = 0;
  for (int k = 0; k < 8; ++k) {
    offset[k] = at;
    at += split.count[k];
  }
  size_t part = 0;
  for (size_t i = 0; i < n; ++i)
    for (uint32_t s = octants[i]; s != 0; s &= s - 1)
      dst[offset[std::countr_zero(s)]++] = parts.empty() ? refs[i] : parts[part++];
}

gpu::GpuOctreeNode make_node(const Box& box) { return {box.lo, 0, box.hi, 0}; }

// A subtree whose root is nodes[0]; `first` fields index this subtree's own
// arrays until it is appended to the whole tree.
struct Subtree {
  std::vector<gpu::GpuOctreeNode> nodes;
  std::vector<uint32_t> refs;
  uint32_t leaves = 0;
  uint32_t max_depth = 0;
};

// Depth-first build of one subtree. References live in one scratch stack: a
// node's children are written above its own range and popped when done, so the
// build allocates nothing per node once the buffers have grown.
class SubtreeBuilder {
 public:
  SubtreeBuilder(const OctreeParams& params, const ClipFn& clip, const ClipOctantsFn& clip_octants,
                 bool clip_straddled)
      : params_(params), clip_(clip), clip_octants_(clip_octants), clip_straddled_(clip_straddled) {}

  Subtree build(const std::vector<Ref>& refs, const BuildNode& root) {
    out_ = {};
    out_.nodes.push_back(make_node(root.box));
    reserve(refs.size());
    std::copy(refs.begin(), refs.end(), scratch_.begin());
    build_node(0, 0, refs.size(), refs.size(), root);
    return std::move(out_);
  }

 private:
  void reserve(size_t size) {
    if (scratch_.size() < size) scratch_.resize(std::max(size, 2 * scratch_.size()));
    if (octants_.size() < size) octants_.resize(std::max(size, 2 * octants_.size()));
  }

  // The node's references are scratch_[begin, end); scratch_ from `top` on is free.
  void build_node(uint32_t index, size_t begin, size_t end, size_t top, const BuildNode& node) {
    const size_t n = end - begin;
    out_.max_depth = std::max(out_.max_depth, node.depth);
    reserve(n);
    Split split;
    if (!plan_best_split(scratch_.data() + begin, n, node, params_, clip_, clip_octants_, clip_straddled_,
                         octants_.data(), parts_, split, spare_octants_, spare_parts_)) {
      out_.nodes[index].first = static_cast<uint32_t>(out_.refs.size());
      out_.nodes[index].count_or_mask = static_cast<uint32_t>(n);
      for (size_t i = begin; i < end; ++i) out_.refs.push_back(scratch_[i].prim);
      ++out_.leaves;
      return;
    }
    reserve(top + split.total);
    scatter(scratch_.data() + begin, n, octants_.data(), parts_, split, scratch_.data() + top);

    const uint32_t first = static_cast<uint32_t>(out_.nodes.size());
    out_.nodes[index].first = first;
    out_.nodes[index].count_or_mask = gpu::OCTREE_INTERNAL | split.mask;
    for (int k = 0; k < 8; ++k)
      if (split.count[k] != 0) out_.nodes.push_back(make_node(split.box[k]));
    uint32_t child = first;
    size_t child_begin = top;
    for (int k = 0; k < 8; ++k) {
      if (split.count[k] == 0) continue;
      build_node(child++, child_begin, child_begin + split.count[k], top + split.total, child_node(node, split, k));
      child_begin += split.count[k];
    }
  }

  const OctreeParams& params_;
  const ClipFn& clip_;
  const ClipOctantsFn& clip_octants_;
  bool clip_straddled_;
  Subtree out_;
  std::vector<Ref> parts_;
  std::vector<Ref> spare_parts_;
  std::vector<uint8_t> spare_octants_;
  std::vector<Ref> scratch_;
  std::vector<uint8_t> octants_;
};

// A node of the top of the tree whose subtree is still to be built.
struct Pending {
  uint32_t index;  // in the top nodes
  std::vector<Ref> refs;
  BuildNode node;
  bool splittable = true;
};

// The first primitives in order of decreasing box size that are big
// (octree.h "Big primitives"), in ascending index order.
std::vector<uint32_t> find_big_primitives(std::span<const Aabb> boxes) {
  const size_t n = boxes.size();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const size_t candidates = std::min<size_t>(n, kMaxBigPrimitives + 1);
  std::partial_sort(order.begin(), order.begin() + candidates, order.end(), [&](uint32_t a, uint32_t b) {
    const float sa = boxes[a].max_extent(), sb = boxes[b].max_extent();
    return sa != sb ? sa > sb : a < b;
  });
  // after[i] = AABB of every primitive after candidate i in the order.
  std::vector<Box> after(candidates);
  Box rest;
  for (size_t i = candidates; i < n; ++i) rest.extend(boxes[order[i]]);
  for (size_t i = candidates; i-- > 0;) {
    after[i] = rest;
    rest.extend(boxes[order[i]]);
  }
  std::vector<uint32_t> big;
  for (size_t i = 0; i < std::min<size_t>(candidates, kMaxBigPrimitives); ++i) {
    if (!(boxes[order[i]].max_extent() > 0.5f * after[i].max_extent())) break;
    big.push_back(order[i]);
  }
  std::sort(big.begin(), big.end());
  return big;
}

}  // namespace

void check_octree_params(const OctreeParams& params) {
  if (params.max_depth < 1 || params.max_depth > kMaxOctreeDepth)
    throw SettingError("octree.max_depth", ": must be in 1.." + std::to_string(kMaxOctreeDepth) + ", got " +
                     std::to_string(params.max_depth));
  if (params.max_refs > kMaxOctreeRefs)
    throw SettingError("octree.max_refs", ": must be in 1.." + std::to_string(kMaxOctreeRefs) + " or 0 (auto), got " +
                       std::to_string(params.max_refs));
}

Octree build_octree(std::span<const Aabb> boxes, const OctreeParams& requested, const ClipFn& clip,
                    const ClipOctantsFn& clip_octants, bool clip_straddled) {
  clip_straddled = clip_straddled && clip;
  check_octree_params(requested);
  OctreeParams params = requested;
  if (params.leaf_size == 0) params.leaf_size = kOctreeLeaf;
  if (params.max_refs == 0) params.max_refs = kOctreeRefs;
  const auto start = Clock::now();
  Octree tree;

  const std::vector<uint32_t> big = find_big_primitives(boxes);
  tree.refs = big;
  tree.big_count = static_cast<uint32_t>(big.size());

  Pending root{0, {}, {}};
  root.refs.reserve(boxes.size() - big.size());
  for (uint32_t i = 0, b = 0; i < boxes.size(); ++i) {
    if (b < big.size() && big[b] == i) {
      ++b;
      continue;
    }
    const Box& box = boxes[i];
    root.refs.push_back({box.lo, box.hi, i});
    root.node.box.extend(box);
  }
  if (root.refs.empty()) root.node.box = {glm::vec3(0.0f), glm::vec3(0.0f)};
  root.node.budget = static_cast<double>(params.max_refs) * static_cast<double>(root.refs.size());
  tree.nodes.push_back(make_node(root.node.box));

  // Top of the tree: split the largest pending subtree until every one is small
  // enough to share out. The threshold depends on the input only.
  const size_t share = std::max<size_t>(root.refs.size() / 16, 4096);
  std::vector<Pending> pending;
  pending.push_back(std::move(root));
  std::vector<uint8_t> octants, spare_octants;
  std::vector<Ref> parts, spare_parts;
  for (;;) {
    size_t largest = pending.size();
    for (size_t i = 0; i < pending.size(); ++i)
      if (pending[i].splittable && pending[i].refs.size() > share &&
          (largest == pending.size() || pending[i].refs.size() > pending[largest].refs.size()))
        largest = i;
    if (largest == pending.size()) break;

    Pending& p = pending[largest];
    octants.resize(p.refs.size());
    Split split;
    if (!plan_best_split(p.refs.data(), p.refs.size(), p.node, params, clip, clip_octants, clip_straddled,
                         octants.data(), parts, split, spare_octants, spare_parts)) {
      p.splittable = false;
      continue;
    }
    std::vector<Ref> children(split.total);
    scatter(p.refs.data(), p.refs.size(), octants.data(), parts, split, children.data());
    const uint32_t first = static_cast<uint32_t>(tree.nodes.size());
    tree.nodes[p.index].first = first;
    tree.nodes[p.index].count_or_mask = gpu::OCTREE_INTERNAL | split.mask;
    std::vector<Pending> replacement;
    size_t at = 0;
    for (int k = 0; k < 8; ++k) {
      if (split.count[k] == 0) continue;
      const uint32_t index = static_cast<uint32_t>(tree.nodes.size());
      tree.nodes.push_back(make_node(split.box[k]));
      replacement.push_back({index, {children.begin() + at, children.begin() + at + split.count[k]},
                             child_node(p.node, split, k)});
      at += split.count[k];
    }
    pending.erase(pending.begin() + largest);
    pending.insert(pending.begin() + largest, std::make_move_iterator(replacement.begin()),
                   std::make_move_iterator(replacement.end()));
  }

  // Build the pending subtrees, largest first, on every hardware thread.
  std::vector<size_t> schedule(pending.size());
  std::iota(schedule.begin(), schedule.end(), 0);
  std::stable_sort(schedule.begin(), schedule.end(),
                   [&](size_t a, size_t b) { return pending[a].refs.size() > pending[b].refs.size(); });
  std::vector<Subtree> subtrees(pending.size());
  parallel_items(
      schedule.size(), [&] { return SubtreeBuilder(params, clip, clip_octants, clip_straddled); },
      [&](SubtreeBuilder& builder, size_t i) {
        const Pending& p = pending[schedule[i]];
        subtrees[schedule[i]] = builder.build(p.refs, p.node);
      });

  // Append each subtree: its root replaces the pending node, the rest follows.
  for (size_t i = 0; i < pending.size(); ++i) {
    const Subtree& s = subtrees[i];
    const uint64_t node_base = tree.nodes.size() - 1;  // subtree node j >= 1 lands at node_base + j
    const uint64_t ref_base = tree.refs.size();
    if (node_base + s.nodes.size() > std::numeric_limits<uint32_t>::max() ||
        ref_base + s.refs.size() >= gpu::OCTREE_INTERNAL)
      throw SettingError("octree.leaf_size", ": the octree would need more than 2^31 references or 2^32 nodes; "
                                             "raise the leaf size");
    const auto fix = [&](gpu::GpuOctreeNode n) {
      n.first += static_cast<uint32_t>((n.count_or_mask & gpu::OCTREE_INTERNAL) ? node_base : ref_base);
      return n;
    };
    tree.nodes[pending[i].index] = fix(s.nodes[0]);
    for (size_t j = 1; j < s.nodes.size(); ++j) tree.nodes.push_back(fix(s.nodes[j]));
    tree.refs.insert(tree.refs.end(), s.refs.begin(), s.refs.end());
    tree.stats.leaves += s.leaves;
    tree.stats.max_depth_reached = std::max(tree.stats.max_depth_reached, s.max_depth);
  }

  finish_tree_stats(tree, boxes.size(), ms_since(start));
  tree.stats.leaf_size = params.leaf_size;
  tree.stats.max_refs = params.max_refs;
  tree.stats.copy_leaf = params.copy_leaf;
  return tree;
}

void finish_tree_stats(Octree& tree, size_t primitives, double build_ms) {
  OctreeStats& st = tree.stats;
  st.nodes = static_cast<uint32_t>(tree.nodes.size());
  st.refs = tree.refs.size();
  st.big_primitives = tree.big_count;
  st.bytes = tree.nodes.size() * sizeof(gpu::GpuOctreeNode) + tree.refs.size() * sizeof(uint32_t);
  if (primitives > 0) {
    st.refs_per_primitive = static_cast<double>(st.refs) / static_cast<double>(primitives);
    st.bytes_per_primitive = static_cast<double>(st.bytes) / static_cast<double>(primitives);
  }
  st.build_ms = build_ms;
}

}  // namespace octrace
