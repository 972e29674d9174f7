// The octree's guarantees, the ones the GPU traversal relies on: a front-to-back
// traversal with early exit finds exactly the closest hit that brute force finds;
// boxes nest, siblings lie on their own sides of the split planes (so octant
// order XOR the ray's sign mask is front-to-back); the build is deterministic;
// the stats add up; bad parameters are errors that name the flag.
#include "accel/octree.h"
#include "accel/clip.h"
#include "accel/hidden_parts.h"
#include "render/gpu_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/errors.h"
#include "test_util.h"

namespace octrace {
namespace {

using gpu::GpuOctreeNode;
using gpu::OCTREE_INTERNAL;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 dir;  // unit length
};

// Closest hit; ties in t go to the lower sphere index, so that brute force and
// the octree agree on coincident spheres.
struct Hit {
  double t = kInf;
  uint32_t sphere = UINT32_MAX;

  bool operator<(const Hit& o) const { return t != o.t ? t < o.t : sphere < o.sphere; }
  bool operator==(const Hit&) const = default;
};

double hit_sphere(const Sphere& s, const Ray& ray) {
  return test::ray_sphere(ray.origin, ray.dir, glm::dvec3(s.center), s.radius);
}

void test_sphere(const std::vector<Sphere>& spheres, uint32_t i, const Ray& ray, Hit& best) {
  const Hit h{hit_sphere(spheres[i], ray), i};
  if (h.t < kInf && h < best) best = h;
}

Hit brute_force(const std::vector<Sphere>& spheres, const Ray& ray) {
  Hit best;
  for (uint32_t i = 0; i < spheres.size(); ++i) test_sphere(spheres, i, ray, best);
  return best;
}

// Entry and exit t of the ray in a box, or an empty interval. A direction
// component of 0 is handled apart, so no 0 * inf. The box grows by a relative
// 1e-12 so that a hit exactly on a face is not lost to double rounding of t.
bool hit_box(const GpuOctreeNode& n, const Ray& ray, double& t_enter, double& t_exit) {
  t_enter = 0.0;
  t_exit = kInf;
  for (int a = 0; a < 3; ++a) {
    const double pad = 1e-12 * std::max({1.0, std::abs(double(n.lo[a])), std::abs(double(n.hi[a]))});
    const double lo = double(n.lo[a]) - pad;
    const double hi = double(n.hi[a]) + pad;
    if (ray.dir[a] == 0.0) {
      if (ray.origin[a] < lo || ray.origin[a] > hi) return false;
      continue;
    }
    double t0 = (lo - ray.origin[a]) / ray.dir[a];
    double t1 = (hi - ray.origin[a]) / ray.dir[a];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
  }
  return t_enter <= t_exit;
}

// The traversal the GPU does: big spheres first, then the tree front to back
// (children in octant order XOR the ray's sign mask, nearest popped first),
// skipping any node whose entry is beyond the closest hit found so far.
Hit traverse(const Octree& tree, const std::vector<Sphere>& spheres, const Ray& ray) {
  Hit best;
  for (uint32_t i = 0; i < tree.big_count; ++i) test_sphere(spheres, tree.refs[i], ray, best);
  const uint32_t sign = (std::signbit(ray.dir.x) ? 1u : 0u) | (std::signbit(ray.dir.y) ? 2u : 0u) |
                        (std::signbit(ray.dir.z) ? 4u : 0u);
  struct Entry {
    uint32_t node;
    double t_enter;
  };
  std::vector<Entry> stack;
  double t0, t1;
  if (hit_box(tree.nodes[0], ray, t0, t1)) stack.push_back({0, t0});
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    if (e.t_enter > best.t) continue;
    const GpuOctreeNode& n = tree.nodes[e.node];
    if (!(n.count_or_mask & OCTREE_INTERNAL)) {
      for (uint32_t i = 0; i < n.count_or_mask; ++i) test_sphere(spheres, tree.refs[n.first + i], ray, best);
      continue;
    }
    const uint32_t mask = n.count_or_mask & 0xFFu;
    for (uint32_t j = 8; j-- > 0;) {  // pushed far to near, so the nearest pops first
      const uint32_t k = j ^ sign;
      if (!(mask & (1u << k))) continue;
      const uint32_t child = n.first + std::popcount(mask & ((1u << k) - 1u));
      if (hit_box(tree.nodes[child], ray, t0, t1) && t0 <= best.t) stack.push_back({child, t0});
    }
  }
  return best;
}

glm::dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    const double len = glm::length(v);
    if (len > 1e-9) return v / len;
  }
}

