// Closest hit against the scene: the one function the path tracer calls to
// find what a ray meets, as (t, primitive id, primitive kind); surface_at
// turns that into a Surface. The acceleration structure (specialization
// constant ACCEL) lives behind it: two levels, the top over spheres and mesh
// instances, and for each instance its mesh's own octree in object space,
// which the ray enters through the instance's transform. The includer
// declares `scene`, `instances` and `meshes`, includes
// shared/scene_buffers.glsl (sphere_at, triangle_at, node_at, ref_at,
// material_at, ...: the big arrays, in one buffer or split over several),
// and declares the specialization constants HAS_SPHERES,
// HAS_TRIANGLES, HAS_VERTEX_NORMALS, HAS_TEXTURES, HAS_ALPHA and
// HAS_SINGLE_SIDED (a kind the
// scene lacks compiles out), and for the alpha test `textures`,
// `texels` and `texture_transforms`. A new
// primitive kind adds its test to test_primitive and its surface to
// surface_at; nothing else here or in the integrator changes.
#ifndef OCTRACE_SCENE_HIT_GLSL
#define OCTRACE_SCENE_HIT_GLSL

#include "geometry/sphere.glsl"
#include "geometry/surface.glsl"
#include "geometry/triangle.glsl"
#include "shading/texture.glsl"

layout(constant_id = SPEC_ACCEL) const uint ACCEL = ACCEL_OCTREE;

struct Hit {
  float t;
  uint prim;  // primitive id (shared.h: a sphere's index, a triangle's global id); NO_PRIM for a miss
  uint kind;  // PRIM_*
  uint inst;  // triangles: the instance hit
};

const uint NO_PRIM = 0xffffffffu;

// Whether every lane of a subgroup walks the same ray and the octree walks
// split each leaf's tests and each node step's child box tests among them
// (path_trace.comp's subgroup stage);
// the includer may define it, as a constant expression, before this file.
#ifndef SPLIT_LEAVES
#define SPLIT_LEAVES false
#endif

// After a leaf whose tests the subgroup's lanes split (SPLIT_LEAVES): the
// nearest of their hits, on every lane. Each lane kept the nearest of its
// share, by the tie rule below (the nearer, at exactly the same distance the
// lower id), which orders hits as (t, prim) and does not depend on the order
// of the tests: the minimum over the lanes is the hit one lane testing them
// all would keep. The lanes holding it hold the same hit, kind and
// instance too (a lane replaces the hit it came in with only by one before
// it in that order, and within an instance an id names one primitive), so
// the minimum of those is theirs. The includer enables
// GL_KHR_shader_subgroup_arithmetic (and, for the split node step in
// accel/octree_descend.glsl, _ballot and _shuffle).
void agree_on_hit(inout Hit hit) {
  const float t = subgroupMin(hit.t);
  const uint prim = subgroupMin(hit.t == t ? hit.prim : NO_PRIM);
  const bool holds = hit.t == t && hit.prim == prim;
  hit.kind = subgroupMin(holds ? hit.kind : 0xffffffffu);
  hit.inst = subgroupMin(holds ? hit.inst : 0xffffffffu);
  hit.t = t;
  hit.prim = prim;
}

// --walk-stats (RenderStats.walk, shared.h WALK_*): this invocation's counts
// of what the walks did since path_trace.comp last added them to the stats
// buffer; with WALK_STATS off (the default) the counting compiles out.
layout(constant_id = SPEC_WALK_STATS) const bool WALK_STATS = false;
uint walk_queries = 0u, walk_nodes = 0u, walk_leaves = 0u, walk_boxes = 0u, walk_primitives = 0u,
     walk_instances = 0u, walk_query_slots = 0u, walk_node_slots = 0u, walk_primitive_slots = 0u;
// At a step counted with it (a query started, a node expanded, a primitive
// tested): one of the subgroup's lanes that run the step adds the subgroup's
// size, so that the step's count over these slots is the share of the
// subgroup's lanes busy there (shared.h, WALK_*_SLOTS). On a GPU the lanes
// that run it are those converged there; on llvmpipe, those of the 8-wide
// vector whose paths and walks have not ended.
uint walk_slots() { return subgroupElect() ? gl_SubgroupSize : 0u; }

// Which instance a mesh walk is in: its index, the global id of its mesh's
// triangle 0, and where the mesh's triangles start.
struct InstanceRef {
  uint inst;
  uint first_id;
  uint first_triangle;
};

