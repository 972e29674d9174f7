// visible_sphere_boxes (accel/hidden_parts.h): every point of a sphere's
// surface that no occluder holds lies in its box; on a dense field the boxes
// shrink to columns; nothing changes where nothing overlaps.
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "accel/hidden_parts.h"

namespace octrace {
namespace {

bool inside(const Aabb& b, const glm::vec3& p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
}

Aabb whole(const Ball& b) { return {b.center - b.radius, b.center + b.radius}; }

// Points of sphere i's surface that lie strictly inside no occluder must be
// in its box (the rule asks this only of points a margin deep; this is stricter).
void expect_visible_points_inside(const std::vector<Ball>& balls, const std::vector<uint8_t>& occ,
                                  const std::vector<Aabb>& boxes, uint32_t samples, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n;
  for (size_t i = 0; i < balls.size(); ++i)
    for (uint32_t k = 0; k < samples; ++k) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
      const glm::dvec3 p = glm::dvec3(balls[i].center) + double(balls[i].radius) * d;
      bool hidden = false;
      for (size_t j = 0; j < balls.size() && !hidden; ++j)
        hidden = j != i && occ[j] && glm::length(p - glm::dvec3(balls[j].center)) < double(balls[j].radius);
      if (hidden) continue;
      ASSERT_TRUE(inside(boxes[i], glm::vec3(p))) << "ball " << i << ", point (" << p.x << ", " << p.y << ", " << p.z
                                                  << ") holds no occluder and lies outside its box";
    }
}

TEST(HiddenParts, VisiblePointsStayInTheirBoxes) {
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> pos(-2.0f, 2.0f), rad(0.2f, 1.5f), coin(0.0f, 1.0f);
    std::vector<Ball> balls;
    std::vector<uint8_t> occ;
    for (int i = 0; i < 60; ++i) {
      balls.push_back({{pos(rng), pos(rng), pos(rng)}, rad(rng)});
      occ.push_back(coin(rng) < 0.8f);
    }
    balls.push_back({{0.0f, -1000.5f, 0.0f}, 1000.0f});  // a ground that cuts the low ones
    occ.push_back(1);
    HiddenPartsStats st;
    const std::vector<Aabb> boxes = visible_sphere_boxes(balls, occ, &st);
    ASSERT_EQ(boxes.size(), balls.size());
    EXPECT_GT(st.clipped + st.hidden, 0u) << "seed " << seed << ": nothing overlapped, the test tests nothing";
    for (size_t i = 0; i < balls.size(); ++i) {
      const Aabb w = whole(balls[i]);
      for (int a = 0; a < 3; ++a) {  // never larger than the sphere's box
        EXPECT_GE(boxes[i].lo[a], w.lo[a]);
        EXPECT_LE(boxes[i].hi[a], w.hi[a]);
      }
    }
    expect_visible_points_inside(balls, occ, boxes, 400, seed);
  }
}

// Equal spheres on a grid 0.02 apart, radius 0.1 (the 1M field's spacing):
// away from the edges a sphere's visible surface is the part above and
// below its grid square, so its box is a column about 0.02 wide.
TEST(HiddenParts, DenseGridBecomesColumns) {
  std::vector<Ball> balls;
  const int n = 30;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) balls.push_back({{0.02f * float(i), 0.1f, 0.02f * float(k)}, 0.1f});
  const std::vector<uint8_t> occ(balls.size(), 1);
  HiddenPartsStats st;
  const std::vector<Aabb> boxes = visible_sphere_boxes(balls, occ, &st);
  EXPECT_EQ(st.hidden, 0u);
  for (int i = 8; i < n - 8; ++i)
    for (int k = 8; k < n - 8; ++k) {
      const Aabb& b = boxes[size_t(i) * n + k];
      EXPECT_LT(b.hi.x - b.lo.x, 0.025f) << i << ", " << k;
      EXPECT_LT(b.hi.z - b.lo.z, 0.025f) << i << ", " << k;
      EXPECT_GT(b.hi.x - b.lo.x, 0.02f) << i << ", " << k;  // the square itself stays
      EXPECT_FLOAT_EQ(b.hi.y, 0.2f);
    }
  expect_visible_points_inside(balls, occ, boxes, 200, 7);
}

// Not occluders (glass): nothing is hidden; the same boxes, bit for bit.
TEST(HiddenParts, WithoutOccludersNothingChanges) {
  std::vector<Ball> balls;
  for (int i = 0; i < 20; ++i) balls.push_back({{0.3f * float(i), 0.0f, 0.0f}, 0.5f});
  const std::vector<Aabb> boxes = visible_sphere_boxes(balls, std::vector<uint8_t>(balls.size(), 0));
  for (size_t i = 0; i < balls.size(); ++i) {
    EXPECT_EQ(boxes[i].lo, whole(balls[i]).lo);
    EXPECT_EQ(boxes[i].hi, whole(balls[i]).hi);
  }
}

// Spheres apart from each other, and coincident copies of one sphere (each
// copy's surface lies on the other's, inside neither): whole boxes.
TEST(HiddenParts, ApartOrCoincidentKeepWholeBoxes) {
  const std::vector<Ball> balls = {{{0, 0, 0}, 1.0f}, {{3, 0, 0}, 1.0f}, {{3, 0, 0}, 1.0f}, {{0, 2.0f, 0}, 1.0f}};
  HiddenPartsStats st;
  const std::vector<Aabb> boxes = visible_sphere_boxes(balls, std::vector<uint8_t>(balls.size(), 1), &st);
  EXPECT_EQ(st.clipped, 0u);
  EXPECT_EQ(st.hidden, 0u);
  for (size_t i = 0; i < balls.size(); ++i) {
    EXPECT_EQ(boxes[i].lo, whole(balls[i]).lo) << i;
    EXPECT_EQ(boxes[i].hi, whole(balls[i]).hi) << i;
  }
}

// A sphere inside an opaque one has nothing left: the point at its centre.
// Inside a glass one (not an occluder) it keeps its box; so does the glass.
TEST(HiddenParts, InsideAnOccluderNothingIsLeft) {
  const std::vector<Ball> balls = {{{0, 0, 0}, 2.0f}, {{0.5f, 0, 0}, 1.0f}, {{10, 0, 0}, 2.0f}, {{10.5f, 0, 0}, 1.0f}};
  const std::vector<uint8_t> occ = {1, 1, 0, 1};
  HiddenPartsStats st;
  const std::vector<Aabb> boxes = visible_sphere_boxes(balls, occ, &st);
  EXPECT_EQ(st.hidden, 1u);
  EXPECT_EQ(boxes[1].lo, balls[1].center);
  EXPECT_EQ(boxes[1].hi, balls[1].center);
  for (size_t i : {0u, 2u, 3u}) {
    EXPECT_EQ(boxes[i].lo, whole(balls[i]).lo) << i;
    EXPECT_EQ(boxes[i].hi, whole(balls[i]).hi) << i;
  }
}

}  // namespace
}  // namespace octrace