// Rays that exercise the tree rather than the big spheres: from random points
// in and around the root box toward random spheres (some along an axis, so the
// direction has components of +0 and -0), and in random directions.
std::vector<Ray> make_rays(const Octree& tree, const std::vector<Sphere>& spheres, size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const GpuOctreeNode& root = tree.nodes[0];
  const glm::dvec3 lo(root.lo), hi(root.hi);
  const glm::dvec3 margin = 0.2 * (hi - lo) + 1.0;
  std::vector<Ray> rays;
  for (size_t i = 0; i < count; ++i) {
    glm::dvec3 origin;
    for (int a = 0; a < 3; ++a) origin[a] = lo[a] - margin[a] + u(rng) * (hi[a] - lo[a] + 2 * margin[a]);
    if (spheres.empty() || i % 4 == 3) {
      rays.push_back({origin, random_unit(rng)});
      continue;
    }
    const Sphere& s = spheres[rng() % spheres.size()];
    const glm::dvec3 target = glm::dvec3(s.center) + 0.9 * double(s.radius) * random_unit(rng);
    if (i % 4 == 2) {  // along an axis, from outside the sphere; the zeros are +0 or -0
      glm::dvec3 dir;
      for (int a = 0; a < 3; ++a) dir[a] = (rng() & 1) ? 0.0 : -0.0;
      const int a = static_cast<int>(rng() % 3);
      dir[a] = (rng() & 1) ? 1.0 : -1.0;
      origin = target - dir * (double(s.radius) * 3.0 + u(rng) * margin[a]);
      rays.push_back({origin, dir});
      continue;
    }
    rays.push_back({origin, glm::normalize(target - origin)});
  }
  return rays;
}

void expect_same_hits(const Octree& tree, const std::vector<Sphere>& spheres, size_t ray_count) {
  size_t hits = 0;
  for (const Ray& ray : make_rays(tree, spheres, ray_count, 7)) {
    const Hit want = brute_force(spheres, ray);
    const Hit got = traverse(tree, spheres, ray);
    ASSERT_EQ(got, want) << "ray from (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z
                         << ") dir (" << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << "): octree sphere "
                         << got.sphere << " t " << got.t << ", brute force sphere " << want.sphere << " t " << want.t;
    hits += want.t < kInf;
  }
  if (!spheres.empty()) {
    EXPECT_GT(hits, ray_count / 4) << "the rays should mostly hit something";
  }
}

bool box_contains(const GpuOctreeNode& n, const glm::vec3& p) {
  return p.x >= n.lo.x && p.y >= n.lo.y && p.z >= n.lo.z && p.x <= n.hi.x && p.y <= n.hi.y && p.z <= n.hi.z;
}

bool leaf_holds(const Octree& tree, uint32_t node, const glm::vec3& p, uint32_t sphere) {
  const GpuOctreeNode& n = tree.nodes[node];
  if (!box_contains(n, p)) return false;
  if (!(n.count_or_mask & OCTREE_INTERNAL)) {
    const auto begin = tree.refs.begin() + n.first;
    return std::binary_search(begin, begin + n.count_or_mask, sphere);
  }
  const uint32_t mask = n.count_or_mask & 0xFFu;
  for (uint32_t c = 0; c < static_cast<uint32_t>(std::popcount(mask)); ++c)
    if (leaf_holds(tree, n.first + c, p, sphere)) return true;
  return false;
}

// Every point of every non-big sphere's AABB lies in a leaf box that references
// the sphere: the property that makes the traversal find every hit.
void expect_spheres_findable(const Octree& tree, const std::vector<Sphere>& spheres) {
  std::vector<bool> big(spheres.size());
  for (uint32_t i = 0; i < tree.big_count; ++i) big[tree.refs[i]] = true;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (uint32_t i = 0; i < spheres.size(); ++i) {
    if (big[i]) continue;
    const Sphere& s = spheres[i];
    std::vector<glm::vec3> points = {s.center};
    for (int c = 0; c < 8; ++c)
      points.push_back(s.center + s.radius * glm::vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1));
    for (int j = 0; j < 4; ++j) points.push_back(s.center + s.radius * glm::vec3(u(rng), u(rng), u(rng)));
    for (const glm::vec3& p : points)
      ASSERT_TRUE(leaf_holds(tree, 0, p, i)) << "sphere " << i << " not referenced at (" << p.x << ", " << p.y
                                             << ", " << p.z << ")";
  }
}

bool inside(const GpuOctreeNode& inner, const GpuOctreeNode& outer) {
  return box_contains(outer, inner.lo) && box_contains(outer, inner.hi);
}

