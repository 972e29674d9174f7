// The BVH builder's guarantees (renderer/accel/bvh.h), the ones the shader
// walk relies on: without shapes, every primitive is referenced exactly
// once; with them (spatial splits, the meshes' trees), every point of a
// triangle lies in a leaf that references it, within the budget; a node's box
// is the union of its primitives' boxes, so children lie inside parents;
// the SAH leaf rule; depth within the shader's stack; determinism; the
// encoding (two to four consecutive children) and the stats. That the walk finds the
// same closest hit as brute force is accel_test (images on the GPU).
#include "accel/bvh.h"
#include "accel/clip.h"
#include "core/errors.h"
#include "core/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <random>
#include <vector>

namespace octrace {
namespace {

using gpu::GpuOctreeNode;
using gpu::OCTREE_INTERNAL;

bool inside(const GpuOctreeNode& inner, const GpuOctreeNode& outer) {
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a]) return false;
  return true;
}

// Walks the tree from node i; checks boxes and counts references per
// primitive. Returns the exact union of the primitives' boxes below i.
Aabb check_node(const Octree& t, std::span<const Aabb> boxes, uint32_t width, uint32_t i, uint32_t depth,
                std::vector<int>& seen, uint32_t& max_depth) {
  const GpuOctreeNode& n = t.nodes.at(i);
  max_depth = std::max(max_depth, depth);
  Aabb u;
  if (n.count_or_mask < OCTREE_INTERNAL) {
    EXPECT_GE(n.count_or_mask, 1u) << "node " << i;
    EXPECT_LE(n.count_or_mask, kBvhMaxLeaf) << "node " << i;
    for (uint32_t k = n.first; k < n.first + n.count_or_mask; ++k) {
      const uint32_t p = t.refs.at(k);
      ++seen.at(p);
      u.extend(boxes[p]);
    }
  } else {
    const uint32_t mask = n.count_or_mask & ~OCTREE_INTERNAL;
    const uint32_t count = static_cast<uint32_t>(std::popcount(mask));
    EXPECT_EQ(mask, (1u << count) - 1u) << "node " << i << ": children are not 0 .. n-1";
    EXPECT_GE(count, 2u) << "node " << i;
    EXPECT_LE(count, width) << "node " << i;
    EXPECT_GT(n.first, i) << "node " << i;
    for (uint32_t c = n.first; c < n.first + count; ++c) {
      EXPECT_TRUE(inside(t.nodes.at(c), n)) << "child " << c << " of node " << i;
      // The collapse stops short of the width only when every child is a leaf.
      if (count < width) {
        EXPECT_LT(t.nodes.at(c).count_or_mask, OCTREE_INTERNAL) << "child " << c;
      }
      u.extend(check_node(t, boxes, width, c, depth + 1, seen, max_depth));
    }
  }
  EXPECT_EQ(glm::vec3(n.lo), u.lo) << "node " << i << ": not the union of its primitives' boxes";
  EXPECT_EQ(glm::vec3(n.hi), u.hi) << "node " << i;
  return u;
}

void check_tree(const Octree& t, std::span<const Aabb> boxes, uint32_t width = kBvhWidth) {
  std::vector<int> seen(boxes.size(), 0);
  uint32_t max_depth = 0;
  check_node(t, boxes, width, 0, 0, seen, max_depth);
  for (size_t p = 0; p < boxes.size(); ++p) EXPECT_EQ(seen[p], 1) << "primitive " << p;
  EXPECT_EQ(t.refs.size(), boxes.size());
  EXPECT_EQ(t.big_count, 0u);
  EXPECT_LE(max_depth, kMaxBvhDepth);
  EXPECT_EQ(t.stats.max_depth_reached, max_depth);
  EXPECT_EQ(t.stats.nodes, t.nodes.size());
  EXPECT_LE(t.nodes.size(), 2 * size_t(t.stats.leaves) - 1);  // at most a binary tree's
  EXPECT_EQ(t.stats.bytes, t.nodes.size() * 32 + t.refs.size() * 4);
}

