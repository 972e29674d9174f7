#include "accel/clip.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

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

namespace {

// A triangle being clipped (Sutherland and Hodgman 1974), in double: at most
// 3 + 6 vertices after 6 planes, and their bounds.
struct Polygon {
  static constexpr int kMax = 9;
  glm::dvec3 v[kMax];
  int n = 0;
  glm::dvec3 lo, hi;
};

Polygon triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  Polygon p;
  p.v[0] = glm::dvec3(a);
  p.v[1] = glm::dvec3(b);
  p.v[2] = glm::dvec3(c);
  p.n = 3;
  p.lo = glm::min(p.v[0], glm::min(p.v[1], p.v[2]));
  p.hi = glm::max(p.v[0], glm::max(p.v[1], p.v[2]));
  return p;
}

// Whether the bounds [lo, hi] lie outside `cell` on some axis.
bool misses(const glm::dvec3& lo, const glm::dvec3& hi, const Aabb& cell) {
  for (int axis = 0; axis < 3; ++axis)
    if (lo[axis] > double(cell.hi[axis]) || hi[axis] < double(cell.lo[axis])) return true;
  return false;
}

// Whether the plane `plane` on `axis` cuts anything off `p`, which keeps
// the side above it (side 0: a cell's low face) or below it (side 1: its
// high face). Most of a cell's six planes cut nothing: the build clips
// against one octant of a box the triangle already lies in.
bool cuts(const Polygon& p, int axis, int side, double plane) {
  return side == 0 ? p.lo[axis] < plane : p.hi[axis] > plane;
}

// `out` = `p` cut by that plane (faces included), with its bounds.
void cut(const Polygon& p, Polygon& out, int axis, int side, double plane) {
  const double sign = side == 0 ? -1.0 : 1.0;
  int m = 0;
  for (int i = 0; i < p.n; ++i) {
    const glm::dvec3& a = p.v[i];
    const glm::dvec3& b = p.v[i + 1 < p.n ? i + 1 : 0];
    const double da = sign * (a[axis] - plane), db = sign * (b[axis] - plane);
    if (da <= 0.0) out.v[m++] = a;
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      glm::dvec3 x = a + (b - a) * (da / (da - db));
      x[axis] = plane;  // exactly on the plane
      out.v[m++] = x;
    }
  }
  out.n = m;
  if (m > 0) {
    out.lo = out.hi = out.v[0];
    for (int i = 1; i < m; ++i) {
      out.lo = glm::min(out.lo, out.v[i]);
      out.hi = glm::max(out.hi, out.v[i]);
    }
  }
}

// `p` cut to the cell's two planes on `axis`, low face first: `p` itself
// where neither cuts, else `a` or `b` (scratch, neither of them `p`).
const Polygon& clip_axis(const Polygon& p, Polygon& a, Polygon& b, int axis, const Aabb& cell) {
  const double lo = double(cell.lo[axis]), hi = double(cell.hi[axis]);
  const Polygon* q = &p;
  if (cuts(*q, axis, 0, lo)) {
    cut(*q, a, axis, 0, lo);
    q = &a;
  }
  if (q->n > 0 && cuts(*q, axis, 1, hi)) {
    Polygon& out = q == &a ? b : a;
    cut(*q, out, axis, 1, hi);
    q = &out;
  }
  return *q;
}

// The box of what is left of `p` (n > 0) in `cell`: outward to float by one
// ulp beyond the rounding, then back into the cell.
Aabb part_box(const Polygon& p, const Aabb& cell) {
  Aabb part;
  for (int k = 0; k < 3; ++k) {
    part.lo[k] = std::max(next_float_down(next_float_down(float(p.lo[k]))), cell.lo[k]);
    part.hi[k] = std::min(next_float_up(next_float_up(float(p.hi[k]))), cell.hi[k]);
  }
  return part;
}

// clip_triangle_octants below, from `axis` on: `p` is the triangle cut to
// the planes of the axes before it, on the sides `octant` names.
struct OctantClip {
  glm::dvec3 lo, hi;  // the whole triangle's bounds
  const Aabb& box;
  const glm::vec3& mid;
  uint32_t candidates;
  Aabb* parts;
  uint32_t reached = 0;

