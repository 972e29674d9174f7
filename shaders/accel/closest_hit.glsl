// Closest hit against the scene: the one function the path tracer calls to
// find what a ray meets, as (t, primitive id, primitive kind); surface_at
// turns that into a Surface. The acceleration structure (specialization
// constant ACCEL) lives behind it. The includer declares `scene`, `spheres`,
// `sphere_materials`, `triangles`, `triangle_normals`, `octree_nodes` and
// `octree_refs`, and the specialization constants HAS_SPHERES, HAS_TRIANGLES
// and HAS_VERTEX_NORMALS (a kind the scene lacks compiles out). A new
// primitive kind adds its test to test_primitive and its surface to
// surface_at; nothing else here or in the integrator changes.
#ifndef OCTRACE_SCENE_HIT_GLSL
#define OCTRACE_SCENE_HIT_GLSL

#include "geometry/sphere.glsl"
#include "geometry/surface.glsl"
#include "geometry/triangle.glsl"

layout(constant_id = SPEC_ACCEL) const uint ACCEL = ACCEL_OCTREE;

struct Hit {
  float t;
  uint prim;  // primitive id (for spheres, the sphere index); NO_PRIM for a miss
  uint kind;  // PRIM_*
};

const uint NO_PRIM = 0xffffffffu;

// Whether global primitive id i is a sphere (spheres come first).
bool is_sphere(uint i) { return !HAS_TRIANGLES || (HAS_SPHERES && i < scene.sphere_count); }

// Tests primitive i and keeps it in `hit` if it is the nearest so far.
// `from_prim`: the primitive the ray was spawned on (NO_PRIM for camera
// rays); `into_from`: whether the ray enters it (see intersect_sphere).
// `sh`: the ray's shear for the triangle test (ray_shear).
void test_primitive(Ray ray, RayShear sh, uint i, uint from_prim, bool into_from, inout Hit hit) {
  bool self = i == from_prim;
  // t_max is hit.t widened by one ulp so that a primitive at exactly the same
  // distance is seen; the tie then goes to the lower id. The result is
  // independent of the order primitives are tested in (octree == brute force).
  float t_max = uintBitsToFloat(floatBitsToUint(hit.t) + 1u);
  float t;
  uint kind;
  if (is_sphere(i)) {
    GpuSphere s = spheres[i];
    t = intersect_sphere(ray, s.center, s.radius, t_max, self && into_from, self && !into_from);
    kind = PRIM_SPHERE;
  } else {
    t = intersect_triangle(ray.origin, sh, triangles[i - scene.sphere_count], t_max, self);
    kind = PRIM_TRIANGLE;
  }
  if (t < hit.t || (t == hit.t && t != INF && i < hit.prim)) {
    hit.t = t;
    hit.prim = i;
    hit.kind = kind;
  }
}

#include "accel/octree.glsl"

bool closest_hit(Ray ray, uint from_prim, bool into_from, out Hit hit) {
  hit.t = INF;
  hit.prim = NO_PRIM;
  hit.kind = PRIM_SPHERE;
  RayShear sh;
  if (HAS_TRIANGLES) sh = ray_shear(ray.dir);
  if (ACCEL == ACCEL_BRUTE) {
    uint count = (HAS_SPHERES ? scene.sphere_count : 0u) + (HAS_TRIANGLES ? scene.triangle_count : 0u);
    for (uint i = 0; i < count; ++i) test_primitive(ray, sh, i, from_prim, into_from, hit);
    return hit.prim != NO_PRIM;
  }

  // Primitives too large for the octree's cells are tested first.
  for (uint i = 0; i < scene.big_count; ++i) test_primitive(ray, sh, octree_refs[i], from_prim, into_from, hit);
  traverse_octree(ray, sh, from_prim, into_from, hit);
  return hit.prim != NO_PRIM;
}


// The surface at a hit that closest_hit returned.
Surface surface_at(Ray ray, Hit hit) {
  if (!HAS_TRIANGLES || (HAS_SPHERES && hit.kind == PRIM_SPHERE))
    return sphere_surface(ray, hit.t, spheres[hit.prim], sphere_materials[hit.prim]);
  return triangle_surface(ray, hit.t, hit.prim - scene.sphere_count);
}

#endif