std::vector<Aabb> random_boxes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), size(0.01f, 1.0f);
  std::vector<Aabb> boxes;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 c(pos(rng), pos(rng) * 0.1f, pos(rng));
    const glm::vec3 h(size(rng), size(rng), size(rng));
    boxes.push_back({c - h, c + h});
  }
  // A ground-sized box among them, as the rtiow ground sphere.
  boxes.push_back({glm::vec3(-1000, -2000, -1000), glm::vec3(1000, 0, 1000)});
  return boxes;
}

TEST(Bvh, RandomBoxesEveryPrimitiveOnceBoxesNest) {
  const std::vector<Aabb> boxes = random_boxes(5000, 1);
  const Octree t = build_bvh(boxes);
  check_tree(t, boxes);
  EXPECT_DOUBLE_EQ(t.stats.refs_per_primitive, 1.0);
  EXPECT_GT(t.stats.leaves, 5000u / kBvhMaxLeaf);
}

// The collapse: over 5000 boxes (3379 leaves) a binary tree has leaves - 1
// internal nodes, all two-wide; the wide tree has fewer than half as many
// (a full four-wide tree would have a third), over two fifths of them four
// wide (the rest: nodes above leaves only; 1582 and 749 when written).
TEST(Bvh, InternalNodesHoldFourChildren) {
  const std::vector<Aabb> boxes = random_boxes(5000, 3);
  const Octree t = build_bvh(boxes);
  check_tree(t, boxes);
  size_t internal = 0, four = 0;
  for (const GpuOctreeNode& n : t.nodes) {
    if (n.count_or_mask < OCTREE_INTERNAL) continue;
    ++internal;
    four += n.count_or_mask == (OCTREE_INTERNAL | 0xfu);
  }
  EXPECT_EQ(t.nodes.size(), internal + t.stats.leaves);
  EXPECT_LT(internal, size_t(t.stats.leaves) / 2);
  EXPECT_GT(four, internal * 2 / 5);  // the others: nodes whose children are all leaves
  EXPECT_LE(t.stats.max_depth_reached, 12u);
}

// Width 2 is the binary tree itself (a top level over spheres): every
// internal node two-wide, leaves - 1 of them; the same leaves and references
// as the four-wide tree's, which collapses it.
TEST(Bvh, WidthTwoIsTheBinaryTree) {
  const std::vector<Aabb> boxes = random_boxes(2000, 5);
  const Octree binary = build_bvh(boxes, 2), wide = build_bvh(boxes, 4);
  check_tree(binary, boxes, 2);
  EXPECT_EQ(binary.nodes.size(), 2 * size_t(binary.stats.leaves) - 1);
  for (const GpuOctreeNode& n : binary.nodes) {
    if (n.count_or_mask >= OCTREE_INTERNAL) {
      EXPECT_EQ(n.count_or_mask, OCTREE_INTERNAL | 0x3u);
    }
  }
  EXPECT_EQ(binary.refs, wide.refs);
  EXPECT_EQ(binary.stats.leaves, wide.stats.leaves);
  EXPECT_LT(wide.nodes.size(), binary.nodes.size());
  EXPECT_LT(wide.stats.max_depth_reached, binary.stats.max_depth_reached);
  EXPECT_THROW(build_bvh(boxes, 1), SettingError);
  EXPECT_THROW(build_bvh(boxes, kBvhWidth + 1), SettingError);
}

// Coincident boxes: no plane separates the centroids; the median split keeps
// leaves within kBvhMaxLeaf, and the depth is that of a balanced tree.
TEST(Bvh, CoincidentBoxesSplitAtTheMedian) {
  const std::vector<Aabb> boxes(1000, Aabb{glm::vec3(-1), glm::vec3(1)});
  const Octree t = build_bvh(boxes);
  check_tree(t, boxes);
  EXPECT_LE(t.stats.max_depth_reached, 4u);  // a balanced binary tree's ceil(log2(1000 / 8)) + 1 = 8, halved
}