  void descend(const Polygon& p, int axis, uint32_t octant) {
    if (axis == 3) {
      const Aabb c = octant_cell(box, mid, octant);
      if (misses(lo, hi, c)) return;  // as clip_triangle rejects it before clipping
      parts[octant] = part_box(p, c);
      reached |= 1u << octant;
      return;
    }
    const uint32_t prefix = (1u << (axis + 1)) - 1u;
    for (uint32_t side = 0; side < 2; ++side) {
      const uint32_t next = octant | (side << axis);
      bool wanted = false;
      for (uint32_t s = candidates; s != 0; s &= s - 1)
        wanted |= (uint32_t(std::countr_zero(s)) & prefix) == next;
      if (!wanted) continue;
      Polygon a, b;
      const Polygon& q = clip_axis(p, a, b, axis, octant_cell(box, mid, next));
      if (q.n > 0) descend(q, axis + 1, next);
    }
  }
};

}  // namespace

bool clip_sphere_surface(const glm::vec3& c, float r, const Aabb& cell, Aabb& part) {
  const glm::dvec3 center(c);
  double scale = double(r);
  for (int a = 0; a < 3; ++a)
    scale = std::max({scale, std::abs(center[a]), std::abs(double(cell.lo[a])), std::abs(double(cell.hi[a]))});
  const double eps = std::ldexp(scale, -19);
  const double outer2 = (double(r) + eps) * (double(r) + eps);
  const double inner = std::max(0.0, double(r) - eps);
  const double inner2 = inner * inner;
  glm::dvec3 lo = glm::dvec3(cell.lo) - eps, hi = glm::dvec3(cell.hi) + eps;
  for (int round = 0; round < 2; ++round) {
    // Per axis, the least and the greatest (p_a - c_a)^2 over the box.
    double nearest[3], farthest[3];
    for (int a = 0; a < 3; ++a) {
      const double below = lo[a] - center[a], above = hi[a] - center[a];
      nearest[a] = below > 0.0 ? below * below : above < 0.0 ? above * above : 0.0;
      farthest[a] = std::max(below * below, above * above);
    }
    const double near = nearest[0] + nearest[1] + nearest[2];
    const double far = farthest[0] + farthest[1] + farthest[2];
    // The ball misses the box, or the box lies inside the ball.
    if (near > outer2 || far < inner2) return false;
    for (int a = 0; a < 3; ++a) {
      const double most = std::sqrt(std::max(0.0, outer2 - (near - nearest[a])));
      const double least = std::sqrt(std::max(0.0, inner2 - (far - farthest[a])));
      double l = std::numeric_limits<double>::infinity(), h = -l;
      const double pieces[2][2] = {{center[a] - most, center[a] - least}, {center[a] + least, center[a] + most}};
      for (const auto& piece : pieces) {
        const double p0 = std::max(lo[a], piece[0]), p1 = std::min(hi[a], piece[1]);
        if (p0 <= p1) {
          l = std::min(l, p0);
          h = std::max(h, p1);
        }
      }
      if (!(l <= h)) return false;
      lo[a] = l;
      hi[a] = h;
    }
  }
  // Within the cell: a part the margin put just outside it keeps the face
  // it lies against.
  for (int k = 0; k < 3; ++k) {
    part.lo[k] = std::clamp(next_float_down(float(lo[k])), cell.lo[k], cell.hi[k]);
    part.hi[k] = std::clamp(next_float_up(float(hi[k])), cell.lo[k], cell.hi[k]);
  }
  return true;
}

Aabb octant_cell(const Aabb& box, const glm::vec3& mid, uint32_t k) {
  Aabb cell = box;
  for (int a = 0; a < 3; ++a) {
    if (!(mid[a] < std::numeric_limits<float>::infinity())) continue;
    if ((k >> a) & 1) cell.lo[a] = mid[a];
    else cell.hi[a] = mid[a];
  }
  return cell;
}

bool clip_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& cell, Aabb& part) {
  const Polygon t = triangle(a, b, c);
  if (misses(t.lo, t.hi, cell)) return false;
  Polygon scratch[3][2];  // a pair per axis, so that none is the polygon it cuts
  const Polygon* p = &t;
  for (int axis = 0; axis < 3 && p->n > 0; ++axis) p = &clip_axis(*p, scratch[axis][0], scratch[axis][1], axis, cell);
  if (p->n == 0) return false;
  part = part_box(*p, cell);
  return true;
}

uint32_t clip_triangle_octants(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& box,
                               const glm::vec3& mid, uint32_t candidates, Aabb parts[8]) {
  const Polygon p = triangle(a, b, c);
  OctantClip clip{p.lo, p.hi, box, mid, candidates & 0xFFu, parts};
  clip.descend(p, 0, 0);
  return clip.reached;
}

}  // namespace octrace