// Whether top-level id i is a sphere (spheres come first).
bool is_sphere(uint i) { return !HAS_TRIANGLES || (HAS_SPHERES && i < scene.sphere_count); }

// Whether the spheres are in the top-level BVH's order (shared.h): only in
// scenes of spheres alone, so every top-level id is a sphere.
layout(constant_id = SPEC_SPHERES_IN_TREE_ORDER) const bool SPHERES_IN_TREE_ORDER = false;

// The top-level id that reference k of a leaf names: k itself where the
// spheres are in the tree's order.
uint top_ref_at(uint k) { return SPHERES_IN_TREE_ORDER ? k : ref_at(k); }

// Sphere i's index in the scene, the order exact ties go by: read only on a tie.
uint scene_sphere_index(uint i) { return SPHERES_IN_TREE_ORDER ? ref_at(i) : i; }

// t_max for a test: hit.t widened by one ulp so that a primitive at exactly
// the same distance is seen; the tie then goes to the lower id. The result
// is independent of the order primitives are tested in (octree == brute force).
float widened(float t) { return uintBitsToFloat(floatBitsToUint(t) + 1u); }

// Tests sphere i and keeps it in `hit` if it is the nearest so far (an
// exact tie: the lower index in the scene). A miss (a negative
// discriminant) leaves before anything else.
// `from_prim`: the primitive the ray was spawned on (NO_PRIM for camera
// rays); `into_from`: whether the ray enters it (see sphere_root).
void test_sphere(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  if (WALK_STATS) {
    ++walk_primitives;
    walk_primitive_slots += walk_slots();
  }
  GpuSphere s = sphere_at(i);
  SphereQuadratic sq = sphere_quadratic(ray, s.center, s.radius);
  if (sq.disc < 0.0) return;
  bool self = i == from_prim;
  float t = sphere_root(sq, widened(hit.t), self && into_from, self && !into_from);
  if (t < hit.t || (t == hit.t && t != INF && scene_sphere_index(i) < scene_sphere_index(hit.prim))) {
    hit.t = t;
    hit.prim = i;
    hit.kind = PRIM_SPHERE;
  }
}

// The key of BLEND's stochastic cut-out for the ray being traced: the
// integrator sets it before each closest_hit from (seed, pixel, sample,
// bounce | ALPHA_STREAM) (shared.h). 0 where no alpha is rendered.
uint alpha_key = 0u;

// glTF's alpha (3.9.6; scene/scene.h): whether the point at barycentrics b
// of triangle `tri` (index `i` in the triangle array, global id `id`) is cut
// out, so that the ray passes through it. alpha = the material's alpha x its
// base colour texture's alpha at the point's uv (through the slot's uv
// transform, as shading samples it). MASK: cut out where alpha < cutoff.
// BLEND: a stochastic cut-out, cut out where a uniform number u in [0, 1)
// is >= alpha, so a point is seen with probability alpha (its coverage:
// unbiased on average over samples). u hashes the ray's key with the
// triangle's id (pcg4d): it depends on neither the order the traversal tests
// triangles in (octree == brute force) nor on any random stream, and a ray
// that meets the same triangle twice decides the same way both times.
bool alpha_cut(GpuTriangle tri, uint i, uint id, vec3 b) {
  uint mode = material_at(tri.material).alpha_mode;
  if (mode == ALPHA_OPAQUE) return false;
  float alpha = material_at(tri.material).alpha;
  uint tex = material_at(tri.material).base_color_texture;
  if (HAS_TEXTURES && tex != NO_TEXTURE && scene.triangle_uvs != 0u) {
    GpuTriangleUvs u = triangle_uvs_at(i);
    vec2 uv = b.x * u.uv0 + b.y * u.uv1 + b.z * u.uv2;
    GpuUvTransform x = texture_transforms[tri.material * TEXTURE_SLOTS + TEXTURE_SLOT_BASE_COLOR];
    alpha *= sample_texture_alpha(tex, x.x_axis * uv.x + x.y_axis * uv.y + x.offset);
  }
  if (mode == ALPHA_MASK) return alpha < material_at(tri.material).alpha_cutoff;
  uint h = pcg4d(uvec4(alpha_key, id, ALPHA_STREAM, 0u)).x;
  return float(h >> 8u) * (1.0 / 16777216.0) >= alpha;
}

