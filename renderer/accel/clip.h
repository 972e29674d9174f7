// The part of a triangle inside a box, for builds that clip references to
// cells (split clipping: ClipFn in accel/octree.h).
#pragma once

#include <glm/vec3.hpp>

#include "accel/aabb.h"

namespace octrace {

// Whether triangle (a, b, c) reaches into the closed box `cell`; if it does,
// `part` receives a box that holds the triangle's part inside the cell (a few
// ulps larger than exact, never outside the cell). The polygon is clipped
// against the cell's six planes (Sutherland and Hodgman 1974, "Reentrant
// polygon clipping") in double, so a thin triangle loses nothing.
bool clip_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Aabb& cell, Aabb& part);

// The float one ulp below / above a finite float f: std::nextafter(f, -inf)
// and std::nextafter(f, +inf), by its bits (libm's call was 7% of the
// engine's octree build: optimisation log 101). Zero of either sign steps
// to the smallest subnormal; the largest finite float steps to infinity.
float next_float_down(float f);
float next_float_up(float f);

}  // namespace octrace
