// Ray/sphere intersection and ray spawning, in fp32.
#ifndef OCTRACE_GEOMETRY_GLSL
#define OCTRACE_GEOMETRY_GLSL

const float PI = 3.14159265358979323846;
const float INF = 3.402823466e38;  // FLT_MAX: "no hit" for t

struct Ray {
  vec3 origin;
  vec3 dir;  // unit length
};

// Ray/sphere in the numerically stable form of Haines et al., "Precision
// Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7):
// the discriminant is r^2 - |l|^2 with l the vector from the centre to the
// ray's closest point (no cancellation of two large squares), and the two
// roots come from q = b + sign(b) sqrt(disc) as c/q and q (no cancellation
// of b against sqrt(disc)). `dir` is unit length, so a = 1.
//
// Returns the nearest root in (0, t_max), or INF. `skip_near` drops the near
// root: the ray starts on this sphere's surface (it was spawned there), so
// the near root is the start point itself and only the far one, if the ray
// goes inward, is a real hit. `skip_all` drops both: the ray leaves the
// sphere outward and, a sphere being convex, cannot meet it again.
float intersect_sphere(Ray ray, vec3 center, float radius, float t_max, bool skip_near, bool skip_all) {
  if (skip_all) return INF;
  vec3 f = ray.origin - center;
  float b = -dot(f, ray.dir);
  vec3 l = f + b * ray.dir;
  float r2 = radius * radius;
  float disc = r2 - dot(l, l);
  if (disc < 0.0) return INF;
  float c = dot(f, f) - r2;
  float q = b + (b >= 0.0 ? sqrt(disc) : -sqrt(disc));
  float t0 = c / q;  // c/q and q are the two roots, in either order
  float t1 = q;
  float near_t = min(t0, t1);
  float far_t = max(t0, t1);
  if (!skip_near && near_t >= 0.0 && near_t < t_max) return near_t;
  if (far_t > 0.0 && far_t < t_max) return far_t;
  return INF;
}

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
// translated scenes have). Self-hits need no offset at all: the skip_near /
// skip_all rule of intersect_sphere removes them exactly.
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

#endif
