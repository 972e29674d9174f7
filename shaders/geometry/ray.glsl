// Rays and what every primitive shares: spawning a ray off a surface without
// meeting it again, and normalising without NaN. fp32 in every precision.
#ifndef OCTRACE_RAY_GLSL
#define OCTRACE_RAY_GLSL

const float PI = 3.14159265358979323846;
const float INF = 3.402823466e38;  // FLT_MAX: "no hit" for t

struct Ray {
  vec3 origin;
  vec3 dir;  // unit length
};

// Moves a hit point off its surface along the geometric normal `n` (pointing
// to the side the new ray leaves into) by more than the point's rounding
// error, so that a surface through the same point (a coincident or touching
// sphere) is not met at a distance that is only rounding. In the spirit of
// Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection"
// (Ray Tracing Gems, ch. 6), with the bound taken from the ray instead of a
// fixed ulp count per coordinate: p = origin + t*dir is rounded to a few ulps
// of max(|origin|, |p|) <= max|p_i| + t, and the stable sphere test's t (Haines)
// is off by a few ulps of t, so OFFSET_ULPS ulps of (max|p_i| + t) cover both
// however far the ray came (a fixed count of p's own ulps does not: a camera
// 20x farther away than |p| lost paths between coincident spheres) and stay
// small where p is small (a scene of r = 1e-4 spheres near the origin) or far
// from the origin (at 1e5 the offset is 16 * 1.2e-7 * 1e5 = 0.2 units where
// W&B's 256 ulps per coordinate jumped 2 units, across the contact gaps the
// translated scenes have). Self-hits need no offset at all: each primitive's own rule removes
// them exactly (for spheres the skip_near / skip_all rule of sphere_root).
vec3 offset_ray_origin(vec3 p, vec3 n, float t) {
  const float OFFSET_ULPS = 8.0;
  float scale = max(max(abs(p.x), abs(p.y)), abs(p.z)) + t;
  return p + (OFFSET_ULPS * 1.1920929e-7 * scale) * n;
}

// Normalises, or returns `fallback` for a vector too short to have a direction.
vec3 safe_normalize(vec3 v, vec3 fallback) {
  float len2 = dot(v, v);
  return len2 > 1e-30 ? v * inversesqrt(len2) : fallback;
}

// 1/dir without infinities: a component of +0 or -0 becomes +-2^64, so a
// slab distance (plane - origin) * inv is never 0 * inf = NaN; it is huge
// with the sign of (plane - origin), or 0 when the origin lies on the plane,
// and both keep the slab test right (the ray runs parallel inside or outside
// the slab). A power of two, so that origin * inv is exact (the fused slab
// test, accel/octree.glsl).
vec3 safe_inverse(vec3 d) {
  const float BIG = 18446744073709551616.0;  // 2^64
  return vec3(d.x == 0.0 ? (floatBitsToUint(d.x) != 0u ? -BIG : BIG) : 1.0 / d.x,
              d.y == 0.0 ? (floatBitsToUint(d.y) != 0u ? -BIG : BIG) : 1.0 / d.y,
              d.z == 0.0 ? (floatBitsToUint(d.z) != 0u ? -BIG : BIG) : 1.0 / d.z);
}

#endif
