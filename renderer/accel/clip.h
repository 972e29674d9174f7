// The part of a triangle inside a box, for builds that clip references to
// cells (split clipping: ClipFn in accel/octree.h).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "accel/aabb.h"

namespace octrace {

// Whether triangle (a, b, c) reaches into the closed box `cell`; if it does,
// `part` receives a box that holds the triangle's part inside the cell (a few
// ulps larger than exact, never outside the cell). The polygon is clipped
// against the cell's six planes (Sutherland and Hodgman 1974, "Reentrant
// polygon clipping") in double, so a thin triangle loses nothing.
bool clip_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& cell, Aabb& part);

// Whether the surface of the sphere with centre `c` and radius `r` (not its
// ball) reaches into the closed box `cell`; if it does, `part` receives a
// box that holds the surface's points in the cell (never outside the cell).
// A cell wholly inside the ball holds none: on a dense field of overlapping
// spheres, a sphere's visible part (accel/hidden_parts.h) is a column whose
// middle lies inside the ball, so the octree's cells separate its top cap
// from its bottom one (optimisation log 126). How: a point p of the surface
// in the cell has (p_a - c_a)^2 = r^2 - (the sum over the other two axes),
// which the cell bounds from below and above, so |p_a - c_a| lies in an
// interval and p_a in at most two, intersected with the cell's extent; two
// rounds, each on the box the last left. In double, with a margin of 2^-19
// of the largest coordinate (about 2e-6 of it) on the cell and the radius,
// so that a point rounding puts a little off the surface or the cell still
// counts; rounded outward to float.
bool clip_sphere_surface(const glm::vec3& c, float r, const Aabb& cell, Aabb& part);

// Octant k of `box` split at `mid` (an axis whose mid is not finite is not
// split: its whole extent is the low half; bit a of k set: the high side of
// axis a).
Aabb octant_cell(const Aabb& box, const glm::vec3& mid, uint32_t k);

// The parts of triangle (a, b, c) in the octants of `box` split at `mid` (an
// axis whose mid is not finite is not split: its whole extent is the low
// half; octant k is on the high side of axis a where bit a of k is set),
// for the octants in `candidates` (bit k: octant k): parts[k] receives, for
// each octant k it reaches, what clip_triangle(a, b, c, that octant's cell,
// parts[k]) would give, bit for bit; returns the octants reached. One
// clip per side of each axis serves every octant on that side (the
// octree's splits: optimisation log 108), where clip_triangle per octant
// clips the triangle through every plane of each.
uint32_t clip_triangle_octants(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& box,
                               const glm::vec3& mid, uint32_t candidates, Aabb parts[8]);

// The float one ulp below / above a finite float f: std::nextafter(f, -inf)
// and std::nextafter(f, +inf), by its bits (libm's call was 7% of the
// engine's octree build: optimisation log 101). Zero of either sign steps
// to the smallest subnormal; the largest finite float steps to infinity.
float next_float_down(float f);
float next_float_up(float f);

}  // namespace octrace
