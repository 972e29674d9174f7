// BVH build: encoding and rules in bvh.h.
#include "accel/bvh.h"

#include <algorithm>
#include <limits>
#include <thread>
#include <vector>

#include "core/clock.h"
#include "core/errors.h"
#include "core/parallel.h"

namespace octrace {
namespace {

// Half the surface area, in double (as the octree's build).
double half_area(const Aabb& b) {
  if (b.empty()) return 0.0;
  const glm::dvec3 e = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct Item {
  Aabb box;
  glm::vec3 centroid;
  uint32_t prim;
};

// The bin of coordinate c on an axis whose kBvhBins bins span
// [lo, lo + kBvhBins / scale]: for centroids, the same float operations at
// binning and at partitioning, so both put a primitive on the same side; for
// the spatial bins, bin_range's first guess.
uint32_t bin_of(float c, float lo, float scale) {
  const float k = (c - lo) * scale;
  return k <= 0.0f ? 0u : std::min(kBvhBins - 1, static_cast<uint32_t>(k));
}

// The best split of one kind found for a node: its SAH cost (A_left N_left +
// A_right N_right, not yet divided by the node's area), axis (-1: none) and
// plane (left = bins [0, plane]), and the two sides' boxes.
struct Candidate {
  double cost = std::numeric_limits<double>::infinity();
  int axis = -1;
  uint32_t plane = 0;
  Aabb left, right;
};

class Builder {
 public:
  // `clip` (may be empty): the primitives' shapes, for spatial splits.
  // Nodes above `parallel_depth` build their subtrees on two threads.
  Builder(Octree& tree, const ClipFn& clip, double node_cost, uint32_t parallel_depth)
      : tree_(tree), clip_(clip), node_cost_(node_cost), parallel_depth_(parallel_depth) {}

  // Node `index` over `items`, at `depth`; its subtree may add `extra`
  // references by spatial splits.
  void build(uint32_t index, std::vector<Item> items, uint32_t depth, double extra) {
    const size_t n = items.size();
    Aabb box, centroids;
    for (const Item& it : items) {
      box.extend(it.box);
      centroids.extend({it.centroid, it.centroid});
    }
    tree_.nodes[index].lo = box.lo;
    tree_.nodes[index].hi = box.hi;
    tree_.stats.max_depth_reached = std::max(tree_.stats.max_depth_reached, depth);
    if (depth == 0) root_area_ = half_area(box);

    std::vector<Item> left, right;
    if (n > kBvhMinLeaf && depth < kMaxBvhDepth) split(items, box, centroids, extra, left, right);
    if (left.empty()) {  // a leaf
      tree_.nodes[index].first = static_cast<uint32_t>(tree_.refs.size());
      tree_.nodes[index].count_or_mask = static_cast<uint32_t>(n);
      for (const Item& it : items) tree_.refs.push_back(it.prim);
      ++tree_.stats.leaves;
      return;
    }
    // What the split added comes out of the budget; the rest is shared in
    // proportion to the children's references (so that no part of the tree
    // spends it all, whatever the order the subtrees are built in).
    const double rest = extra - static_cast<double>(left.size() + right.size() - n);
    const double to_left = rest * static_cast<double>(left.size()) / static_cast<double>(left.size() + right.size());
    items = {};
    const uint32_t first = static_cast<uint32_t>(tree_.nodes.size());
    tree_.nodes[index].first = first;
    tree_.nodes[index].count_or_mask = gpu::OCTREE_INTERNAL | 0x3u;
    tree_.nodes.push_back({});
    tree_.nodes.push_back({});
    if (depth < parallel_depth_ && n >= kBvhParallelItems) {
      // The two subtrees on two threads, each into arrays of its own, then
      // appended left first: the nodes and references a build on one thread
      // puts there, in the same order.
      Octree l, r;
      {
        std::jthread helper([&] { l = subtree(std::move(left), depth + 1, to_left); });
        r = subtree(std::move(right), depth + 1, rest - to_left);
      }
      tree_.nodes.reserve(tree_.nodes.size() + l.nodes.size() + r.nodes.size() - 2);
      tree_.refs.reserve(tree_.refs.size() + l.refs.size() + r.refs.size());
      splice(first, l);
      splice(first + 1, r);
      return;
    }
    build(first, std::move(left), depth + 1, to_left);
    build(first + 1, std::move(right), depth + 1, rest - to_left);
  }

 private:
  // The subtree over `items` (build), in arrays of its own whose node 0 is its root.
  Octree subtree(std::vector<Item> items, uint32_t depth, double extra) const {
    Octree t;
    t.nodes.push_back({});
    Builder b(t, clip_, node_cost_, parallel_depth_);
    b.root_area_ = root_area_;
    b.build(0, std::move(items), depth, extra);
    return t;
  }
  // Puts subtree `t`'s root at node `index` and appends the rest of it.
  void splice(uint32_t index, const Octree& t) {
    const uint64_t node_base = tree_.nodes.size() - 1;  // subtree node j >= 1 lands at node_base + j
    const uint64_t ref_base = tree_.refs.size();
    const auto fix = [&](gpu::GpuOctreeNode n) {
      n.first += static_cast<uint32_t>((n.count_or_mask & gpu::OCTREE_INTERNAL) ? node_base : ref_base);
      return n;
    };
    tree_.nodes[index] = fix(t.nodes[0]);
    for (size_t j = 1; j < t.nodes.size(); ++j) tree_.nodes.push_back(fix(t.nodes[j]));
    tree_.refs.insert(tree_.refs.end(), t.refs.begin(), t.refs.end());
    tree_.stats.leaves += t.stats.leaves;
    tree_.stats.max_depth_reached = std::max(tree_.stats.max_depth_reached, t.stats.max_depth_reached);
  }

  // Splits `items` into `left` and `right`, or leaves both empty for a leaf
  // (bvh.h "How it is built").
  void split(std::vector<Item>& items, const Aabb& box, const Aabb& centroids, double extra,
             std::vector<Item>& left, std::vector<Item>& right) {
    const size_t n = items.size();
    const double area = half_area(box);
    float scale[3] = {};
    const Candidate object = object_split(items, centroids, scale);
    if (object.axis < 0) {
      // No plane separates the centroids (they coincide): split at the
      // median primitive id, unless few enough for a leaf.
      if (n <= kBvhMaxLeaf) return;
      std::nth_element(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(n / 2), items.end(),
                       [](const Item& x, const Item& y) { return x.prim < y.prim; });
      left.assign(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(n / 2));
      right.assign(items.begin() + static_cast<std::ptrdiff_t>(n / 2), items.end());
      return;
    }
    // A spatial split is looked for only where the object split's children
    // overlap by more than kBvhSpatialOverlap of the root's area (Stich et
    // al. 2009's alpha: elsewhere it would rarely win and costs a pass over
    // the bins each primitive spans), and while the references stay within
    // the budget.
    Candidate spatial;
    if (clip_ && extra >= 1.0) {
      Aabb overlap{glm::max(object.left.lo, object.right.lo), glm::min(object.left.hi, object.right.hi)};
      const bool overlaps =
          overlap.lo.x <= overlap.hi.x && overlap.lo.y <= overlap.hi.y && overlap.lo.z <= overlap.hi.z;
      if (overlaps && half_area(overlap) > kBvhSpatialOverlap * root_area_) spatial = spatial_split(items, box);
    }
    const double best = std::min(object.cost, spatial.cost);
    const double split_cost = node_cost_ + (area > 0.0 ? best / area : 0.0);
    if (split_cost >= static_cast<double>(n) && n <= kBvhMaxLeaf) return;
    if (spatial.cost < object.cost && partition_spatial(items, box, spatial, extra, left, right)) return;
    left.clear();
    right.clear();
    const int a = object.axis;
    const float lo = centroids.lo[a], s = scale[a];
    const auto goes_left = [&](const Item& it) { return bin_of(it.centroid[a], lo, s) <= object.plane; };
    const size_t to_left = static_cast<size_t>(std::count_if(items.begin(), items.end(), goes_left));
    left.reserve(to_left);  // exactly: the sides' vectors are most of the build's memory
    right.reserve(n - to_left);
    for (const Item& it : items) (goes_left(it) ? left : right).push_back(it);
  }

  // The sweep over the planes between bins on axis a, for either kind of
  // split: the plane after bin p puts bins [0, p] on the left, counting
  // their `to_left`, and the rest on the right, counting their `to_right`;
  // a plane with an empty side is skipped. Keeps the cheapest in `best`
  // (ties: the earlier axis, then the lower plane).
  static void sweep(const Aabb (&bins)[kBvhBins], const uint32_t (&to_left)[kBvhBins],
                    const uint32_t (&to_right)[kBvhBins], int a, Candidate& best) {
    Aabb right_box[kBvhBins];  // bins (p, kBvhBins) for the plane after p
    uint32_t right_n[kBvhBins] = {};
    Aabb right;
    uint32_t rn = 0;
    for (uint32_t p = kBvhBins - 1; p > 0; --p) {
      right.extend(bins[p]);
      rn += to_right[p];
      right_box[p - 1] = right;
      right_n[p - 1] = rn;
    }
    Aabb left;
    uint32_t left_n = 0;
    for (uint32_t p = 0; p + 1 < kBvhBins; ++p) {
      left.extend(bins[p]);
      left_n += to_left[p];
      if (left_n == 0 || right_n[p] == 0) continue;
      const double cost = half_area(left) * left_n + half_area(right_box[p]) * right_n[p];
      if (cost < best.cost) best = {cost, a, p, left, right_box[p]};
    }
  }

  // The binned SAH over the centroids (Wald 2007); scale[a] the bins per
  // unit of axis a, for the partition.
  static Candidate object_split(const std::vector<Item>& items, const Aabb& centroids, float scale[3]) {
    Candidate best;
    for (int a = 0; a < 3; ++a) {
      const float extent = centroids.hi[a] - centroids.lo[a];
      if (!(extent > 0.0f)) continue;
      scale[a] = static_cast<float>(kBvhBins) / extent;
      uint32_t count[kBvhBins] = {};
      Aabb bins[kBvhBins];
      for (const Item& it : items) {
        const uint32_t k = bin_of(it.centroid[a], centroids.lo[a], scale[a]);
        ++count[k];
        bins[k].extend(it.box);
      }
      sweep(bins, count, count, a, best);
    }
    return best;
  }

  // Where the spatial bins' planes lie on axis a of `box`: bin k is
  // [plane(k), plane(k + 1)]; the first and last planes are the box's faces.
  static float plane(const Aabb& box, int a, uint32_t k) {
    if (k == 0) return box.lo[a];
    if (k == kBvhBins) return box.hi[a];
    return box.lo[a] + (box.hi[a] - box.lo[a]) * (static_cast<float>(k) / kBvhBins);
  }
  // The bins [first, last] that [lo, hi] reaches on axis a of `box`.
  // first: the last bin whose lower plane is <= lo; last: the first bin from
  // there whose upper plane is >= hi (the last bin if none). Guessed from the
  // bins' width and settled against plane() itself, whose values grow with k.
  static void bin_range(const Aabb& box, int a, float lo, float hi, uint32_t& first, uint32_t& last) {
    const float scale = static_cast<float>(kBvhBins) / (box.hi[a] - box.lo[a]);
    first = bin_of(lo, box.lo[a], scale);
    while (first > 0 && lo < plane(box, a, first)) --first;
    while (first + 1 < kBvhBins && lo >= plane(box, a, first + 1)) ++first;
    last = std::max(first, bin_of(hi, box.lo[a], scale));
    while (last > first && hi <= plane(box, a, last)) --last;
    while (last + 1 < kBvhBins && hi > plane(box, a, last + 1)) ++last;
  }
  // `box` cut to [lo, hi] on axis a (empty there where they do not meet).
  static Aabb slab(const Aabb& box, int a, float lo, float hi) {
    Aabb cut = box;
    cut.lo[a] = std::max(cut.lo[a], lo);
    cut.hi[a] = std::min(cut.hi[a], hi);
    return cut;
  }
  // Item `it` clipped to [lo, hi] on axis a (its part there), if it reaches it.
  bool clipped(const Item& it, int a, float lo, float hi, Item& part) const {
    const Aabb cell = slab(it.box, a, lo, hi);
    if (cell.lo[a] > cell.hi[a]) return false;
    Aabb b;
    if (!clip_(it.prim, cell, b)) return false;
    part = {b, 0.5f * (b.lo + b.hi), it.prim};
    return true;
  }

  // The spatial split (Stich, Friedrich and Dietrich 2009, "Spatial splits
  // in bounding volume hierarchies"): kBvhBins equal bins along each axis of
  // the node's box; a primitive is counted in the bin where it enters and in
  // the one where it leaves, and grows every bin it spans by its box clamped
  // to that bin (not by its clipped part, as the paper does: that clip per
  // bin took the engine's build from 0.13 s to 2.1 s on the 2-core machine,
  // and the trees walked the same to two decimals, optimisation log 75);
  // the sweep's cost of a plane counts those entering at or left of it on
  // the left, those leaving right of it on the right. Only the split made
  // clips (partition_spatial).
  Candidate spatial_split(const std::vector<Item>& items, const Aabb& box) const {
    Candidate best;
    for (int a = 0; a < 3; ++a) {
      if (!(box.hi[a] > box.lo[a])) continue;
      uint32_t enter[kBvhBins] = {}, leave[kBvhBins] = {};
      Aabb bins[kBvhBins];
      for (const Item& it : items) {
        uint32_t first, last;
        bin_range(box, a, it.box.lo[a], it.box.hi[a], first, last);
        ++enter[first];
        ++leave[last];
        if (first == last) {
          bins[first].extend(it.box);
          continue;
        }
        for (uint32_t k = first; k <= last; ++k)
          bins[k].extend(slab(it.box, a, plane(box, a, k), plane(box, a, k + 1)));
      }
      sweep(bins, enter, leave, a, best);
    }
    return best;
  }

  // Splits at the spatial candidate's plane: a primitive on one side goes
  // there whole; one that straddles it is clipped to each side, and each
  // part goes to its side. False (nothing split) where a side would get
  // every primitive, or where the references would exceed the budget.
  bool partition_spatial(const std::vector<Item>& items, const Aabb& box, const Candidate& c, double extra,
                         std::vector<Item>& left, std::vector<Item>& right) const {
    const int a = c.axis;
    const float x = plane(box, a, c.plane + 1);
    for (const Item& it : items) {
      uint32_t first, last;
      bin_range(box, a, it.box.lo[a], it.box.hi[a], first, last);
      if (last <= c.plane) {
        left.push_back(it);
      } else if (first > c.plane) {
        right.push_back(it);
      } else {
        Item l, r;
        const bool in_left = clipped(it, a, it.box.lo[a], x, l), in_right = clipped(it, a, x, it.box.hi[a], r);
        if (in_left) left.push_back(l);
        if (in_right) right.push_back(r);
        if (!in_left && !in_right) left.push_back(it);  // rounding: keep it whole
      }
    }
    const size_t n = items.size();
    if (left.size() == n || right.size() == n || static_cast<double>(left.size() + right.size() - n) > extra) {
      left.clear();
      right.clear();
      return false;
    }
    return true;
  }

  Octree& tree_;
  const ClipFn& clip_;
  double node_cost_;
  uint32_t parallel_depth_;
  double root_area_ = 0.0;  // the root's half area (Stich et al.'s alpha is relative to it)
};

// The binary tree collapsed into a kBvhWidth-wide one (bvh.h "How it is
// built"): node `wide` of `out` gets binary node `b`'s box and, if b is
// internal, up to kBvhWidth children, consecutive, in the binary tree's
// left-to-right order. refs are the binary tree's, unchanged.
class Collapser {
 public:
  Collapser(const Octree& binary, uint32_t width, Octree& out) : bin_(binary), width_(width), out_(out) {}

  void collapse(uint32_t b, uint32_t wide, uint32_t depth) {
    const gpu::GpuOctreeNode& n = bin_.nodes[b];
    out_.nodes[wide] = n;
    out_.stats.max_depth_reached = std::max(out_.stats.max_depth_reached, depth);
    if (n.count_or_mask < gpu::OCTREE_INTERNAL) return;
    // The children so far and how many binary levels below b each is.
    uint32_t children[kBvhWidth] = {n.first, n.first + 1};
    uint32_t levels[kBvhWidth] = {1, 1};
    uint32_t count = 2;
    while (count < width_) {
      // The internal child of the largest box opens (ties: the one fewer
      // levels down, then the first, so equal boxes open evenly).
      int open = -1;
      double best = -1.0;
      for (uint32_t c = 0; c < count; ++c) {
        const gpu::GpuOctreeNode& ch = bin_.nodes[children[c]];
        if (ch.count_or_mask < gpu::OCTREE_INTERNAL) continue;
        const double a = half_area({ch.lo, ch.hi});
        if (a > best || (a == best && levels[c] < levels[open])) {
          best = a;
          open = static_cast<int>(c);
        }
      }
      if (open < 0) break;
      const uint32_t grand = bin_.nodes[children[open]].first, level = levels[open] + 1;
      for (uint32_t c = count; c > static_cast<uint32_t>(open) + 1; --c) {
        children[c] = children[c - 1];
        levels[c] = levels[c - 1];
      }
      children[open] = grand;
      children[open + 1] = grand + 1;
      levels[open] = levels[open + 1] = level;
      ++count;
    }
    const uint32_t first = static_cast<uint32_t>(out_.nodes.size());
    out_.nodes[wide].first = first;
    out_.nodes[wide].count_or_mask = gpu::OCTREE_INTERNAL | ((1u << count) - 1u);
    out_.nodes.resize(out_.nodes.size() + count);
    for (uint32_t c = 0; c < count; ++c) collapse(children[c], first + c, depth + 1);
  }

 private:
  const Octree& bin_;
  uint32_t width_;
  Octree& out_;
};

}  // namespace

uint32_t default_bvh_parallel_depth() { return bvh_parallel_depth(host_threads()); }

Octree build_bvh(std::span<const Aabb> boxes, uint32_t width, const ClipFn& clip, double spatial_refs,
                 double node_cost, uint32_t parallel_depth) {
  const auto start = Clock::now();
  Octree tree;
  if (width < 2 || width > kBvhWidth)
    throw SettingError("accel", ": a BVH node has 2 to " + std::to_string(kBvhWidth) + " children, not " +
                                    std::to_string(width));
  if (boxes.size() >= gpu::OCTREE_INTERNAL)
    throw SettingError("accel", ": a BVH holds at most 2^31 - 1 primitives, got " + std::to_string(boxes.size()));
  std::vector<Item> items;
  items.reserve(boxes.size());
  for (uint32_t i = 0; i < boxes.size(); ++i)
    items.push_back({boxes[i], 0.5f * (boxes[i].lo + boxes[i].hi), i});
  tree.nodes.push_back({});
  if (boxes.empty()) {
    tree.nodes[0] = {glm::vec3(0.0f), 0, glm::vec3(0.0f), 0};
    tree.stats.leaves = 1;
  } else {
    Octree binary;
    binary.nodes.push_back({});
    Builder(binary, clip, node_cost, parallel_depth).build(0, std::move(items), 0, static_cast<double>(boxes.size()) * (spatial_refs - 1.0));
    tree.refs = std::move(binary.refs);
    tree.stats.leaves = binary.stats.leaves;
    Collapser(binary, width, tree).collapse(0, 0, 0);
  }

  finish_tree_stats(tree, boxes.size(), ms_since(start));
  return tree;
}

}  // namespace octrace