// Tests triangle `local` of an instance's mesh against the ray in the mesh's
// object space (whose t is the world t). A point that alpha cuts out is no
// hit, nor is the back face of a single-sided material.
void test_instance_triangle(Ray oray, RayShear osh, InstanceRef ir, uint local, uint from_prim, inout Hit hit) {
  uint id = ir.first_id + local;
  uint i = ir.first_triangle + local;
  if (WALK_STATS) {
    ++walk_primitives;
    walk_primitive_slots += walk_slots();
  }
  GpuTriangle tri = triangle_at(i);
  // Both faces are hit here (the material decides what a back face does,
  // below). Each miss returns at once: a ray spawned on the triangle cannot
  // meet the plane it leaves again; the watertight edge test; t = T / det
  // outside (0, t_max), compared without dividing where the sign of det
  // flips the inequalities. The division and the update and tie tests run
  // for hits only (optimisation log 66: the engine 3-5% faster on the H200,
  // the meshes 13-16% on lavapipe; the same test as a function returning a
  // bool was not faster on the engine there).
  if (id == from_prim) return;
  vec3 uvw;
  float T, det;
  if (!triangle_edges(oray.origin, osh, tri.v0, tri.v1, tri.v2, uvw, T, det)) return;
  float t_max = widened(hit.t);
  if (det > 0.0 ? (T <= 0.0 || T >= t_max * det) : (T >= 0.0 || T <= t_max * det)) return;
  vec3 b = uvw / det;
  float t = T / det;
  if (t < hit.t || (t == hit.t && t != INF && id < hit.prim)) {
    // glTF's single-sided materials (doubleSided false): the back face (the
    // side the winding's normal points away from; the same side shading
    // calls back, as normal_to_world keeps dot(dir, n) through the
    // placement) is not hit.
    if (HAS_SINGLE_SIDED && material_at(tri.material).double_sided == 0u &&
        dot(oray.dir, cross(tri.v1 - tri.v0, tri.v2 - tri.v0)) > 0.0)
      return;
    if (HAS_ALPHA && alpha_cut(tri, i, id, b)) return;
    hit.t = t;
    hit.prim = id;
    hit.kind = PRIM_TRIANGLE;
    hit.inst = ir.inst;
  }
}

#include "accel/octree.glsl"

#define OCTREE_WALK_NAME traverse_mesh
#define OCTREE_BVH_WIDE BVH_MESH_WIDE
#define OCTREE_BVH_WHILE false
#define OCTREE_CHILD_PAIRS true
#define OCTREE_SLAB FusedSlabRay
#define OCTREE_SLAB_MAKE fused_slab_ray
#define OCTREE_LEAF(k) test_instance_triangle(ray, sh, ir, ref_at(k), from_prim, hit)
#define OCTREE_SPLIT (SPLIT_LEAVES && ACCEL == ACCEL_OCTREE)
#include "accel/octree_walk.glsl"
#undef OCTREE_SPLIT
#undef OCTREE_WALK_NAME
#undef OCTREE_BVH_WIDE
#undef OCTREE_BVH_WHILE
#undef OCTREE_CHILD_PAIRS
#undef OCTREE_SLAB
#undef OCTREE_SLAB_MAKE
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
  if (WALK_STATS) ++walk_instances;
  if (ACCEL == ACCEL_BRUTE) {
    for (uint k = 0; k < m.triangle_count; ++k) test_instance_triangle(oray, osh, ir, k, from_prim, hit);
    return;
  }
  if (WALK_STATS && !BIG_LEAF && m.big_count > 0u) ++walk_leaves;
  if (!BIG_LEAF)
    for (uint j = 0; j < m.big_count; ++j)
      test_instance_triangle(oray, osh, ir, ref_at(m.first_ref + j), from_prim, hit);
  traverse_mesh(m.root, m.first_ref, m.first_ref + m.big_count, oray, osh, from_prim, false, ir, hit);
}

// Tests top-level primitive i: a sphere or a mesh instance.
void test_primitive(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  if (is_sphere(i)) test_sphere(ray, i, from_prim, into_from, hit);
  else test_instance(ray, i - scene.sphere_count, from_prim, hit);
}