TEST(Bvh, EmptyAndOne) {
  const Octree empty = build_bvh({});
  ASSERT_EQ(empty.nodes.size(), 1u);
  EXPECT_EQ(empty.nodes[0].count_or_mask, 0u);
  EXPECT_EQ(glm::vec3(empty.nodes[0].lo), glm::vec3(0.0f));
  EXPECT_EQ(glm::vec3(empty.nodes[0].hi), glm::vec3(0.0f));
  EXPECT_TRUE(empty.refs.empty());

  const std::vector<Aabb> one{{glm::vec3(1, 2, 3), glm::vec3(4, 5, 6)}};
  const Octree t = build_bvh(one);
  check_tree(t, one);
  ASSERT_EQ(t.nodes.size(), 1u);
  EXPECT_EQ(t.nodes[0].count_or_mask, 1u);
}

// The SAH leaf rule, both ways, on inputs small enough for a leaf
// (N <= kBvhMaxLeaf). Two clusters far apart: a split costs about
// 1 + 2 * (tiny area / huge area) * 2 << 4, so the root splits between them.
// Four nearly coincident unit boxes: any split costs about 1 + 2 + 2 = 5 > 4,
// so the root stays a leaf.
TEST(Bvh, SahDecidesSmallNodes) {
  const std::vector<Aabb> far{{glm::vec3(0), glm::vec3(1)},
                              {glm::vec3(0.5f), glm::vec3(1.5f)},
                              {glm::vec3(100), glm::vec3(101)},
                              {glm::vec3(100.5f), glm::vec3(101.5f)}};
  const Octree split = build_bvh(far);
  check_tree(split, far);
  ASSERT_GE(split.nodes[0].count_or_mask, OCTREE_INTERNAL);
  const GpuOctreeNode& left = split.nodes[split.nodes[0].first];
  EXPECT_LT(left.hi.x, 2.0f);  // the first child holds (part of) the cluster at 0, the last the one at 100
  const uint32_t last = split.nodes[0].first + std::popcount(split.nodes[0].count_or_mask & ~OCTREE_INTERNAL) - 1;
  EXPECT_GT(split.nodes[last].lo.x, 99.0f);

  std::vector<Aabb> close;
  for (int i = 0; i < 4; ++i) close.push_back({glm::vec3(0.001f * i), glm::vec3(1 + 0.001f * i)});
  const Octree leaf = build_bvh(close);
  check_tree(leaf, close);
  ASSERT_EQ(leaf.nodes.size(), 1u);
  EXPECT_EQ(leaf.nodes[0].count_or_mask, 4u);
}

// Byte for byte: the nodes and the references.
void expect_same_tree(const Octree& a, const Octree& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.refs, b.refs);
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(GpuOctreeNode)), 0);
  EXPECT_EQ(a.stats.leaves, b.stats.leaves);
  EXPECT_EQ(a.stats.max_depth_reached, b.stats.max_depth_reached);
}

TEST(Bvh, Deterministic) {
  const std::vector<Aabb> boxes = random_boxes(3000, 7);
  expect_same_tree(build_bvh(boxes), build_bvh(boxes));
}

// Spatial splits (a ClipFn: the meshes' trees). Long thin triangles along
// the diagonal of a box, whose boxes overlap everywhere: the object split
// alone leaves siblings overlapping, so spatial splits must happen (more
// references than triangles), within kBvhSpatialRefs per triangle; every
// point of a triangle (vertices, edge midpoints, random barycentrics) lies
// in a leaf that references it; boxes nest; deterministic, and the same
// tree whether the build's subtrees run on threads or not.
struct Soup {
  std::vector<glm::vec3> v;  // 3 per triangle
  std::vector<Aabb> boxes;
  ClipFn clip;
};

Soup slivers(size_t n, uint32_t seed) {
  Soup s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 a(u(rng) * 10, u(rng) * 10, u(rng) * 10), b(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    const glm::vec3 c = a + 0.02f * glm::vec3(u(rng), u(rng), u(rng)) + 0.01f * (b - a);
    s.v.insert(s.v.end(), {a, b, c});
    Aabb box{glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))};
    s.boxes.push_back(box);
  }
  s.clip = [v = s.v](uint32_t t, const Aabb& cell, Aabb& part) {
    return clip_triangle(v[3 * t], v[3 * t + 1], v[3 * t + 2], cell, part);
  };
  return s;
}