// The structure the GPU reads: a tree (every node reached once), children
// consecutive, inside their parent, siblings on their own side of every split
// plane; leaves in range, references ascending and overlapping the leaf box.
// Returns the depth of the deepest node.
uint32_t expect_valid_structure(const Octree& tree, const std::vector<Sphere>& spheres, const OctreeParams& params) {
  EXPECT_FALSE(tree.nodes.empty());
  EXPECT_LE(tree.big_count, kMaxBigPrimitives);
  EXPECT_LE(tree.big_count, tree.refs.size());
  EXPECT_TRUE(std::is_sorted(tree.refs.begin(), tree.refs.begin() + tree.big_count));
  std::vector<bool> big(spheres.size()), referenced(spheres.size());
  for (uint32_t i = 0; i < tree.big_count; ++i) big[tree.refs[i]] = true;

  std::vector<int> reached(tree.nodes.size());
  uint64_t leaf_refs = 0;
  uint32_t deepest = 0;
  struct Item {
    uint32_t node, depth;
  };
  std::vector<Item> stack = {{0, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    ++reached[index];
    deepest = std::max(deepest, depth);
    const GpuOctreeNode& n = tree.nodes[index];
    EXPECT_TRUE(n.lo.x <= n.hi.x && n.lo.y <= n.hi.y && n.lo.z <= n.hi.z) << "node " << index;
    if (!(n.count_or_mask & OCTREE_INTERNAL)) {
      EXPECT_GE(n.first, tree.big_count);
      EXPECT_LE(uint64_t(n.first) + n.count_or_mask, tree.refs.size());
      EXPECT_TRUE(n.count_or_mask > 0 || (index == 0 && tree.refs.size() == tree.big_count)) << "empty leaf " << index;
      leaf_refs += n.count_or_mask;
      for (uint32_t i = 0; i < n.count_or_mask; ++i) {
        const uint32_t s = tree.refs[n.first + i];
        EXPECT_LT(s, spheres.size());
        EXPECT_FALSE(big[s]) << "big sphere " << s << " in leaf " << index;
        if (i > 0) {
          EXPECT_LT(tree.refs[n.first + i - 1], s) << "leaf " << index << " not ascending";
        }
        referenced[s] = true;
        const glm::vec3 lo = spheres[s].center - spheres[s].radius, hi = spheres[s].center + spheres[s].radius;
        EXPECT_TRUE(lo.x <= n.hi.x && lo.y <= n.hi.y && lo.z <= n.hi.z && hi.x >= n.lo.x && hi.y >= n.lo.y &&
                    hi.z >= n.lo.z)
            << "sphere " << s << " does not overlap leaf " << index;
      }
      continue;
    }
    EXPECT_LT(depth, params.max_depth);
    const uint32_t mask = n.count_or_mask & ~OCTREE_INTERNAL;
    EXPECT_TRUE(mask != 0 && mask <= 0xFF) << "node " << index << " mask " << mask;
    const uint32_t count = std::popcount(mask);
    EXPECT_GT(n.first, index);
    EXPECT_LE(uint64_t(n.first) + count, tree.nodes.size());
    if (uint64_t(n.first) + count > tree.nodes.size()) continue;
    uint32_t octant[8];
    for (uint32_t k = 0, c = 0; k < 8; ++k)
      if (mask & (1u << k)) octant[c++] = k;
    for (uint32_t c = 0; c < count; ++c) {
      const GpuOctreeNode& child = tree.nodes[n.first + c];
      EXPECT_TRUE(inside(child, n)) << "child " << n.first + c << " outside parent " << index;
      for (uint32_t d = c + 1; d < count; ++d) {
        const GpuOctreeNode& other = tree.nodes[n.first + d];
        for (int a = 0; a < 3; ++a) {
          const bool c_up = (octant[c] >> a) & 1, d_up = (octant[d] >> a) & 1;
          if (c_up != d_up) {
            EXPECT_LE(c_up ? other.hi[a] : child.hi[a], c_up ? child.lo[a] : other.lo[a])
                << "siblings " << n.first + c << ", " << n.first + d << " overlap on axis " << a;
          }
        }
      }
      stack.push_back({n.first + c, depth + 1});
    }
  }
  for (size_t i = 0; i < reached.size(); ++i) EXPECT_EQ(reached[i], 1) << "node " << i << " reached " << reached[i];
  EXPECT_EQ(tree.big_count + leaf_refs, tree.refs.size()) << "leaf ranges do not tile refs";
  for (size_t i = 0; i < spheres.size(); ++i) EXPECT_TRUE(big[i] || referenced[i]) << "sphere " << i << " lost";
  return deepest;
}

void expect_consistent_stats(const Octree& tree, const std::vector<Sphere>& spheres, uint32_t deepest) {
  const OctreeStats& st = tree.stats;
  EXPECT_EQ(st.nodes, tree.nodes.size());
  EXPECT_EQ(st.leaves, std::count_if(tree.nodes.begin(), tree.nodes.end(),
                                     [](const GpuOctreeNode& n) { return !(n.count_or_mask & OCTREE_INTERNAL); }));
  EXPECT_EQ(st.max_depth_reached, deepest);
  EXPECT_EQ(st.refs, tree.refs.size());
  EXPECT_EQ(st.big_primitives, tree.big_count);
  EXPECT_EQ(st.bytes, 32 * tree.nodes.size() + 4 * tree.refs.size());
  const double n = static_cast<double>(spheres.size());
  EXPECT_DOUBLE_EQ(st.refs_per_primitive, spheres.empty() ? 0.0 : static_cast<double>(st.refs) / n);
  EXPECT_DOUBLE_EQ(st.bytes_per_primitive, spheres.empty() ? 0.0 : static_cast<double>(st.bytes) / n);
  EXPECT_GE(st.build_ms, 0.0);
}

// Every guarantee at once, for one scene and one set of parameters.
// What rays pay: the references in every leaf whose box one crosses (no
// early exit), summed over the rays.
uint64_t references_met(const Octree& tree, const std::vector<Ray>& rays) {
  uint64_t met = 0;
  for (const Ray& ray : rays) {
    std::vector<uint32_t> stack = {0};
    while (!stack.empty()) {
      const GpuOctreeNode& n = tree.nodes[stack.back()];
      stack.pop_back();
      double t0, t1;
      if (!hit_box(n, ray, t0, t1)) continue;
      if (!(n.count_or_mask & OCTREE_INTERNAL)) {
        met += n.count_or_mask;
        continue;
      }
      for (uint32_t c = 0; c < uint32_t(std::popcount(n.count_or_mask & 0xFFu)); ++c) stack.push_back(n.first + c);
    }
  }
  return met;
}

void expect_correct_octree(const std::vector<Sphere>& spheres, const OctreeParams& params, size_t rays = 2000) {
  const Octree tree = build_octree(sphere_boxes(spheres), params);
  const uint32_t deepest = expect_valid_structure(tree, spheres, params);
  expect_consistent_stats(tree, spheres, deepest);
  expect_spheres_findable(tree, spheres);
  expect_same_hits(tree, spheres, rays);
}

std::vector<Sphere> rtiow(uint64_t n, float radius, uint64_t seed = 1) {
  return make_rtiow_scene({n, radius, seed}).spheres;
}

struct RtiowCase {
  uint64_t spheres;
  float radius;
};

class OctreeRtiow : public testing::TestWithParam<RtiowCase> {};

TEST_P(OctreeRtiow, FindsTheSameClosestHitAsBruteForce) {
  const auto spheres = rtiow(GetParam().spheres, GetParam().radius);
  for (const OctreeParams params : {OctreeParams{}, OctreeParams{1, 20}, OctreeParams{2, 3}, OctreeParams{64, 16}}) {
    SCOPED_TRACE("leaf " + std::to_string(params.leaf_size) + " depth " + std::to_string(params.max_depth));
    expect_correct_octree(spheres, params);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, OctreeRtiow,
                         testing::Values(RtiowCase{0, 0.2f}, RtiowCase{10, 0.2f}, RtiowCase{488, 0.2f},
                                         RtiowCase{2000, 0.1f}, RtiowCase{8000, 0.1f}, RtiowCase{4000, 0.4f},
                                         RtiowCase{30000, 0.05f}),
                         [](const auto& info) {
                           return std::to_string(info.param.spheres) + "_r" +
                                  std::to_string(static_cast<int>(info.param.radius * 100));
                         });

TEST(Octree, RtiowGroundIsTheOnlyBigSphere) {
  for (const uint64_t n : {0, 488, 8000}) {
    const auto spheres = rtiow(n, 0.1f);
    const Octree tree = build_octree(sphere_boxes(spheres), {});
    ASSERT_EQ(tree.big_count, 1u) << n << " spheres";
    EXPECT_EQ(spheres[tree.refs[0]].radius, 1000.0f);
  }
}

TEST(Octree, EmptySceneIsAnEmptyRootLeaf) {
  const Octree tree = build_octree(std::span<const Aabb>{}, {});
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_EQ(tree.nodes[0].count_or_mask, 0u);
  EXPECT_TRUE(tree.refs.empty());
  EXPECT_EQ(tree.big_count, 0u);
  expect_correct_octree({}, {});
}

TEST(Octree, OneSphere) {
  const std::vector<Sphere> spheres = {{{1, 2, 3}, 0.5f, 0}};
  const Octree tree = build_octree(sphere_boxes(spheres), {});
  EXPECT_EQ(tree.big_count, 1u);
  expect_correct_octree(spheres, {});
}

TEST(Octree, BigSpheresStopAtSixteen) {
  // Concentric spheres, each twice the radius of the next: all big by the rule.
  std::vector<Sphere> spheres;
  for (int i = 0; i < 20; ++i) spheres.push_back({{0, 0, 0}, std::ldexp(1.0f, 10 - i), 0});
  const Octree tree = build_octree(sphere_boxes(spheres), {});
  EXPECT_EQ(tree.big_count, kMaxBigPrimitives);
  expect_correct_octree(spheres, {});
}

TEST(Octree, FieldOfEqualSpheresHasNoBigSphere) {
  std::vector<Sphere> spheres;
  for (int x = 0; x < 10; ++x)
    for (int z = 0; z < 10; ++z) spheres.push_back({{x, 0.5f, z}, 0.4f, 0});
  EXPECT_EQ(build_octree(sphere_boxes(spheres), {}).big_count, 0u);
}

TEST(Octree, CoincidentSpheres) {
  const std::vector<Sphere> same(1000, Sphere{{1, 2, 3}, 0.5f, 0});
  expect_correct_octree(same, {});
  expect_correct_octree(same, {1, 20});
  auto mixed = rtiow(2000, 0.1f);
  mixed.insert(mixed.end(), 500, Sphere{{2.5f, 0.1f, -3.0f}, 0.1f, 0});
  expect_correct_octree(mixed, {1, 20});
}

TEST(Octree, SpheresCentredOnSplitPlanes) {
  // Integer grid, symmetric about 0: split planes pass through centres, and
  // neighbours (r = 0.5) touch exactly on them.
  for (const float radius : {0.5f, 0.25f}) {
    std::vector<Sphere> spheres;
    for (int x = -8; x <= 8; ++x)
      for (int y = -8; y <= 8; ++y)
        for (int z = -8; z <= 8; ++z) spheres.push_back({{x, y, z}, radius, 0});
    expect_correct_octree(spheres, {});
    expect_correct_octree(spheres, {1, 20});
  }
}

TEST(Octree, FlatAndLinearScenes) {
  std::vector<Sphere> plane, line;
  for (int x = 0; x < 100; ++x)
    for (int z = 0; z < 100; ++z) plane.push_back({{x * 0.01f, 0.0f, z * 0.01f}, 0.001f, 0});
  for (int x = 0; x < 1000; ++x) line.push_back({{x * 0.01f, 0.0f, 0.0f}, 0.004f, 0});
  expect_correct_octree(plane, {});
  expect_correct_octree(plane, {1, 20});
  expect_correct_octree(line, {1, 20});
}

TEST(Octree, HugeCoordinates) {
  auto spheres = rtiow(2000, 0.1f);
  for (Sphere& s : spheres) s.center += glm::vec3(1e5f, 1e5f, -1e5f);
  expect_correct_octree(spheres, {});
  expect_correct_octree(spheres, {1, 20});
}

TEST(Octree, ReferencesStayWithinTheBudgetPerSphere) {
  // Overlapping spheres far smaller than a float step at 1e5 in x: the box is
  // flat in x, and every sphere straddles the z midpoint. Once, this doubled
  // the references at every level.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-5e-6f, 5e-6f);
  std::vector<Sphere> line(10000);
  for (Sphere& s : line) s = {{1e5f + u(rng), u(rng), 0.0f}, 1e-7f, 0};
  for (const OctreeParams params : {OctreeParams{}, OctreeParams{1, 20},
                                     OctreeParams{.leaf_size = 1, .max_depth = 20, .max_refs = 1},
                                     OctreeParams{.leaf_size = 1, .max_depth = 20, .max_refs = 16}}) {
    const Octree tree = build_octree(sphere_boxes(line), params);
    EXPECT_LE(tree.refs.size(), tree.stats.max_refs * line.size()) << tree.stats.max_refs << " refs per sphere";
    expect_correct_octree(line, params, 500);
  }
}

TEST(Octree, SameInputSameOutput) {
  // Large enough to be built by several threads.
  const auto spheres = rtiow(300000, 0.02f);
  const Octree a = build_octree(sphere_boxes(spheres), {});
  for (int i = 0; i < 3; ++i) {
    const Octree b = build_octree(sphere_boxes(spheres), {});
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(GpuOctreeNode)), 0);
    EXPECT_EQ(a.refs, b.refs);
    EXPECT_EQ(a.big_count, b.big_count);
  }
  const uint32_t deepest = expect_valid_structure(a, spheres, {});
  expect_consistent_stats(a, spheres, deepest);
  expect_spheres_findable(a, spheres);
  expect_same_hits(a, spheres, 500);
}