// Whether the top-level walk's leaf may skip the primitive in slot k of
// the refs array without testing it: an instance of a leaf (not of the big
// list, refs[0, big_count)) whose world box the ray misses before the
// nearest hit (`sr`: the walk's slab terms). The box is the one the tree
// holds the instance by, so a ray that misses it could not hit the
// instance; skipping spares the entry (instance and mesh read, the ray into
// object space, its shear and slab terms) of rays that only pass through
// the instance's cells. Not in the big list: there every query would pay
// for the test, and the balloon, whose baked mesh is the one big primitive,
// rendered 7.6% slower on the H200 with it; in leaves the engine gained 11.5%
// (optimisation log 48).
bool skip_instance(SlabRay sr, uint k, uint i, float t_max) {
  if (is_sphere(i) || k < scene.big_count) return false;
  if (WALK_STATS) ++walk_boxes;
  float t_entry;
  GpuInstance g = instances[i - scene.sphere_count];
  return !hit_box(g.lo, g.hi, sr, t_max, t_entry);
}

void test_primitive_at(Ray ray, SlabRay sr, uint k, uint from_prim, bool into_from, inout Hit hit) {
  uint i = top_ref_at(k);
  if (!skip_instance(sr, k, i, hit.t)) test_primitive(ray, i, from_prim, into_from, hit);
}

#define OCTREE_WALK_NAME traverse_top
#define OCTREE_BVH_WIDE BVH_TOP_WIDE
#define OCTREE_BVH_WHILE BVH_TOP_WHILE
#define OCTREE_CHILD_PAIRS false
#define OCTREE_SLAB SlabRay
#define OCTREE_SLAB_MAKE slab_ray
#define OCTREE_LEAF(k) test_primitive_at(ray, sr, k, from_prim, into_from, hit)
// Spheres alone: a top-level leaf holding an instance would have the lanes
// walk different meshes.
#define OCTREE_SPLIT (SPLIT_LEAVES && ACCEL == ACCEL_OCTREE && !HAS_TRIANGLES)
#include "accel/octree_walk.glsl"
#undef OCTREE_SPLIT
#undef OCTREE_WALK_NAME
#undef OCTREE_BVH_WIDE
#undef OCTREE_BVH_WHILE
#undef OCTREE_CHILD_PAIRS
#undef OCTREE_SLAB
#undef OCTREE_SLAB_MAKE
#undef OCTREE_LEAF

// A scene of one mesh instance and no sphere (SPEC_ONE_INSTANCE; every
// glTF whose meshes are all baked into one): whatever the structure, the
// top-level walk can only lead a ray to test_instance(ray, 0), with the
// nearest hit still t_max (the octree holds the instance in its big list,
// tested first; the BVH tests its box first, and a ray that misses the box
// misses the mesh's root box too), so the queries call it at once: the
// same hits, without the walk's set-up and its box tests.
layout(constant_id = SPEC_ONE_INSTANCE) const bool ONE_INSTANCE = false;

// A query's start: no hit before t_max yet, and the query counted
// (WALK_STATS). Every query of the scene starts so: closest_hit_within,
// occluded, and path_trace.comp's camera lists.
void start_query(float t_max, out Hit hit) {
  hit.t = t_max;
  hit.prim = NO_PRIM;
  hit.kind = PRIM_SPHERE;
  hit.inst = 0u;
  if (WALK_STATS) {
    ++walk_queries;
    walk_query_slots += walk_slots();
  }
}

// The nearest hit before t_max (INF: anywhere). Alpha cut-outs and
// back-face culling apply as to any ray (and to shadow rays: occluded).
bool closest_hit_within(Ray ray, uint from_prim, bool into_from, float t_max, out Hit hit) {
  start_query(t_max, hit);
  if (ONE_INSTANCE) {
    test_instance(ray, 0u, from_prim, hit);
    return hit.prim != NO_PRIM;
  }
  if (ACCEL == ACCEL_BRUTE) {
    if (HAS_SPHERES)
      for (uint i = 0; i < scene.sphere_count; ++i) test_sphere(ray, i, from_prim, into_from, hit);
    if (HAS_TRIANGLES)
      for (uint i = 0; i < scene.instance_count; ++i) test_instance(ray, i, from_prim, hit);
    return hit.prim != NO_PRIM;
  }

  // Primitives too large for the octree's cells (refs[0, big_count)) are
  // tested first: here, or as the walk's first leaf (BIG_LEAF).
  if (WALK_STATS && !BIG_LEAF && scene.big_count > 0u) ++walk_leaves;
  if (!BIG_LEAF)
    for (uint i = 0; i < scene.big_count; ++i) test_primitive(ray, ref_at(i), from_prim, into_from, hit);
  RayShear no_shear;
  traverse_top(0u, 0u, scene.big_count, ray, no_shear, from_prim, into_from, InstanceRef(0u, 0u, 0u), hit);
  return hit.prim != NO_PRIM;
}