bool in_box(const GpuOctreeNode& n, const glm::vec3& p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < n.lo[a] || p[a] > n.hi[a]) return false;
  return true;
}

// Whether point p of triangle t lies in some leaf below node i that references t.
bool covered(const Octree& tree, uint32_t i, uint32_t t, const glm::vec3& p) {
  const GpuOctreeNode& n = tree.nodes[i];
  if (!in_box(n, p)) return false;
  if (n.count_or_mask < OCTREE_INTERNAL) {
    for (uint32_t k = n.first; k < n.first + n.count_or_mask; ++k)
      if (tree.refs[k] == t) return true;
    return false;
  }
  const uint32_t count = static_cast<uint32_t>(std::popcount(n.count_or_mask & ~OCTREE_INTERNAL));
  for (uint32_t c = n.first; c < n.first + count; ++c)
    if (covered(tree, c, t, p)) return true;
  return false;
}

void check_nesting(const Octree& t, uint32_t i) {
  const GpuOctreeNode& n = t.nodes[i];
  if (n.count_or_mask < OCTREE_INTERNAL) return;
  const uint32_t count = static_cast<uint32_t>(std::popcount(n.count_or_mask & ~OCTREE_INTERNAL));
  for (uint32_t c = n.first; c < n.first + count; ++c) {
    EXPECT_TRUE(inside(t.nodes[c], n)) << "child " << c << " of node " << i;
    check_nesting(t, c);
  }
}