// The same tree, node for node and reference for reference.
void expect_identical_trees(const Octree& a, const Octree& b) {
  EXPECT_EQ(a.refs, b.refs);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), b.nodes.size() * sizeof(GpuOctreeNode)), 0);
}

// OctreeParams::leaf_size 0 (auto; the tracer puts the device's rule in
// first, render_test) builds with kOctreeLeaf, and the stats say which size
// the build used.
TEST(Octree, LeafSizeZeroIsTheDefault) {
  const auto boxes = sphere_boxes(rtiow(8000, 0.1f));
  const Octree automatic = build_octree(boxes, {.leaf_size = 0});
  const Octree ten = build_octree(boxes, {.leaf_size = kOctreeLeaf});
  const Octree sixteen = build_octree(boxes, {.leaf_size = 16});
  EXPECT_EQ(automatic.stats.leaf_size, kOctreeLeaf);
  EXPECT_EQ(sixteen.stats.leaf_size, 16u);
  expect_identical_trees(automatic, ten);
  EXPECT_LT(sixteen.nodes.size(), ten.nodes.size());  // the sizes make other trees here
}

// OctreeParams::max_refs 0 (auto; the tracer puts the device's rule in
// first, render_test) builds with kOctreeRefs, and the stats say which
// budget the build used.
TEST(Octree, MaxRefsZeroIsTheDefault) {
  const auto boxes = sphere_boxes(rtiow(8000, 0.1f));
  const Octree automatic = build_octree(boxes, {.max_refs = 0});
  const Octree eight = build_octree(boxes, {.max_refs = kOctreeRefs});
  const Octree one = build_octree(boxes, {.max_refs = 1});
  EXPECT_EQ(automatic.stats.max_refs, kOctreeRefs);
  EXPECT_EQ(one.stats.max_refs, 1u);
  expect_identical_trees(automatic, eight);
  EXPECT_NE(one.refs.size(), eight.refs.size());  // the budgets make other trees here
}

