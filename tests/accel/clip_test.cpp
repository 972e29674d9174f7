// clip_triangle: the box of a triangle's part inside a cell holds every point
// of that part, lies in the cell, and a triangle that only passes by a cell
// (its box overlaps, the triangle does not) is not in it.
#include "accel/clip.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <glm/geometric.hpp>

namespace octrace {
namespace {

bool contains(const Aabb& b, const glm::dvec3& p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < double(b.lo[a]) || p[a] > double(b.hi[a])) return false;
  return true;
}

const Aabb kUnit{glm::vec3(0.0f), glm::vec3(1.0f)};

TEST(ClipTriangle, InsideIsItsOwnBox) {
  Aabb part;
  ASSERT_TRUE(clip_triangle({0.1f, 0.2f, 0.3f}, {0.9f, 0.25f, 0.3f}, {0.5f, 0.8f, 0.7f}, kUnit, part));
  // Its box, to the ulps the result is widened by.
  EXPECT_NEAR(part.lo.x, 0.1f, 1e-6f);
  EXPECT_NEAR(part.hi.x, 0.9f, 1e-6f);
  EXPECT_NEAR(part.lo.y, 0.2f, 1e-6f);
  EXPECT_NEAR(part.hi.y, 0.8f, 1e-6f);
  EXPECT_NEAR(part.lo.z, 0.3f, 1e-6f);
  EXPECT_NEAR(part.hi.z, 0.7f, 1e-6f);
}

TEST(ClipTriangle, SliverPassingByACornerIsNotInTheCell) {
  // A thin triangle beyond the diagonal x + y = 3 in the plane z = 0.5: its
  // box [1, 2]^2 overlaps the cell [0, 1.4]^3 in [1, 1.4]^2, where x + y is
  // at most 2.8: the triangle itself passes the cell by.
  const Aabb cell{glm::vec3(0.0f), glm::vec3(1.4f)};
  Aabb part;
  EXPECT_FALSE(clip_triangle({1.0f, 2.0f, 0.5f}, {2.0f, 1.0f, 0.5f}, {1.6f, 1.6f, 0.5f}, cell, part));
  // Moved across the corner (1.4, 1.4): in.
  EXPECT_TRUE(clip_triangle({0.6f, 2.0f, 0.5f}, {2.0f, 0.6f, 0.5f}, {1.6f, 1.6f, 0.5f}, cell, part));
}

TEST(ClipTriangle, CutByTheCellKeepsOnlyThePartInside) {
  // A triangle across x = 1: its part in the unit cell spans x in [0.5, 1].
  Aabb part;
  ASSERT_TRUE(clip_triangle({0.5f, 0.1f, 0.5f}, {3.0f, 0.1f, 0.5f}, {0.5f, 0.9f, 0.5f}, kUnit, part));
  EXPECT_NEAR(part.lo.x, 0.5f, 1e-6f);
  EXPECT_EQ(part.hi.x, 1.0f);  // clamped to the cell
  EXPECT_NEAR(part.hi.y, 0.9f, 1e-6f);
  EXPECT_NEAR(part.lo.y, 0.1f, 1e-6f);
}

TEST(ClipTriangle, OnAFaceIsInTheCell) {
  // Lying in the cell's face x = 1, and touching it at one vertex only.
  Aabb part;
  EXPECT_TRUE(clip_triangle({1.0f, 0.2f, 0.2f}, {1.0f, 0.8f, 0.2f}, {1.0f, 0.5f, 0.8f}, kUnit, part));
  EXPECT_NEAR(part.lo.x, 1.0f, 1e-6f);
  EXPECT_EQ(part.hi.x, 1.0f);
  EXPECT_TRUE(clip_triangle({1.0f, 0.5f, 0.5f}, {2.0f, 0.5f, 0.5f}, {2.0f, 0.9f, 0.5f}, kUnit, part));
  EXPECT_FALSE(clip_triangle({1.5f, 0.5f, 0.5f}, {2.0f, 0.5f, 0.5f}, {2.0f, 0.9f, 0.5f}, kUnit, part));
}

TEST(ClipTriangle, DegenerateTrianglesAreClippedToo) {
  Aabb part;
  // A segment through the cell, and a point outside it.
  EXPECT_TRUE(clip_triangle({-1.0f, 0.5f, 0.5f}, {2.0f, 0.5f, 0.5f}, {2.0f, 0.5f, 0.5f}, kUnit, part));
  EXPECT_EQ(part.lo.x, 0.0f);
  EXPECT_EQ(part.hi.x, 1.0f);
  EXPECT_FALSE(clip_triangle({2.0f, 2.0f, 2.0f}, {2.0f, 2.0f, 2.0f}, {2.0f, 2.0f, 2.0f}, kUnit, part));
}

// Random triangles against random cells: every sampled point of a triangle
// inside the cell lies in the part's box; where no sampled point is inside
// and the part is empty, fine; a reported part always lies in the cell.
TEST(ClipTriangle, PartHoldsEveryPointOfTheTriangleInTheCell) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> pos(-2.0f, 3.0f), w(0.0f, 1.0f);
  int kept = 0, dropped = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::vec3 a(pos(rng), pos(rng), pos(rng)), b(pos(rng), pos(rng), pos(rng)), c(pos(rng), pos(rng), pos(rng));
    Aabb part;
    const bool in = clip_triangle(a, b, c, kUnit, part);
    (in ? kept : dropped)++;
    if (in) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(part.lo[k], 0.0f);
        EXPECT_LE(part.hi[k], 1.0f);
      }
    }
    for (int s = 0; s < 200; ++s) {
      float u = w(rng), v = w(rng);
      if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
      const glm::dvec3 p = glm::dvec3(a) + double(u) * (glm::dvec3(b) - glm::dvec3(a)) +
                           double(v) * (glm::dvec3(c) - glm::dvec3(a));
      if (!contains(kUnit, p)) continue;
      ASSERT_TRUE(in) << "trial " << trial << ": a point of the triangle is in the cell";
      ASSERT_TRUE(contains(part, p)) << "trial " << trial;
    }
  }
  // Both outcomes occur: the test exercises both.
  EXPECT_GT(kept, 100);
  EXPECT_GT(dropped, 100);
}

