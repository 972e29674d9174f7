// Axis-aligned boxes: what an acceleration structure knows of a primitive.
#pragma once

#include <algorithm>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace octrace {

struct Aabb {
  glm::vec3 lo{std::numeric_limits<float>::max()};  // empty by default: lo > hi
  glm::vec3 hi{-std::numeric_limits<float>::max()};

  void extend(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  // The longest side: a box's size for the "big primitive" rule.
  float max_extent() const { return empty() ? 0.0f : std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}); }
};

}  // namespace octrace