// The most references a leaf holding primitive `prim` has (0 if none holds it).
uint32_t largest_leaf_with(const Octree& tree, uint32_t prim) {
  uint32_t largest = 0;
  for (const GpuOctreeNode& n : tree.nodes) {
    if (n.count_or_mask & OCTREE_INTERNAL) continue;
    for (uint32_t i = 0; i < n.count_or_mask; ++i)
      if (tree.refs[n.first + i] == prim) largest = std::max(largest, n.count_or_mask);
  }
  return largest;
}

// OctreeParams::copy_leaf (optimisation log 136): a node of more than
// leaf_size and at most copy_leaf references stays a leaf where one of them
// spans more than kCopyLeafSpan of the node's extent along an axis; with
// more references, or without such a reference, it splits as before. Five
// clusters of 15 small boxes in a 4-wide cube, and a box along x across the
// first cluster: that cluster's node (16 references) stays whole.
TEST(Octree, CopyLeavesKeepANodeThatAReferenceSpansWhole) {
  std::vector<Aabb> boxes;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.05f, 0.9f);
  for (const glm::vec3 at : {glm::vec3(0), glm::vec3(3, 0, 0), glm::vec3(0, 3, 0), glm::vec3(0, 0, 3), glm::vec3(3)})
    for (int i = 0; i < 15; ++i) {
      const glm::vec3 p = at + glm::vec3(u(rng), u(rng), u(rng));
      boxes.push_back({p, p + 0.05f});
    }
  const uint32_t first_small = 0;
  const uint32_t across = uint32_t(boxes.size());
  boxes.push_back({glm::vec3(0.05f, 0.5f, 0.5f), glm::vec3(0.95f, 0.52f, 0.52f)});
  const OctreeParams copy{.leaf_size = 10, .max_refs = 8, .copy_leaf = 20};
  const Octree kept = build_octree(boxes, copy);
  EXPECT_EQ(kept.big_count, 0u);
  EXPECT_EQ(kept.stats.copy_leaf, 20u);
  EXPECT_EQ(largest_leaf_with(kept, across), 16u);  // the cluster and the box across it
  EXPECT_EQ(largest_leaf_with(kept, first_small), 16u);
  // Without copy leaves, or with fewer than the node's 16, it splits.
  const Octree plain = build_octree(boxes, {.leaf_size = 10, .max_refs = 8});
  EXPECT_EQ(plain.stats.copy_leaf, 0u);
  EXPECT_LE(largest_leaf_with(plain, first_small), 10u);
  EXPECT_LT(largest_leaf_with(build_octree(boxes, {.leaf_size = 10, .max_refs = 8, .copy_leaf = 15}), across), 16u);
  // Without the box across, copy leaves change nothing.
  boxes.pop_back();
  expect_identical_trees(build_octree(boxes, copy), build_octree(boxes, {.leaf_size = 10, .max_refs = 8}));
}

