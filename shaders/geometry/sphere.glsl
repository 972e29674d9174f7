// Spheres: ray/sphere intersection and the surface at a hit, in fp32.
#ifndef OCTRACE_SPHERE_GLSL
#define OCTRACE_SPHERE_GLSL

#include "geometry/ray.glsl"
#include "geometry/surface.glsl"

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

// The surface of sphere `s` at distance t along the ray. The outward normal
// is the unit vector from the centre (the ray's reverse for a point at the
// centre, which only a sphere of radius 0 has). Spheres carry no texture
// coordinates yet: uv is 0.
Surface sphere_surface(Ray ray, float t, GpuSphere s, uint material) {
  vec3 p = ray.origin + t * ray.dir;
  vec3 outward = safe_normalize(p - s.center, -ray.dir);
  return Surface(p, outward, outward, material, vec2(0.0), vec3(0.0), vec3(0.0));
}

#endif
