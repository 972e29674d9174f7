#include "accel/clip.h"

#include <bit>
#include <cstdint>
#include <limits>
#include <utility>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace octrace {

float next_float_down(float f) {
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits - 1u : bits + 1u);
}

float next_float_up(float f) {
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits + 1u : bits - 1u);
}

bool clip_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& cell, Aabb& part) {
  // A triangle clipped by 6 planes has at most 3 + 6 vertices; two arrays,
  // the polygon and the next one, swapped after each plane.
  constexpr int kMax = 9;
  glm::dvec3 buffers[2][kMax] = {{glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)}};
  glm::dvec3* poly = buffers[0];
  glm::dvec3* next = buffers[1];
  int n = 3;
  glm::dvec3 lo = glm::min(poly[0], glm::min(poly[1], poly[2]));
  glm::dvec3 hi = glm::max(poly[0], glm::max(poly[1], poly[2]));
  for (int axis = 0; axis < 3; ++axis)
    if (lo[axis] > double(cell.hi[axis]) || hi[axis] < double(cell.lo[axis])) return false;
  for (int axis = 0; axis < 3 && n > 0; ++axis) {
    for (int side = 0; side < 2 && n > 0; ++side) {
      // Keep the points with sign * (p[axis] - plane) <= 0: inside, faces included.
      const double plane = side == 0 ? double(cell.lo[axis]) : double(cell.hi[axis]);
      const double sign = side == 0 ? -1.0 : 1.0;
      // A plane that cuts nothing off the polygon (most of the six: the
      // build clips against one octant of a box the triangle already lies in).
      if (side == 0 ? lo[axis] >= plane : hi[axis] <= plane) continue;
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const glm::dvec3& p = poly[i];
        const glm::dvec3& q = poly[i + 1 < n ? i + 1 : 0];
        const double dp = sign * (p[axis] - plane), dq = sign * (q[axis] - plane);
        if (dp <= 0.0) next[m++] = p;
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
          glm::dvec3 x = p + (q - p) * (dp / (dp - dq));
          x[axis] = plane;  // exactly on the plane
          next[m++] = x;
        }
      }
      n = m;
      std::swap(poly, next);
      if (n > 0) {
        lo = hi = poly[0];
        for (int i = 1; i < n; ++i) {
          lo = glm::min(lo, poly[i]);
          hi = glm::max(hi, poly[i]);
        }
      }
    }
  }
  if (n == 0) return false;
  for (int i = 0; i < n; ++i) {
    lo = glm::min(lo, poly[i]);
    hi = glm::max(hi, poly[i]);
  }
  // Outward to float by one ulp beyond the rounding, then back into the cell.
  for (int k = 0; k < 3; ++k) {
    part.lo[k] = std::max(next_float_down(next_float_down(float(lo[k]))), cell.lo[k]);
    part.hi[k] = std::min(next_float_up(next_float_up(float(hi[k]))), cell.hi[k]);
  }
  return true;
}

}  // namespace octrace