bool closest_hit(Ray ray, uint from_prim, bool into_from, out Hit hit) {
  return closest_hit_within(ray, from_prim, into_from, INF, hit);
}

// Shadow rays (light sampling) ask an any-hit question: does some primitive
// other than `skip` (a sphere light's own sphere) lie on the ray before
// t_max? The walk stops at the first blocker it finds, in whatever order,
// with no Surface built. The stop reuses the closest-hit walk's early exit:
// a blocker sets hit.t to -1, which rules out every node still on the stack
// (their entry distance is >= 0) and every box and primitive test after it.
// Inside a mesh instance the walk still finds its nearest triangle; the top
// level stops after it.
uint shadow_skip = NO_PRIM;

void test_primitive_any(Ray ray, uint i, uint from_prim, bool into_from, inout Hit hit) {
  if (i == shadow_skip) return;
  test_primitive(ray, i, from_prim, into_from, hit);
  if (hit.prim != NO_PRIM) hit.t = -1.0;
}

void test_primitive_any_at(Ray ray, SlabRay sr, uint k, uint from_prim, bool into_from, inout Hit hit) {
  uint i = top_ref_at(k);
  if (!skip_instance(sr, k, i, hit.t)) test_primitive_any(ray, i, from_prim, into_from, hit);
}

#define OCTREE_WALK_NAME traverse_top_any
#define OCTREE_BVH_WIDE BVH_TOP_WIDE
#define OCTREE_BVH_WHILE false
#define OCTREE_CHILD_PAIRS false
#define OCTREE_SLAB SlabRay
#define OCTREE_SLAB_MAKE slab_ray
#define OCTREE_LEAF(k) test_primitive_any_at(ray, sr, k, from_prim, into_from, hit)
#define OCTREE_SPLIT (SPLIT_LEAVES && ACCEL == ACCEL_OCTREE && !HAS_TRIANGLES)
#include "accel/octree_walk.glsl"
#undef OCTREE_SPLIT
#undef OCTREE_WALK_NAME
#undef OCTREE_BVH_WIDE
#undef OCTREE_BVH_WHILE
#undef OCTREE_CHILD_PAIRS
#undef OCTREE_SLAB
#undef OCTREE_SLAB_MAKE
#undef OCTREE_LEAF

bool occluded(Ray ray, uint from_prim, bool into_from, float t_max, uint skip) {
  Hit hit;
  start_query(t_max, hit);
  shadow_skip = skip;
  // Only a sphere is ever skipped (a sphere light's own), and there is none.
  if (ONE_INSTANCE) {
    test_instance(ray, 0u, from_prim, hit);
    return hit.prim != NO_PRIM;
  }
  if (ACCEL == ACCEL_BRUTE) {
    if (HAS_SPHERES)
      for (uint i = 0; i < scene.sphere_count && hit.prim == NO_PRIM; ++i)
        if (i != skip) test_sphere(ray, i, from_prim, into_from, hit);
    if (HAS_TRIANGLES)
      for (uint i = 0; i < scene.instance_count && hit.prim == NO_PRIM; ++i) test_instance(ray, i, from_prim, hit);
    return hit.prim != NO_PRIM;
  }
  if (!BIG_LEAF) {
    if (WALK_STATS && scene.big_count > 0u) ++walk_leaves;
    for (uint i = 0; i < scene.big_count && hit.prim == NO_PRIM; ++i)
      test_primitive_any(ray, ref_at(i), from_prim, into_from, hit);
    if (hit.prim != NO_PRIM) return true;
  }
  RayShear no_shear;
  traverse_top_any(0u, 0u, scene.big_count, ray, no_shear, from_prim, into_from, InstanceRef(0u, 0u, 0u), hit);
  return hit.prim != NO_PRIM;
}

// The surface at a hit that closest_hit returned.
Surface surface_at(Ray ray, Hit hit) {
  if (!HAS_TRIANGLES || (HAS_SPHERES && hit.kind == PRIM_SPHERE))
    return sphere_surface(ray, hit.t, sphere_at(hit.prim), sphere_material_at(hit.prim));
  GpuInstance g = instances[hit.inst];
  uint tri = meshes[g.mesh].first_triangle + (hit.prim - g.first_id);
  return triangle_surface(ray, to_object(g, ray), hit.t, tri, g);
}

#endif
