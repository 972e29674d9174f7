// Warps from uniform numbers to the distributions the book's materials and
// lens draw from. Each takes a fixed count of numbers, so a pipeline that
// compiles an effect out draws the same numbers for the rest.
#ifndef OCTRACE_WARP_GLSL
#define OCTRACE_WARP_GLSL

#include "geometry/ray.glsl"
#include "shared/rng.h"

// A direction uniform on the unit sphere (z uniform in [-1,1], phi uniform):
// the distribution the book's rejection-sampled random_unit_vector has, from
// a fixed count of two numbers.
vec3 random_unit_vector(inout Rng rng) {
  float z = 1.0 - 2.0 * rng_next(rng);
  float phi = 2.0 * PI * rng_next(rng);
  float r = sqrt(max(0.0, 1.0 - z * z));
  return vec3(r * cos(phi), r * sin(phi), z);
}

// A point uniform in the unit disc (polar, with r = sqrt(u)).
vec2 random_in_unit_disk(inout Rng rng) {
  float r = sqrt(rng_next(rng));
  float phi = 2.0 * PI * rng_next(rng);
  return r * vec2(cos(phi), sin(phi));
}

#endif
