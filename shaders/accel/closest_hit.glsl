// Closest hit against the scene: the one function the path tracer calls to
// find what a ray meets, as (t, primitive id, primitive kind); surface_at
// turns that into a Surface. The acceleration structure (specialization
// constant ACCEL) lives behind it: two levels, the top over spheres and mesh
// instances, and for each instance its mesh's own octree in object space,
// which the ray enters through the instance's transform. The includer
// declares `scene`, `spheres`, `sphere_materials`, `triangles`,
// `triangle_normals`, `triangle_uvs`, `instances`, `meshes`, `octree_nodes`
// and `octree_refs`, and the specialization constants HAS_SPHERES,
// HAS_TRIANGLES, HAS_VERTEX_NORMALS and HAS_TEXTURES (a kind the scene lacks
// compiles out). A new
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
  uint prim;  // primitive id (shared.h: a sphere's index, a triangle's global id); NO_PRIM for a miss
  uint kind;  // PRIM_*
  uint inst;  // triangles: the instance hit
};

const uint NO_PRIM = 0xffffffffu;

// Which instance a mesh walk is in: its index, the global id of its mesh's
// triangle 0, and where the mesh's triangles start.
struct InstanceRef {
  uint inst;
  uint first_id;
  uint first_triangle;
};

// Whether top-level id i is a sphere (spheres come first).
bool is_sphere(uint i) { return !HAS_TRIANGLES || (HAS_SPHERES && i < scene.sphere_count); }

// t_max for a test: hit.t widened by one ulp so that a primitive at exactly
// the same distance is seen; the tie then goes to the lower id. The result
// is independent of the order primitives are tested in (octree == brute force).
float widened(float t) { return uintBitsToFloat(floatBitsToUint(t) + 1u); }

// Tests sphere i and keeps it in `hit` if it is the nearest so far.
// `from_prim`: the primitive the ray was spawned on (NO_PRIM for camera
// rays); `into_from`: whether the ray enters it (see intersect_sphere).
void test_sphere(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  bool self = i == from_prim;
  GpuSphere s = spheres[i];
  float t = intersect_sphere(ray, s.center, s.radius, widened(hit.t), self && into_from, self && !into_from);
  if (t < hit.t || (t == hit.t && t != INF && i < hit.prim)) {
    hit.t = t;
    hit.prim = i;
    hit.kind = PRIM_SPHERE;
  }
}

// Tests triangle `local` of an instance's mesh against the ray in the mesh's
// object space (whose t is the world t).
void test_instance_triangle(Ray oray, RayShear osh, InstanceRef ir, uint local, uint from_prim, inout Hit hit) {
  uint id = ir.first_id + local;
  float t = intersect_triangle(oray.origin, osh, triangles[ir.first_triangle + local], widened(hit.t), id == from_prim);
  if (t < hit.t || (t == hit.t && t != INF && id < hit.prim)) {
    hit.t = t;
    hit.prim = id;
    hit.kind = PRIM_TRIANGLE;
    hit.inst = ir.inst;
  }
}

#include "accel/octree.glsl"

#define OCTREE_WALK_NAME traverse_mesh
#define OCTREE_LEAF(ref) test_instance_triangle(ray, sh, ir, ref, from_prim, hit)
#include "accel/octree_walk.glsl"
#undef OCTREE_WALK_NAME
#undef OCTREE_LEAF

// The ray in instance g's object space: the same t, the direction not renormalised.
Ray to_object(GpuInstance g, Ray ray) {
  vec4 o = vec4(ray.origin, 1.0);
  return Ray(vec3(dot(g.to_object0, o), dot(g.to_object1, o), dot(g.to_object2, o)),
             vec3(dot(g.to_object0.xyz, ray.dir), dot(g.to_object1.xyz, ray.dir), dot(g.to_object2.xyz, ray.dir)));
}

// Tests instance `inst`: its mesh's triangles (all of them for brute force,
// else its big list and its octree), in object space.
void test_instance(Ray ray, uint inst, uint from_prim, inout Hit hit) {
  GpuInstance g = instances[inst];
  GpuMesh m = meshes[g.mesh];
  Ray oray = to_object(g, ray);
  RayShear osh = ray_shear(oray.dir);
  InstanceRef ir = InstanceRef(inst, g.first_id, m.first_triangle);
  if (ACCEL == ACCEL_BRUTE) {
    for (uint k = 0; k < m.triangle_count; ++k) test_instance_triangle(oray, osh, ir, k, from_prim, hit);
    return;
  }
  for (uint j = 0; j < m.big_count; ++j) test_instance_triangle(oray, osh, ir, octree_refs[m.first_ref + j], from_prim, hit);
  traverse_mesh(m.root, oray, osh, from_prim, false, ir, hit);
}

// Tests top-level primitive i: a sphere or a mesh instance.
void test_primitive(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  if (is_sphere(i)) test_sphere(ray, i, from_prim, into_from, hit);
  else test_instance(ray, i - scene.sphere_count, from_prim, hit);
}

#define OCTREE_WALK_NAME traverse_top
#define OCTREE_LEAF(ref) test_primitive(ray, ref, from_prim, into_from, hit)
#include "accel/octree_walk.glsl"
#undef OCTREE_WALK_NAME
#undef OCTREE_LEAF

bool closest_hit(Ray ray, uint from_prim, bool into_from, out Hit hit) {
  hit.t = INF;
  hit.prim = NO_PRIM;
  hit.kind = PRIM_SPHERE;
  hit.inst = 0u;
  if (ACCEL == ACCEL_BRUTE) {
    if (HAS_SPHERES)
      for (uint i = 0; i < scene.sphere_count; ++i) test_sphere(ray, i, from_prim, into_from, hit);
    if (HAS_TRIANGLES)
      for (uint i = 0; i < scene.instance_count; ++i) test_instance(ray, i, from_prim, hit);
    return hit.prim != NO_PRIM;
  }

  // Primitives too large for the octree's cells are tested first.
  for (uint i = 0; i < scene.big_count; ++i) test_primitive(ray, octree_refs[i], from_prim, into_from, hit);
  RayShear no_shear;
  traverse_top(0u, ray, no_shear, from_prim, into_from, InstanceRef(0u, 0u, 0u), hit);
  return hit.prim != NO_PRIM;
}

// The surface at a hit that closest_hit returned.
Surface surface_at(Ray ray, Hit hit) {
  if (!HAS_TRIANGLES || (HAS_SPHERES && hit.kind == PRIM_SPHERE))
    return sphere_surface(ray, hit.t, spheres[hit.prim], sphere_materials[hit.prim]);
  GpuInstance g = instances[hit.inst];
  uint tri = meshes[g.mesh].first_triangle + (hit.prim - g.first_id);
  return triangle_surface(ray, to_object(g, ray), hit.t, tri, g);
}

#endif