TEST(Bvh, SpatialSplitsCoverEveryTriangleWithinTheBudget) {
  const size_t n = 3000;
  const Soup s = slivers(n, 11);
  for (uint32_t width : {2u, 4u}) {
    SCOPED_TRACE(width);
    const Octree t = build_bvh(s.boxes, width, s.clip);
    EXPECT_GT(t.refs.size(), n);  // spatial splits happened
    EXPECT_LE(static_cast<double>(t.refs.size()), static_cast<double>(n) * kBvhSpatialRefs);
    EXPECT_DOUBLE_EQ(t.stats.refs_per_primitive, static_cast<double>(t.refs.size()) / n);
    EXPECT_EQ(t.stats.bytes, t.nodes.size() * 32 + t.refs.size() * 4);
    EXPECT_LE(t.stats.max_depth_reached, kMaxBvhDepth);
    check_nesting(t, 0);
    for (const GpuOctreeNode& node : t.nodes) {
      if (node.count_or_mask < OCTREE_INTERNAL) {
        EXPECT_GE(node.count_or_mask, 1u);
      }
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    size_t missed = 0;
    for (uint32_t tri = 0; tri < n; ++tri) {
      const glm::vec3 a = s.v[3 * tri], b = s.v[3 * tri + 1], c = s.v[3 * tri + 2];
      std::vector<glm::vec3> points{a, b, c, 0.5f * (a + b), 0.5f * (b + c), 0.5f * (c + a)};
      for (int k = 0; k < 6; ++k) {
        float x = u(rng), y = u(rng);
        if (x + y > 1.0f) x = 1.0f - x, y = 1.0f - y;
        points.push_back(a + x * (b - a) + y * (c - a));
      }
      for (const glm::vec3& p : points) missed += !covered(t, 0, tri, p);
    }
    EXPECT_EQ(missed, 0u);
  }
  // The same input, the same tree.
  const Octree a = build_bvh(s.boxes, 4, s.clip), b = build_bvh(s.boxes, 4, s.clip);
  expect_same_tree(a, b);
}

// The top levels' subtrees build on threads (default_bvh_parallel_depth, for nodes of
// at least kBvhParallelItems references) and are appended in the order one
// thread writes them: the tree, with spatial splits or without, is the one a
// build on the calling thread makes, byte for byte, however deep the threads go.
TEST(Bvh, ThreadsBuildTheOneThreadTree) {
  const Soup s = slivers(12 * kBvhParallelItems, 23);
  const std::vector<Aabb> boxes = random_boxes(12 * kBvhParallelItems, 29);
  for (uint32_t width : {2u, 4u}) {
    SCOPED_TRACE(width);
    const Octree one = build_bvh(s.boxes, width, s.clip, kBvhSpatialRefs, kBvhNodeCost, 0);
    const Octree plain_one = build_bvh(boxes, width, {}, kBvhSpatialRefs, kBvhNodeCost, 0);
    EXPECT_GT(one.refs.size(), s.boxes.size());  // spatial splits happened
    for (uint32_t depth : {kBvhParallelDepth, kBvhParallelDepth + 2, bvh_parallel_depth(16)}) {
      SCOPED_TRACE(depth);
      expect_same_tree(build_bvh(s.boxes, width, s.clip, kBvhSpatialRefs, kBvhNodeCost, depth), one);
      expect_same_tree(build_bvh(boxes, width, {}, kBvhSpatialRefs, kBvhNodeCost, depth), plain_one);
    }
  }
}

// The threads' depth follows the host: one subtree per hardware thread at
// least, never fewer than kBvhParallelDepth's four (log 105: two cores
// unchanged, sixteen at depth 4).
TEST(Bvh, ParallelDepthCoversTheThreads) {
  for (uint32_t threads : {1u, 2u, 3u, 4u}) EXPECT_EQ(bvh_parallel_depth(threads), kBvhParallelDepth) << threads;
  EXPECT_EQ(bvh_parallel_depth(5), 3u);
  EXPECT_EQ(bvh_parallel_depth(8), 3u);
  EXPECT_EQ(bvh_parallel_depth(16), 4u);
  EXPECT_EQ(bvh_parallel_depth(17), 5u);
  EXPECT_EQ(bvh_parallel_depth(0xffffffffu), 31u);
  EXPECT_EQ(default_bvh_parallel_depth(), bvh_parallel_depth(host_threads()));
}

// The SAH's node cost: a dearer node makes fewer, larger leaves (the top
// level's kBvhTopNodeCost against the meshes' kBvhNodeCost), every one
// within kBvhMaxLeaf, over every primitive once.
TEST(Bvh, DearerNodesMakeFewerLeaves) {
  const std::vector<Aabb> boxes = random_boxes(5000, 31);
  const Octree cheap = build_bvh(boxes, 2, {}, kBvhSpatialRefs, kBvhNodeCost);
  const Octree dear = build_bvh(boxes, 2, {}, kBvhSpatialRefs, kBvhTopNodeCost);
  check_tree(cheap, boxes, 2);
  check_tree(dear, boxes, 2);
  EXPECT_LT(dear.stats.leaves, cheap.stats.leaves);
  EXPECT_LT(dear.nodes.size(), cheap.nodes.size());
}

// At most 1 reference per triangle: no spatial splits, the tree of the
// boxes alone (the plain binned SAH), shapes or not.
TEST(Bvh, OneReferencePerTriangleIsThePlainSah) {
  const Soup s = slivers(2000, 17);
  const Octree plain = build_bvh(s.boxes, 4), one = build_bvh(s.boxes, 4, s.clip, 1.0);
  expect_same_tree(one, plain);
  // And a larger budget splits more.
  const Octree more = build_bvh(s.boxes, 4, s.clip, 2.0), fewer = build_bvh(s.boxes, 4, s.clip, 1.2);
  EXPECT_LE(static_cast<double>(fewer.refs.size()), 2000 * 1.2);
  EXPECT_GT(more.refs.size(), fewer.refs.size());
  EXPECT_LE(static_cast<double>(more.refs.size()), 2000 * 2.0);
}

// Without shapes, spatial splits never happen: a tree over boxes is the
// plain binned SAH's (one reference each), large enough to build on threads.
TEST(Bvh, NoShapesNoSpatialSplits) {
  const std::vector<Aabb> boxes = random_boxes(20000, 13);
  const Octree t = build_bvh(boxes);
  check_tree(t, boxes);
}

}  // namespace
}  // namespace octrace