// A tree with copy leaves is a valid octree that finds every hit brute
// force does (the rtiow field's three large spheres among small ones make
// copy leaves at 12 references).
TEST(Octree, CopyLeavesFindWhatBruteForceFinds) {
  const auto spheres = rtiow(2000, 0.1f);
  const OctreeParams params{.leaf_size = 10, .max_refs = 12, .copy_leaf = 20};
  const Octree copy = build_octree(sphere_boxes(spheres), params);
  const Octree plain = build_octree(sphere_boxes(spheres), {.leaf_size = 10, .max_refs = 12});
  EXPECT_NE(copy.nodes.size(), plain.nodes.size());  // the rule made other leaves here
  expect_correct_octree(spheres, params, 1000);
}

TEST(Octree, AtMost64BytesPerSphere) {
  for (const RtiowCase c : {RtiowCase{488, 0.2f}, RtiowCase{8000, 0.1f}, RtiowCase{1000000, 0.01f}}) {
    const Octree tree = build_octree(sphere_boxes(rtiow(c.spheres, c.radius)), {});
    EXPECT_LE(tree.stats.bytes_per_primitive, 64.0) << c.spheres << " spheres of radius " << c.radius;
  }
}

// Split clipping (octree.h ClipFn): long thin triangles in every direction.
// Every point of every triangle lies in a leaf box that references it (what
// the traversal needs), the build is deterministic, and the triangles are
// referenced by fewer leaves than their boxes would be.
TEST(Octree, ClippedTrianglesAreFindableWithFewerReferences) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), small(-0.05f, 0.05f);
  struct Tri {
    glm::vec3 a, b, c;
  };
  std::vector<Tri> tris(4000);
  std::vector<Aabb> boxes(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    // Half slivers across the scene, half small triangles.
    const glm::vec3 a(pos(rng), pos(rng), pos(rng));
    const glm::vec3 b = i % 2 ? glm::vec3(pos(rng), pos(rng), pos(rng)) : a + glm::vec3(small(rng), small(rng), small(rng));
    const glm::vec3 c = a + glm::vec3(small(rng), small(rng), small(rng));
    tris[i] = {a, b, c};
    for (const glm::vec3& v : {a, b, c}) boxes[i].extend({v, v});
  }
  const ClipFn clip = [&](uint32_t t, const Aabb& cell, Aabb& part) {
    return clip_triangle(tris[t].a, tris[t].b, tris[t].c, cell, part);
  };
  const Octree plain = build_octree(boxes, {});
  const Octree clipped = build_octree(boxes, {}, clip);
  const Octree again = build_octree(boxes, {}, clip);
  EXPECT_EQ(clipped.refs, again.refs);
  ASSERT_EQ(clipped.nodes.size(), again.nodes.size());
  EXPECT_EQ(std::memcmp(clipped.nodes.data(), again.nodes.data(), clipped.nodes.size() * sizeof(GpuOctreeNode)), 0);
  // Clipped into every octant of a split at once (ClipOctantsFn, what a
  // scene's meshes use): the same tree, node for node.
  const ClipOctantsFn clip_octants = [&](uint32_t t, const Aabb& box, const glm::vec3& mid, uint32_t candidates,
                                         Aabb parts[8]) {
    return clip_triangle_octants(tris[t].a, tris[t].b, tris[t].c, box, mid, candidates, parts);
  };
  const Octree at_once = build_octree(boxes, {}, clip, clip_octants);
  EXPECT_EQ(clipped.refs, at_once.refs);
  ASSERT_EQ(clipped.nodes.size(), at_once.nodes.size());
  EXPECT_EQ(std::memcmp(clipped.nodes.data(), at_once.nodes.data(), clipped.nodes.size() * sizeof(GpuOctreeNode)), 0);
  EXPECT_LE(clipped.refs.size(), 8 * tris.size());
  // Random rays through the scene.
  std::vector<Ray> rays;
  std::mt19937_64 ray_rng(23);
  for (int r = 0; r < 2000; ++r) {
    const glm::dvec3 origin(pos(ray_rng), pos(ray_rng), pos(ray_rng));
    rays.push_back({origin, random_unit(ray_rng)});
  }
  const auto refs_met = [&](const Octree& tree) { return references_met(tree, rays); };
  const uint64_t met_plain = refs_met(plain), met_clipped = refs_met(clipped);
  EXPECT_LT(double(met_clipped), 0.5 * double(met_plain)) << "clipped " << met_clipped << ", by boxes " << met_plain;

  // Every point of every triangle lies in a leaf that references it.
  const auto expect_complete = [&](const Octree& tree) {
    std::vector<bool> big(tris.size());
    for (uint32_t i = 0; i < tree.big_count; ++i) big[tree.refs[i]] = true;
    std::mt19937_64 point_rng(29);
    std::uniform_real_distribution<float> w(0.0f, 1.0f);
    for (uint32_t i = 0; i < tris.size(); ++i) {
      if (big[i]) continue;
      const Tri& t = tris[i];
      std::vector<glm::vec3> points = {t.a, t.b, t.c, (t.a + t.b) * 0.5f};
      for (int j = 0; j < 12; ++j) {
        float u = w(point_rng), v = w(point_rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        points.push_back(t.a + u * (t.b - t.a) + v * (t.c - t.a));
      }
      for (const glm::vec3& p : points)
        ASSERT_TRUE(leaf_holds(tree, 0, p, i))
            << "triangle " << i << " not referenced at (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  };
  expect_complete(clipped);

  // A larger split budget (OctreeParams::max_refs, `--octree-refs`) lets the
  // slivers be cut further: more references, within the new bound, and fewer
  // of them met by a ray (optimisation log 57: the engine's triangle tests).
  const Octree deeper = build_octree(boxes, {.max_refs = 16}, clip);
  EXPECT_LE(deeper.refs.size(), 16 * tris.size());
  EXPECT_GT(deeper.refs.size(), clipped.refs.size());
  EXPECT_LT(refs_met(deeper), met_clipped);
  expect_complete(deeper);
}

// A dense field of overlapping spheres, as the hidden-parts rule leaves it
// (each sphere's box the column of its visible part, accel/hidden_parts.h):
// the boxes straddle every horizontal middle, so without the spheres'
// surfaces (clip_sphere_surface) and clip_straddled the octree cannot part
// the top caps from the bottom ones (optimisation log 126). With them every
// visible surface point stays findable, rays from above find what brute
// force finds, and a ray meets far fewer references.
TEST(Octree, SphereSurfacesPartTheCapsOfADenseField) {
  std::vector<Sphere> spheres;
  for (int x = 0; x < 40; ++x)
    for (int z = 0; z < 40; ++z) spheres.push_back({glm::vec3(0.02f * x, 0.1f, 0.02f * z), 0.1f, 0});
  std::vector<Ball> balls;
  for (const Sphere& s : spheres) balls.push_back({s.center, s.radius});
  const std::vector<Aabb> boxes = visible_sphere_boxes(balls, std::vector<uint8_t>(balls.size(), 1));
  const ClipFn surfaces = sphere_surface_clip(spheres, boxes);  // the top level's, render/gpu_scene.h
  const Octree plain = build_octree(boxes, {});
  const Octree clipped = build_octree(boxes, {}, surfaces, {}, true);
  const Octree narrow = build_octree(boxes, {}, surfaces);  // the straddle rule as before
  EXPECT_GT(clipped.stats.max_depth_reached, plain.stats.max_depth_reached);
  EXPECT_LE(clipped.refs.size(), size_t(kOctreeRefs) * spheres.size());
  // Every point of a sphere's surface in its box (above or below a random
  // point of the column's cross-section) lies in a leaf that references it.
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  size_t checked = 0;
  for (uint32_t i = 0; i < spheres.size(); ++i)
    for (int k = 0; k < 20; ++k) {
      const Aabb& b = boxes[i];
      const glm::dvec3 c(spheres[i].center);
      glm::dvec3 p(b.lo.x + unit(rng) * (b.hi.x - b.lo.x), 0.0, b.lo.z + unit(rng) * (b.hi.z - b.lo.z));
      const double h2 = double(spheres[i].radius) * spheres[i].radius - (p.x - c.x) * (p.x - c.x) -
                        (p.z - c.z) * (p.z - c.z);
      if (h2 < 0.0) continue;
      p.y = c.y + (k % 2 ? 1.0 : -1.0) * std::sqrt(h2);
      if (p.y < b.lo.y || p.y > b.hi.y) continue;
      ++checked;
      ASSERT_TRUE(leaf_holds(clipped, 0, glm::vec3(p), i)) << "sphere " << i << " at (" << p.x << ", " << p.y << ", "
                                                            << p.z << ")";
    }
  EXPECT_GT(checked, spheres.size());
  // Rays from above the field, which start outside every sphere.
  std::vector<Ray> rays;
  std::uniform_real_distribution<double> u(0.0, 0.78);
  for (int r = 0; r < 2000; ++r) {
    const glm::dvec3 target(u(rng), 0.1, u(rng));
    const glm::dvec3 origin = target + glm::dvec3(u(rng) - 0.39, 1.0, u(rng) - 0.39);
    rays.push_back({origin, glm::normalize(target - origin)});
  }
  for (const Ray& ray : rays) {
    const Hit want = brute_force(spheres, ray);
    ASSERT_EQ(traverse(clipped, spheres, ray), want) << "ray from (" << ray.origin.x << ", " << ray.origin.y << ", "
                                                      << ray.origin.z << ")";
    ASSERT_EQ(traverse(narrow, spheres, ray), want);
  }
  const uint64_t met_plain = references_met(plain, rays), met_clipped = references_met(clipped, rays);
  EXPECT_LT(2 * met_clipped, met_plain) << "surfaces " << met_clipped << ", boxes " << met_plain;
  EXPECT_LT(met_clipped, references_met(narrow, rays));
}

// The library names its own settings; the CLI maps them to flags (cli_test).
TEST(Octree, BadParametersNameTheSetting) {
  const auto spheres = rtiow(10, 0.2f);
  const auto message = [&](OctreeParams params) -> std::string {
    try {
      build_octree(sphere_boxes(spheres), params);
    } catch (const SettingError& e) {
      return e.setting + " | " + e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message({0, 16}), "no error");  // auto: kOctreeLeaf (LeafSizeZeroIsTheDefault)
  EXPECT_EQ(message({8, 0}), "octree.max_depth | octree.max_depth: must be in 1..20, got 0");
  EXPECT_EQ(message({8, 21}), "octree.max_depth | octree.max_depth: must be in 1..20, got 21");
  EXPECT_EQ(message({.max_refs = 0}), "no error");  // auto: kOctreeRefs (MaxRefsZeroIsTheDefault)
  EXPECT_EQ(message({.max_refs = 65}), "octree.max_refs | octree.max_refs: must be in 1..64 or 0 (auto), got 65");
  EXPECT_EQ(message({.max_refs = 64}), "no error");
  EXPECT_EQ(message({1, 20}), "no error");
}

}  // namespace
}  // namespace octrace
