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
  if (!skip_near && near_t > 0.0 && near_t < t_max) return near_t;
  if (far_t > 0.0 && far_t < t_max) return far_t;
  return INF;
}

// Moves a point off a surface along the geometric normal `n` (pointing to the
// side the new ray leaves into), after Wächter & Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6). Far from
// the origin the offset is a fixed number of ulps of each coordinate (integer
// steps on the float's bit pattern), so it grows with the point's magnitude as
// the rounding error of the hit point does; near the origin, where ulps
// vanish, a small absolute offset takes over. 256 ulps bound the error of a hit
// point computed as origin + t*dir plus the sphere test's error in t (a few
// ulps of |origin - centre|) for spheres up to ~100x the point's magnitude;
// for larger spheres (the ground) the skip_near/skip_all rule of
// intersect_sphere removes self-hits exactly.
vec3 offset_ray_origin(vec3 p, vec3 n) {
  const float ORIGIN_REGION = 1.0 / 32.0;
  const float ABS_SCALE = 1.0 / 65536.0;
  const float ULP_SCALE = 256.0;
  ivec3 steps = ivec3(ULP_SCALE * n);
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + ivec3(p.x < 0.0 ? -steps.x : steps.x,
                                                        p.y < 0.0 ? -steps.y : steps.y,
                                                        p.z < 0.0 ? -steps.z : steps.z));
  return vec3(abs(p.x) < ORIGIN_REGION ? p.x + ABS_SCALE * n.x : moved.x,
              abs(p.y) < ORIGIN_REGION ? p.y + ABS_SCALE * n.y : moved.y,
              abs(p.z) < ORIGIN_REGION ? p.z + ABS_SCALE * n.z : moved.z);
}

// Normalises, or returns `fallback` for a vector too short to have a direction.
vec3 safe_normalize(vec3 v, vec3 fallback) {
  float len2 = dot(v, v);
  return len2 > 1e-30 ? v * inversesqrt(len2) : fallback;
}

#endif
