// Closest hit against the scene: the one function the path tracer calls to
// find what a ray meets, as (t, primitive id, primitive kind); surface_at
// turns that into a Surface. The acceleration structure (specialization
// constant ACCEL) lives behind it. The includer declares `scene`, `spheres`,
// `sphere_materials`, `octree_nodes` and `octree_refs`. A new primitive kind
// adds its test to test_primitive and its surface to surface_at; nothing
// else here or in the integrator changes.
#ifndef OCTRACE_SCENE_HIT_GLSL
#define OCTRACE_SCENE_HIT_GLSL

#include "geometry/sphere.glsl"
#include "geometry/surface.glsl"

layout(constant_id = SPEC_ACCEL) const uint ACCEL = ACCEL_OCTREE;

struct Hit {
  float t;
  uint prim;  // primitive id (for spheres, the sphere index); NO_PRIM for a miss
  uint kind;  // PRIM_*
};

const uint NO_PRIM = 0xffffffffu;

// Tests primitive i and keeps it in `hit` if it is the nearest so far.
// `from_prim`: the primitive the ray was spawned on (NO_PRIM for camera
// rays); `into_from`: whether the ray enters it (see intersect_sphere).
void test_primitive(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  bool self = i == from_prim;
  GpuSphere s = spheres[i];
  // t_max is hit.t widened by one ulp so that a sphere at exactly the same
  // distance is seen; the tie then goes to the lower index. The result is
  // independent of the order spheres are tested in (octree == brute force).
  float t = intersect_sphere(ray, s.center, s.radius, uintBitsToFloat(floatBitsToUint(hit.t) + 1u),
                             self && into_from, self && !into_from);
  if (t < hit.t || (t == hit.t && t != INF && i < hit.prim)) {
    hit.t = t;
    hit.prim = i;
    hit.kind = PRIM_SPHERE;
  }
}

#include "accel/octree.glsl"

bool closest_hit(Ray ray, uint from_prim, bool into_from, out Hit hit) {
  hit.t = INF;
  hit.prim = NO_PRIM;
  hit.kind = PRIM_SPHERE;
  if (ACCEL == ACCEL_BRUTE) {
    for (uint i = 0; i < scene.sphere_count; ++i) test_primitive(ray, i, from_prim, into_from, hit);
    return hit.prim != NO_PRIM;
  }

  // Primitives too large for the octree's cells are tested first.
  for (uint i = 0; i < scene.big_count; ++i) test_primitive(ray, octree_refs[i], from_prim, into_from, hit);
  traverse_octree(ray, from_prim, into_from, hit);
  return hit.prim != NO_PRIM;
}


// The surface at a hit that closest_hit returned.
Surface surface_at(Ray ray, Hit hit) {
  return sphere_surface(ray, hit.t, spheres[hit.prim], sphere_materials[hit.prim]);
}

#endif