// All octants at once (the octree's splits, optimisation log 108): for
// each candidate octant, the same answer and the same box, bit for bit, as
// clip_triangle with that octant's cell; triangles across the split planes,
// on them, past the box's faces, and axes left unsplit (mid = +inf).
TEST(ClipTriangleOctants, EachOctantAsClipTriangleGivesIt) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<float> pos(-0.5f, 1.5f), w(0.0f, 1.0f);
  const float inf = std::numeric_limits<float>::infinity();
  int reached_total = 0, partial = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    glm::vec3 a(pos(rng), pos(rng), pos(rng)), b(pos(rng), pos(rng), pos(rng)), c(pos(rng), pos(rng), pos(rng));
    if (trial % 4 == 1) b = a + 0.01f * (b - a), c = a + 0.01f * (c - a);  // small ones
    if (trial % 8 == 3) {  // inside the box, across the split planes: cut both ways in one pass
      a = 0.25f + 0.5f * (a + 0.5f) * 0.5f;
      b = 0.25f + 0.5f * (b + 0.5f) * 0.5f;
      c = 0.25f + 0.5f * (c + 0.5f) * 0.5f;
    }
    if (trial % 4 == 2) a.x = b.x = c.x = 0.5f;                           // in a split plane
    glm::vec3 mid(0.5f, 0.375f, w(rng));
    if (trial % 5 == 3) mid.y = inf;                                        // an axis not split
    const uint32_t candidates = trial % 3 == 0 ? 0xFFu : uint32_t(rng() & 0xFFu);
    Aabb parts[8];
    const uint32_t reached = clip_triangle_octants(a, b, c, kUnit, mid, candidates, parts);
    EXPECT_EQ(reached & ~candidates, 0u);
    for (uint32_t k = 0; k < 8; ++k) {
      if (!((candidates >> k) & 1u)) continue;
      Aabb cell = kUnit;
      for (int ax = 0; ax < 3; ++ax) {
        if (!(mid[ax] < inf)) continue;
        if ((k >> ax) & 1u) cell.lo[ax] = mid[ax];
        else cell.hi[ax] = mid[ax];
      }
      Aabb part;
      const bool in = clip_triangle(a, b, c, cell, part);
      ASSERT_EQ(in, ((reached >> k) & 1u) != 0u) << "trial " << trial << ", octant " << k;
      if (!in) continue;
      ++reached_total;
      for (int ax = 0; ax < 3; ++ax) {
        ASSERT_EQ(std::bit_cast<uint32_t>(part.lo[ax]), std::bit_cast<uint32_t>(parts[k].lo[ax])) << trial;
        ASSERT_EQ(std::bit_cast<uint32_t>(part.hi[ax]), std::bit_cast<uint32_t>(parts[k].hi[ax])) << trial;
      }
    }
    partial += reached != 0 && reached != candidates;
  }
  EXPECT_GT(reached_total, 4000);
  EXPECT_GT(partial, 500);  // octants missed as well as reached
}

