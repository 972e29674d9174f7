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
// In two halves, so that a test can leave on a miss (disc < 0) before
// anything else (optimisation log 65: on the H200 the octree's walk 4-7%
// faster, the BVH's 1%, a missed sphere no longer running the hit's update
// and tie tests): sphere_quadratic gives the discriminant, sphere_root the
// root.
struct SphereQuadratic {
  vec3 f;
  float b;
  float r2;
  float disc;
};

SphereQuadratic sphere_quadratic(Ray ray, vec3 center, float radius) {
  SphereQuadratic s;
  s.f = ray.origin - center;
  s.b = -dot(s.f, ray.dir);
  vec3 l = s.f + s.b * ray.dir;
  s.r2 = radius * radius;
  s.disc = s.r2 - dot(l, l);
  return s;
}

// For a quadratic whose disc >= 0: the nearest root in (0, t_max), or
// INF. `skip_near` drops the near root: the ray starts on this sphere's
// surface (it was spawned there), so the near root is the start point
// itself and only the far one, if the ray goes inward, is a real hit.
// `skip_all` drops both: the ray leaves the sphere outward and, a sphere
// being convex, cannot meet it again.
float sphere_root(SphereQuadratic s, float t_max, bool skip_near, bool skip_all) {
  if (skip_all) return INF;
  float c = dot(s.f, s.f) - s.r2;
  float q = s.b + (s.b >= 0.0 ? sqrt(s.disc) : -sqrt(s.disc));
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
