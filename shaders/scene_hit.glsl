// Closest hit against the scene. The one function the rest of the path tracer
// calls to find what a ray meets; the acceleration structure lives behind it.
// Expects the `spheres` buffer and `params` to be declared by the includer.
#ifndef OCTRACE_SCENE_HIT_GLSL
#define OCTRACE_SCENE_HIT_GLSL

#include "geometry.glsl"

struct Hit {
  float t;
  uint sphere;
};

const uint NO_SPHERE = 0xffffffffu;

// `from_sphere`: the sphere the ray was spawned on (NO_SPHERE for camera
// rays); `into_from`: whether the ray enters that sphere (see intersect_sphere).
bool closest_hit(Ray ray, uint from_sphere, bool into_from, out Hit hit) {
  hit.t = INF;
  hit.sphere = NO_SPHERE;
  for (uint i = 0; i < params.sphere_count; ++i) {
    bool self = i == from_sphere;
    GpuSphere s = spheres[i];
    float t = intersect_sphere(ray, s.center, s.radius, hit.t, self && into_from, self && !into_from);
    if (t < hit.t) {
      hit.t = t;
      hit.sphere = i;
    }
  }
  return hit.sphere != NO_SPHERE;
}

#endif