// The one-ulp steps are std::nextafter's, for every finite float of a
// stride over all bit patterns and for the edges: zeros, subnormals, the
// smallest normal, one, the largest finite float.
TEST(NextFloat, StepsAsNextafterDoes) {
  const float inf = std::numeric_limits<float>::infinity();
  const auto check = [&](float f) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(next_float_down(f)), std::bit_cast<std::uint32_t>(std::nextafter(f, -inf)))
        << f;
    ASSERT_EQ(std::bit_cast<std::uint32_t>(next_float_up(f)), std::bit_cast<std::uint32_t>(std::nextafter(f, inf)))
        << f;
  };
  for (float f : {0.0f, -0.0f, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                  std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(), 1.0f, -1.0f,
                  std::numeric_limits<float>::max(), -std::numeric_limits<float>::max()})
    check(f);
  for (std::uint64_t bits = 0; bits <= 0xffffffffu; bits += 4099) {
    const float f = std::bit_cast<float>(std::uint32_t(bits));
    if (std::isfinite(f)) check(f);
  }
}

// clip_sphere_surface: the part's box holds every point of the sphere's
// surface inside the cell (spheres near the origin and 1000 away), lies in
// the cell, and a cell that only the ball reaches holds none.
glm::dvec3 unit_vector(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-9) return glm::normalize(v);
  }
}

TEST(ClipSphereSurface, HoldsEverySurfacePointInTheCell) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  size_t tested = 0, reached = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double scale = trial % 3 == 0 ? 1000.0 : 1.0;
    const glm::vec3 c(float(u(rng) * scale), float(u(rng) * scale), float(u(rng) * scale));
    const float r = float(0.05 + 0.95 * v(rng));
    const glm::dvec3 q = glm::dvec3(c) + 1.2 * double(r) * glm::dvec3(u(rng), u(rng), u(rng));
    const glm::dvec3 half = double(r) * glm::dvec3(0.01 + 0.5 * v(rng), 0.01 + 0.5 * v(rng), 0.01 + 0.5 * v(rng));
    const Aabb cell{glm::vec3(q - half), glm::vec3(q + half)};
    Aabb part;
    const bool got = clip_sphere_surface(c, r, cell, part);
    if (got) {
      ++reached;
      for (int a = 0; a < 3; ++a) {
        ASSERT_GE(part.lo[a], cell.lo[a]);
        ASSERT_LE(part.hi[a], cell.hi[a]);
        ASSERT_LE(part.lo[a], part.hi[a]);
      }
    }
    for (int k = 0; k < 300; ++k) {
      const glm::dvec3 p = glm::dvec3(c) + double(r) * unit_vector(rng);
      if (!contains(cell, p)) continue;
      ++tested;
      ASSERT_TRUE(got) << "trial " << trial << ": a surface point in the cell, none found";
      ASSERT_TRUE(contains(part, p)) << "trial " << trial << ": (" << p.x << ", " << p.y << ", " << p.z
                                     << ") outside the part";
    }
  }
  EXPECT_GT(tested, 5000u);
  EXPECT_GT(reached, 500u);
}

TEST(ClipSphereSurface, ACellInsideTheBallOrApartHoldsNone) {
  Aabb part;
  const glm::vec3 c(0.0f);
  EXPECT_FALSE(clip_sphere_surface(c, 1.0f, {glm::vec3(-0.5f), glm::vec3(0.5f)}, part));
  EXPECT_FALSE(clip_sphere_surface(c, 1.0f, {glm::vec3(0.6f), glm::vec3(2.0f)}, part));  // its corner is outside
  EXPECT_TRUE(clip_sphere_surface(c, 1.0f, {glm::vec3(0.5f), glm::vec3(2.0f)}, part));
  EXPECT_FALSE(clip_sphere_surface(c, 1.0f, {glm::vec3(1.1f, -0.1f, -0.1f), glm::vec3(2.0f, 0.1f, 0.1f)}, part));
}

// The visible column of a sphere in a dense field (accel/hidden_parts.h):
// its surface there is two thin caps; the column's top half holds the top
// cap only, a slab a thousandth of the radius thick.
TEST(ClipSphereSurface, AColumnIsItsTwoCaps) {
  const glm::vec3 c(0.0f, 0.1f, 0.0f);
  const float r = 0.1f;
  Aabb part;
  ASSERT_TRUE(clip_sphere_surface(c, r, {{-0.01f, 0.0f, -0.01f}, {0.01f, 0.2f, 0.01f}}, part));
  EXPECT_LE(part.lo.y, 0.0011f);
  EXPECT_GE(part.hi.y, 0.1989f);
  ASSERT_TRUE(clip_sphere_surface(c, r, {{-0.01f, 0.1f, -0.01f}, {0.01f, 0.2f, 0.01f}}, part));
  const float cap = 0.1f + std::sqrt(0.01f - 0.0002f);  // the lowest point of the cap in the column
  EXPECT_NEAR(part.lo.y, cap, 1e-5f);
  EXPECT_GE(part.hi.y, 0.2f - 1e-6f);
  EXPECT_LE(part.hi.y, 0.2f);
  EXPECT_FALSE(clip_sphere_surface(c, r, {{-0.01f, 0.03f, -0.01f}, {0.01f, 0.17f, 0.01f}}, part));
}

}  // namespace
}  // namespace octrace
