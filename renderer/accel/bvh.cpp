// BVH build: encoding and rules in bvh.h.
#include "accel/bvh.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "core/clock.h"
#include "core/errors.h"

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

// The bin of centroid coordinate c on an axis whose centroids span
// [lo, lo + kBvhBins / scale]: the same float operations at binning and at
// partitioning, so both put a primitive on the same side.
uint32_t bin_of(float c, float lo, float scale) {
  const float k = (c - lo) * scale;
  return k <= 0.0f ? 0u : std::min(kBvhBins - 1, static_cast<uint32_t>(k));
}

class Builder {
 public:
  Builder(std::vector<Item> items, Octree& tree) : items_(std::move(items)), tree_(tree) {}

  // Node `index` over items_[begin, end).
  void build(uint32_t index, size_t begin, size_t end, uint32_t depth) {
    const size_t n = end - begin;
    Aabb box, centroids;
    for (size_t i = begin; i < end; ++i) {
      box.extend(items_[i].box);
      centroids.extend({items_[i].centroid, items_[i].centroid});
    }
    tree_.nodes[index].lo = box.lo;
    tree_.nodes[index].hi = box.hi;
    tree_.stats.max_depth_reached = std::max(tree_.stats.max_depth_reached, depth);

    size_t mid = begin;
    if (n > kBvhMinLeaf && depth < kMaxBvhDepth) mid = split(begin, end, box, centroids);
    if (mid == begin) {  // a leaf
      tree_.nodes[index].first = static_cast<uint32_t>(tree_.refs.size());
      tree_.nodes[index].count_or_mask = static_cast<uint32_t>(n);
      for (size_t i = begin; i < end; ++i) tree_.refs.push_back(items_[i].prim);
      ++tree_.stats.leaves;
      return;
    }
    const uint32_t first = static_cast<uint32_t>(tree_.nodes.size());
    tree_.nodes[index].first = first;
    tree_.nodes[index].count_or_mask = gpu::OCTREE_INTERNAL | 0x3u;
    tree_.nodes.push_back({});
    tree_.nodes.push_back({});
    build(first, begin, mid, depth + 1);
    build(first + 1, mid, end, depth + 1);
  }

 private:
  // Where items_[begin, end) splits (items_ reordered so that the left child
  // is [begin, result)), or begin for a leaf (bvh.h "How it is built").
  size_t split(size_t begin, size_t end, const Aabb& box, const Aabb& centroids) {
    const size_t n = end - begin;
    const double area = half_area(box);
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1;
    uint32_t best_plane = 0;  // left = bins [0, best_plane]
    float scale[3] = {};
    for (int a = 0; a < 3; ++a) {
      const float extent = centroids.hi[a] - centroids.lo[a];
      if (!(extent > 0.0f)) continue;
      scale[a] = static_cast<float>(kBvhBins) / extent;
      uint32_t count[kBvhBins] = {};
      Aabb bins[kBvhBins];
      for (size_t i = begin; i < end; ++i) {
        const uint32_t k = bin_of(items_[i].centroid[a], centroids.lo[a], scale[a]);
        ++count[k];
        bins[k].extend(items_[i].box);
      }
      // Sweep from the right: right_cost[p] = A * N of bins (p, kBvhBins).
      double right_cost[kBvhBins] = {};
      Aabb right;
      uint32_t right_n = 0;
      for (uint32_t p = kBvhBins - 1; p > 0; --p) {
        right.extend(bins[p]);
        right_n += count[p];
        right_cost[p - 1] = half_area(right) * right_n;
      }
      Aabb left;
      uint32_t left_n = 0;
      for (uint32_t p = 0; p + 1 < kBvhBins; ++p) {
        left.extend(bins[p]);
        left_n += count[p];
        if (left_n == 0 || left_n == n) continue;
        const double cost = half_area(left) * left_n + right_cost[p];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = a;
          best_plane = p;
        }
      }
    }
    auto first = items_.begin() + static_cast<std::ptrdiff_t>(begin);
    auto last = items_.begin() + static_cast<std::ptrdiff_t>(end);
    if (best_axis < 0) {
      // No plane separates the centroids (they coincide): split at the
      // median primitive id, unless few enough for a leaf.
      if (n <= kBvhMaxLeaf) return begin;
      auto median = first + static_cast<std::ptrdiff_t>(n / 2);
      std::nth_element(first, median, last, [](const Item& x, const Item& y) { return x.prim < y.prim; });
      return begin + n / 2;
    }
    const double split_cost = kBvhNodeCost + (area > 0.0 ? best_cost / area : 0.0);
    if (split_cost >= static_cast<double>(n) && n <= kBvhMaxLeaf) return begin;
    const int a = best_axis;
    const float lo = centroids.lo[a], s = scale[a];
    const auto mid = std::stable_partition(
        first, last, [&](const Item& it) { return bin_of(it.centroid[a], lo, s) <= best_plane; });
    return begin + static_cast<size_t>(mid - first);
  }

  std::vector<Item> items_;
  Octree& tree_;
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

Octree build_bvh(std::span<const Aabb> boxes, uint32_t width) {
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
    binary.nodes.reserve(2 * boxes.size() - 1);
    binary.refs.reserve(boxes.size());
    binary.nodes.push_back({});
    Builder(std::move(items), binary).build(0, 0, boxes.size(), 0);
    tree.refs = std::move(binary.refs);
    tree.stats.leaves = binary.stats.leaves;
    Collapser(binary, width, tree).collapse(0, 0, 0);
  }

  finish_tree_stats(tree, boxes.size(), ms_since(start));
  return tree;
}

}  // namespace octrace
