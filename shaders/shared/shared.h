// Buffer layouts shared by the C++ host and the GLSL shaders (std430 rules).
// Each struct is written once, here. Rules that keep the two views identical:
// a vec3 is always followed by a 4-byte scalar (std430 aligns vec3 to 16 bytes,
// glm to 4), and every struct is a multiple of 16 bytes. The C++ side checks
// sizes and offsets with static_assert (renderer/render/gpu_layout.h); the layout
// probe test checks them against the GLSL compiler's view.
#ifndef OCTRACE_SHARED_H
#define OCTRACE_SHARED_H

#if !defined(__cplusplus) && OCTRACE_PRECISION >= 1
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#extension GL_EXT_shader_16bit_storage : require
#endif

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <glm/gtc/type_precision.hpp>
namespace octrace::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using f16vec4 = glm::u16vec4;  // half bit patterns (glm::packHalf)
#define OCT_CONST(type, name, value) inline constexpr type name = value
#else
#define OCT_CONST(type, name, value) const type name = value
#endif

OCT_CONST(uint, MAT_LAMBERTIAN, 0u);
OCT_CONST(uint, MAT_METAL, 1u);
OCT_CONST(uint, MAT_DIELECTRIC, 2u);
OCT_CONST(uint, MAT_EMISSIVE, 3u);
OCT_CONST(uint, MAT_PBR, 4u);  // glTF's metallic-roughness material (shading/pbr.glsl)

OCT_CONST(uint, SKY_GRADIENT, 0u);
OCT_CONST(uint, SKY_UNIFORM, 1u);
OCT_CONST(uint, SKY_NONE, 2u);
OCT_CONST(uint, SKY_ENVMAP, 3u);  // an equirectangular image (shading/envmap.glsl)

// Texture wrap modes (glTF's sampler wrapS / wrapT) and "no texture".
OCT_CONST(uint, WRAP_REPEAT, 0u);
OCT_CONST(uint, WRAP_CLAMP_TO_EDGE, 1u);
OCT_CONST(uint, WRAP_MIRRORED_REPEAT, 2u);
OCT_CONST(uint, NO_TEXTURE, 0xffffffffu);

// A material's texture references (slots), each with its uv transform
// (GpuUvTransform): the transform of material i's slot k is
// texture_transforms[i * TEXTURE_SLOTS + k].
OCT_CONST(uint, TEXTURE_SLOT_BASE_COLOR, 0u);
OCT_CONST(uint, TEXTURE_SLOT_METALLIC_ROUGHNESS, 1u);
OCT_CONST(uint, TEXTURE_SLOT_EMISSION, 2u);
OCT_CONST(uint, TEXTURE_SLOT_NORMAL, 3u);
OCT_CONST(uint, TEXTURE_SLOT_TRANSMISSION, 4u);  // its index is GpuTransmission's
OCT_CONST(uint, TEXTURE_SLOTS, 5u);

// glTF's alpha modes (GpuMaterial.alpha_mode; scene/scene.h's AlphaMode).
OCT_CONST(uint, ALPHA_OPAQUE, 0u);
OCT_CONST(uint, ALPHA_MASK, 1u);
OCT_CONST(uint, ALPHA_BLEND, 2u);

OCT_CONST(uint, WORKGROUP_SIZE, 8u);  // 8x8 invocations per workgroup
// At most this many invocations of a path-tracing workgroup share one pixel's
// samples (PassParams.sample_lanes).
OCT_CONST(uint, MAX_SAMPLE_LANES, 8u);

// Kinds of primitive a hit can name (Hit.kind in shaders/accel/closest_hit.glsl).
// Ids: the top level (the scene's octree) holds spheres [0, sphere_count)
// and mesh instances [sphere_count, sphere_count + instance_count); a hit
// on a triangle names it by a global id unique per instance and triangle,
// GpuInstance.first_id + its index in the mesh (first_id starts at
// sphere_count + instance_count), so no two primitives share an id.
OCT_CONST(uint, PRIM_SPHERE, 0u);
OCT_CONST(uint, PRIM_TRIANGLE, 1u);

// Descriptor bindings of the path-tracing pipeline (set 0). The host binds by
// these names (render/path_tracer.cpp), the shader declares by them.
OCT_CONST(uint, BINDING_SCENE, 0u);
OCT_CONST(uint, BINDING_SPHERES, 1u);
OCT_CONST(uint, BINDING_SPHERE_MATERIALS, 2u);
OCT_CONST(uint, BINDING_MATERIALS, 3u);
OCT_CONST(uint, BINDING_ACCUM_SUM, 4u);
OCT_CONST(uint, BINDING_ACCUM_COMP, 5u);
OCT_CONST(uint, BINDING_ACCUM_SQ, 6u);
OCT_CONST(uint, BINDING_STATS, 7u);
OCT_CONST(uint, BINDING_OCTREE_NODES, 8u);
OCT_CONST(uint, BINDING_OCTREE_REFS, 9u);
OCT_CONST(uint, BINDING_TRIANGLES, 10u);
OCT_CONST(uint, BINDING_TRIANGLE_NORMALS, 11u);
OCT_CONST(uint, BINDING_INSTANCES, 12u);
OCT_CONST(uint, BINDING_MESHES, 13u);
OCT_CONST(uint, BINDING_TEXTURES, 14u);
OCT_CONST(uint, BINDING_TEXELS, 15u);
OCT_CONST(uint, BINDING_TRIANGLE_UVS, 16u);
OCT_CONST(uint, BINDING_TEXTURE_TRANSFORMS, 17u);
// Light sampling (shading/lights.glsl): the light list (GpuLight, with its
// alias table), and per sphere the index of its light in that list
// (NO_LIGHT for a sphere that does not emit), for the MIS weight of a
// BSDF-sampled ray that hits it.
OCT_CONST(uint, BINDING_LIGHTS, 18u);
OCT_CONST(uint, BINDING_SPHERE_LIGHTS, 19u);
// The light index of a hit on an emissive triangle (render/lights.h,
// LightList::triangle_lights), in uints: [0] = how many instances the table
// covers (0: no triangle emits; the array is then the one word, within the
// 16-byte placeholder), [1 + instance] = where that instance's per-triangle
// entries start (NO_LIGHT: none of its triangles emits), [start + local
// triangle] = its light's index or NO_LIGHT. Memory: one word per instance
// and one per triangle of each instance that has an emissive triangle.
OCT_CONST(uint, BINDING_TRIANGLE_LIGHTS, 20u);
// The environment map (SKY_ENVMAP; renderer/scene/envmap.h): its texels, 3
// floats (linear rgb, fp32) per texel, row 0 the top (+y); and the sampling
// tables: the marginal CDF over rows (height + 1 floats, then the density
// scale), the conditional CDFs (width + 1 floats per row). 16-byte
// placeholders without an envmap.
OCT_CONST(uint, BINDING_ENVMAP_TEXELS, 21u);
OCT_CONST(uint, BINDING_ENVMAP_MARGINAL, 22u);
OCT_CONST(uint, BINDING_ENVMAP_CONDITIONAL, 23u);
// The part table of a scene split over several buffers (scene_buffers.glsl);
// bindings 18-20 are light sampling's, 21-23 the environment map's.
OCT_CONST(uint, BINDING_BUFFER_PARTS, 24u);
// What transmission reads besides GpuMaterial, one GpuTransmission per
// material; a 16-byte placeholder in a scene without transmission.
OCT_CONST(uint, BINDING_TRANSMISSION, 26u);
// The tail queue (PassParams.tail_depth; path_trace.comp): each sample's
// value (vec4: rgb, segments as uint bits) per [sample of the dispatch][pixel],
// the paths that go on after the head (GpuTailPath; with tail levels two
// halves of PassParams.tail_capacity entries, level l reading half l % 2 and
// queueing into the other), and a TailControl per level. 16-byte
// placeholders when the queue is off.
OCT_CONST(uint, MAX_TAIL_LEVELS, 16u);
OCT_CONST(uint, BINDING_TAIL_VALUES, 27u);
OCT_CONST(uint, BINDING_TAIL_QUEUE, 28u);
OCT_CONST(uint, BINDING_TAIL_CONTROL, 29u);
// The camera's tiles (RenderSettings::camera_tiles; camera_tiles.comp
// writes them, path_trace.comp reads them): for each tile of CAMERA_TILE_PIXELS x
// CAMERA_TILE_PIXELS pixels (tile = (y / 8) * tiles across + x / 8) its
// count of candidates, or CAMERA_TILE_OVERFLOW where more than
// CAMERA_TILE_REFS are; after the counts, CAMERA_TILE_REFS sphere indices
// per tile (places in the sphere buffer, which is in the tree's order
// under SPEC_SPHERES_IN_TREE_ORDER; the scenes with tiles have spheres
// alone, so these are their top-level ids): every sphere a camera ray
// through the tile could meet. A 16-byte placeholder when off.
OCT_CONST(uint, BINDING_CAMERA_TILES, 30u);
OCT_CONST(uint, BINDING_COUNT, 31u);
OCT_CONST(uint, CAMERA_TILE_PIXELS, 8u);
OCT_CONST(uint, CAMERA_TILE_REFS, 32u);
OCT_CONST(uint, CAMERA_TILE_OVERFLOW, 0xffffffffu);

// A scene larger than one storage buffer (the device's maxStorageBufferRange,
// 128 MiB on lavapipe) is read through buffer device addresses
// (VK_KHR_buffer_device_address, Vulkan 1.2 core): each big per-primitive
// array is cut into parts of 2^SPEC_PART_LOG2 bytes at most, element i of an
// array of elements of size s lying in part i >> (PART_LOG2 - ceil(log2 s)),
// and the part table (BINDING_BUFFER_PARTS) holds each part's address as a
// uvec2 (low, high) at [array * MAX_PARTS + part]. The arrays, by SPLIT_*:
OCT_CONST(uint, SPLIT_SPHERES, 0u);
OCT_CONST(uint, SPLIT_SPHERE_MATERIALS, 1u);
OCT_CONST(uint, SPLIT_TRIANGLES, 2u);
OCT_CONST(uint, SPLIT_TRIANGLE_NORMALS, 3u);
OCT_CONST(uint, SPLIT_TRIANGLE_UVS, 4u);
OCT_CONST(uint, SPLIT_OCTREE_NODES, 5u);
OCT_CONST(uint, SPLIT_OCTREE_REFS, 6u);
OCT_CONST(uint, SPLIT_MATERIALS, 7u);       // GpuMaterial (fp32 variant)
OCT_CONST(uint, SPLIT_MATERIALS_HALF, 8u);  // GpuMaterialHalf (fp16 variants)
OCT_CONST(uint, SPLIT_ARRAYS, 9u);
OCT_CONST(uint, MAX_PARTS, 64u);  // per array: 8 GiB at lavapipe's 128 MiB parts

// Descriptor bindings of the resolve pipeline (resolve.comp).
OCT_CONST(uint, RESOLVE_BINDING_ACCUM_SUM, 0u);
OCT_CONST(uint, RESOLVE_BINDING_ACCUM_COMP, 1u);
OCT_CONST(uint, RESOLVE_BINDING_PIXELS, 2u);
OCT_CONST(uint, RESOLVE_BINDING_COUNT, 3u);
// Its one specialization constant: swap red and blue (B8G8R8A8 swapchains).
OCT_CONST(uint, RESOLVE_SPEC_SWAP_RB, 0u);

// Specialization constants of the path-tracing pipeline: the accel, and the
// scene's features (renderer/scene/features.h) so that absent effects compile out.
OCT_CONST(uint, SPEC_ACCEL, 0u);
OCT_CONST(uint, SPEC_LAMBERTIAN, 1u);
OCT_CONST(uint, SPEC_METAL, 2u);
OCT_CONST(uint, SPEC_FUZZ, 3u);
OCT_CONST(uint, SPEC_DIELECTRIC, 4u);
OCT_CONST(uint, SPEC_EMISSIVE, 5u);
OCT_CONST(uint, SPEC_DEFOCUS, 6u);
OCT_CONST(uint, SPEC_SKY, 7u);
OCT_CONST(uint, SPEC_ANY_LIGHT, 8u);
OCT_CONST(uint, SPEC_SPHERES, 9u);
OCT_CONST(uint, SPEC_TRIANGLES, 10u);
OCT_CONST(uint, SPEC_VERTEX_NORMALS, 11u);
OCT_CONST(uint, SPEC_TEXTURES, 12u);
OCT_CONST(uint, SPEC_SURFACE_EMISSION, 13u);
// Whether invocations may share a pixel's samples (PassParams.sample_lanes);
// off, the workgroup barrier that sharing needs is compiled out.
OCT_CONST(uint, SPEC_SAMPLE_LANES, 14u);
OCT_CONST(uint, SPEC_PBR, 15u);
OCT_CONST(uint, SPEC_NORMAL_MAPS, 16u);
// Whether some mesh material is not opaque (alpha MASK or BLEND): off, the
// alpha test in the triangle hit test (accel/closest_hit.glsl) compiles out.
OCT_CONST(uint, SPEC_ALPHA, 17u);
// Whether some mesh material is single-sided (glTF's doubleSided false): off,
// the back-face test in the triangle hit test compiles out.
OCT_CONST(uint, SPEC_SINGLE_SIDED, 18u);
// Whether some pbr material transmits (KHR_materials_transmission): off, the
// refraction of shading/pbr.glsl compiles out.
OCT_CONST(uint, SPEC_TRANSMISSION, 19u);
// Whether some transmissive solid absorbs (KHR_materials_volume's
// attenuation, GpuTransmission.absorption): off, the Beer-Lambert factor
// of path_trace.comp compiles out.
OCT_CONST(uint, SPEC_ABSORPTION, 24u);
// log2 of the largest part of a split scene, in bytes (the split pipeline
// only, path_trace_*_split; scene_buffers.glsl).
OCT_CONST(uint, SPEC_PART_LOG2, 27u);
// Next-event estimation (--nee on and a scene with lights to sample): off,
// the integrator is the one without light sampling, bit for bit.
OCT_CONST(uint, SPEC_NEE, 20u);
// Whether the scene has punctual lights (point, spot, directional).
OCT_CONST(uint, SPEC_PUNCTUAL, 21u);
// Whether the sky is a light of the light list (an envmap that is not black;
// render/lights.h): light sampling may pick it, and a path that escapes to
// it after a vertex that sampled a light takes an MIS weight.
OCT_CONST(uint, SPEC_SKY_LIGHT, 22u);
// Whether some placed mesh triangle emits (render/lights.h: an emissive
// triangle is a light of the list): off, triangle-light sampling and its
// MIS weight compile out.
OCT_CONST(uint, SPEC_TRIANGLE_LIGHTS, 23u);
// Octant culling in the octree walk (RenderSettings::octant_culling; the
// image is the same either way).
OCT_CONST(uint, SPEC_OCTANT_CULLING, 25u);
// Whether the octree walks test the big list as their first leaf, or their
// callers in a loop of their own (RenderSettings::big_list; the image is the
// same either way).
OCT_CONST(uint, SPEC_BIG_LEAF, 26u);
// Whether the octree walk keeps a node's nearest child in registers instead
// of pushing it (RenderSettings::nearest_child; the image is the same
// either way).
OCT_CONST(uint, SPEC_OCTREE_HOLD_NEAREST, 32u);
// Whether a BVH's top level, and its meshes' trees, are four-wide
// (renderer/accel/bvh.h default_bvh_widths, OctreeParams::bvh_width): their
// walk is accel/bvh_walk.glsl's four-wide form, else its binary one.
OCT_CONST(uint, SPEC_BVH_TOP_WIDE, 30u);
OCT_CONST(uint, SPEC_BVH_MESH_WIDE, 31u);
// Whether the device holds the spheres in the order the top-level BVH's
// leaves reference them (render/gpu_scene.cpp device_sphere_order): a leaf's
// reference k is then sphere k itself, and refs[k] that sphere's index in
// the scene. The image is the same either way.
OCT_CONST(uint, SPEC_SPHERES_IN_TREE_ORDER, 33u);
// Whether the scene on the device is one mesh instance and no sphere (a
// glTF whose meshes were all baked: render/gpu_scene.h device_meshes): the
// queries test that instance without the top-level walk
// (accel/closest_hit.glsl). The image is the same either way. Off in the
// general pipeline (`--effects all`).
OCT_CONST(uint, SPEC_ONE_INSTANCE, 34u);
// The entries of path_trace.comp's workgroup array lane_sample: at least one
// per invocation (render/path_tracer.h lane_sample_slots says why more).
OCT_CONST(uint, SPEC_LANE_SAMPLE_SLOTS, 35u);
// Whether the top level's binary BVH walk takes its while-while form
// (accel/bvh_walk.glsl; RenderSettings::bvh_walk, render/path_tracer.h
// default_bvh_top_while). The image is the same either way.
OCT_CONST(uint, SPEC_BVH_TOP_WHILE, 36u);
// Whether the walks count what they do (RenderSettings::walk_stats,
// RenderStats.walk); off, the counting compiles out.
OCT_CONST(uint, SPEC_WALK_STATS, 28u);
// Which part of a dispatch of samples the pipeline runs (path_trace.comp):
// the whole paths, or with the tail queue its head or its tail (the sum is
// accumulate.comp).
OCT_CONST(uint, SPEC_STAGE, 29u);
OCT_CONST(uint, STAGE_WHOLE, 0u);
OCT_CONST(uint, STAGE_HEAD, 1u);
OCT_CONST(uint, STAGE_TAIL, 2u);
// A tail level of fewer paths than SPEC_TAIL_SUBGROUP (RenderSettings::
// tail_subgroup; 0: none) runs in this stage instead: a subgroup a path,
// whose lanes share each octree leaf's tests (path_trace.comp).
OCT_CONST(uint, STAGE_TAIL_SUBGROUP, 3u);
OCT_CONST(uint, SPEC_TAIL_SUBGROUP, 37u);
// Whether the whole paths and the head take a camera ray's hit from its
// tile's list (RenderSettings::camera_tiles) instead of the walk.
OCT_CONST(uint, SPEC_CAMERA_TILES, 38u);
// Whether the tail stage takes its level's paths from a counter a bounce
// at a time (RenderSettings::tail_fetch; TailControl.fetched) instead of
// one path an invocation (path_trace.comp tail_pass).
OCT_CONST(uint, SPEC_TAIL_FETCH, 39u);
// Whether the path tracer's invocations check, at their end, that the
// driver did not end their loops early (llvmpipe's limit; path_trace.comp
// check_loop_limit) and count those it did in RenderStats.cut_paths: on
// CPU devices.
OCT_CONST(uint, SPEC_LOOP_LIMIT_CHECK, 40u);
// SPEC_SKY value for the general pipeline: the sky type is read at run time.
OCT_CONST(uint, SKY_RUNTIME, 255u);

// Acceleration structures (specialization constant ACCEL).
OCT_CONST(uint, ACCEL_BRUTE, 0u);
OCT_CONST(uint, ACCEL_OCTREE, 1u);
OCT_CONST(uint, ACCEL_BVH, 2u);  // the octree's arrays hold a BVH (renderer/accel/bvh.h)
// The BVH's depth limit: its shader walks' stacks hold BVH_MAX_DEPTH + 1
// (binary) and (BVH_WIDTH - 1) * BVH_MAX_DEPTH + 1 (four-wide) entries.
OCT_CONST(uint, BVH_MAX_DEPTH, 48u);
// Children per BVH node, at most (renderer/accel/bvh.h; the wide walk's
// sort, accel/bvh_walk.glsl, is written for four).
OCT_CONST(uint, BVH_WIDTH, 4u);

// Kinds of light (GpuLight.type).
OCT_CONST(uint, LIGHT_SPHERE, 0u);       // an emissive sphere, sampled by solid angle
OCT_CONST(uint, LIGHT_POINT, 1u);
OCT_CONST(uint, LIGHT_SPOT, 2u);
OCT_CONST(uint, LIGHT_DIRECTIONAL, 3u);
OCT_CONST(uint, LIGHT_ENVMAP, 4u);       // the sky's envmap, sampled by its 2D CDF; always the list's last
OCT_CONST(uint, LIGHT_TRIANGLE, 5u);     // an emissive mesh triangle of one instance, sampled by area
OCT_CONST(uint, NO_LIGHT, 0xffffffffu);

// 80 bytes. One light of the light list (render/lights.h builds it), which
// is also the alias table that picks a light in proportion to its power
// (Walker 1977; Vose 1991): draw i uniform in [0, n) and u in [0, 1), take
// light i if u < alias_q, else light alias. pmf is the probability that this
// pick returns this light, for the estimator's 1 / pmf and the MIS weights.
//   sphere       position = centre, radius; the radiance is the sphere's
//                material's (read where it is used, as a hit reads it);
//                sphere = its index in the sphere array
//   point, spot  position; intensity = radiant intensity (rgb)
//   spot         direction (unit, where the light travels); cos_inner,
//                cos_outer: the cosines of glTF's cone angles
//   directional  direction (unit, where the light travels); intensity =
//                irradiance (rgb)
//   envmap       nothing: the texels, strength and tables are the sky's
//                (SceneParams, the envmap bindings); the last entry of the list
//   triangle     position, direction, intensity = the world-space vertices
//                v0, v1, v2; radius = the world-space area; instance = the
//                instance, triangle = the triangle's index in its mesh (the
//                material and uvs, read as a hit reads them)
struct GpuLight {
  vec3 position;
  uint type;  // LIGHT_*
  vec3 direction;
  float radius;
  vec3 intensity;
  uint sphere;
  float cos_inner;
  float cos_outer;
  float pmf;
  float alias_q;
  uint alias;
  uint instance;
  uint triangle;
  uint pad0;
};

// 16 bytes. Sphere i's material index is sphere_materials[i] (a separate array,
// so the intersection loop reads only centres and radii).
struct GpuSphere {
  vec3 center;
  float radius;
};

// 48 bytes. One triangle of a mesh, in the mesh's own (object) space, stored
// once however many instances place the mesh. The vertices are stored rather
// than an index into a vertex array: the intersection test reads one 48-byte
// record, and a triangle's material sits in the same cache line.
struct GpuTriangle {
  vec3 v0;
  uint material;  // index into the material array
  vec3 v1;
  uint pad0;
  vec3 v2;
  uint pad1;
};

// 48 bytes. Triangle i's vertex normals in object space (unit), for smooth
// shading; uploaded only when some mesh has normals (a flat triangle's three
// are its geometric normal). tangentK: vertex K's tangent from the file
// (glTF's TANGENT, 3.7.2.1, object space) in what would be padding, or 0
// for none (the normal map's frame then comes from the uvs): a unit vector
// in the octahedral encoding of Cigolle et al. 2014 ("A Survey of Efficient
// Representations for Independent Unit Vectors", JCGT 3(2), sec. 3.7), its
// two coordinates in [-1, 1] as 15-bit unorms (bits 0-14 and 15-29; at most
// ~1e-4 radians off), TANGENT_NEGATIVE_W for handedness w = -1,
// TANGENT_PRESENT. A file's tangents cost no memory on the GPU: TANGENT is
// read only beside NORMAL (glTF ignores it without), so where a mesh has one
// the normals are uploaded anyway.
struct GpuTriangleNormals {
  vec3 n0;
  uint tangent0;
  vec3 n1;
  uint tangent1;
  vec3 n2;
  uint tangent2;
};
OCT_CONST(uint, TANGENT_PRESENT, 0x80000000u);
OCT_CONST(uint, TANGENT_NEGATIVE_W, 0x40000000u);
OCT_CONST(uint, TANGENT_UNORM_MAX, 0x7fffu);

// 24 bytes. Triangle i's texture coordinates (glTF's TEXCOORD_0 at v0, v1,
// v2; 0 for a mesh without them); uploaded only when some material has a
// texture. 24 rather than a multiple of 16: it holds no vec3, and std430
// aligns a vec2 (and so this struct) to 8 bytes, so that the array stride is
// 24 in both views (checked by static_assert and the layout probe). fp32: a
// texture repeated many times over a mesh needs the precision.
struct GpuTriangleUvs {
  vec2 uv0;
  vec2 uv1;
  vec2 uv2;
};

// 24 bytes. The uv transform of one texture reference of a material
// (glTF's KHR_texture_transform, as a 2x3 matrix by columns): a surface at
// uv samples the texture at x_axis * uv.x + y_axis * uv.y + offset. The
// identity (1, 0), (0, 1), (0, 0) gives uv back exactly. Uploaded only when
// the scene has textures; 24 bytes in both views for the reason
// GpuTriangleUvs gives.
struct GpuUvTransform {
  vec2 x_axis;
  vec2 y_axis;
  vec2 offset;
};

// 80 bytes. One placement of a mesh. A ray enters the instance through
// to_object (the rows of the 3x4 world-to-object matrix: the ray's t stays
// the world t, its direction is not renormalised); normals leave it through
// the transpose of the same 3x3 part (the inverse transpose of the
// placement), which keeps a mirrored mesh's outside outside. lo, hi: the
// world box of the placed mesh (the box the top level's tree places it by);
// a ray that misses it does not enter (accel/closest_hit.glsl).
struct GpuInstance {
  vec4 to_object0;
  vec4 to_object1;
  vec4 to_object2;
  vec3 lo;
  uint mesh;  // index into the mesh table
  vec3 hi;
  uint first_id;  // global id of the mesh's triangle 0 in this instance
};

// 32 bytes. A mesh: its triangles triangles[first_triangle, + triangle_count)
// and its own octree in object space (octree: nodes[root]; refs of mesh-local
// triangle indices; refs[first_ref, first_ref + big_count) tested first).
struct GpuMesh {
  uint root;
  uint first_ref;
  uint big_count;
  uint first_triangle;
  uint triangle_count;
  uint pad0;
  uint pad1;
  uint pad2;
};

// 80 bytes. `color` is the albedo (lambertian, metal), the base colour
// (pbr) or the radiance (emissive). A lambertian or pbr material may also
// sample textures (indices into the texture table, or NO_TEXTURE) and emit:
// albedo x base colour texture, and emission x emission texture (glTF's
// materials; scene/scene.h). A pbr material's metallic and roughness are
// multiplied by the blue and green channels of its metallic-roughness
// texture; its ior sets the dielectric layer's F0. A lambertian or pbr
// material may have a normal map (tangent space, linear; its xy times
// normal_scale). A pbr material keeps its transmission in `fuzz` (which only
// metal uses): t > 0 bounds a closed solid, -t a thin-walled surface (the
// sign is exact in half too); 0 transmits nothing. The first 24 bytes are all that the RTIOW materials use;
// the texture indices sit in what was padding, the emission and the pbr
// parameters in rows of their own, the normal map in the last row's padding.
// The last row (no padding was left) is glTF's alpha (read by the triangle
// hit test, not by shading; the same row, fp32, ends GpuMaterialHalf so that
// the test reads either struct alike): alpha_mode ALPHA_*, alpha_cutoff
// (MASK: a texel is cut out where alpha < cutoff), alpha (baseColorFactor.a,
// times the base colour texture's alpha where it is sampled) and
// double_sided (0: a triangle's back face is not hit, by any ray).
struct GpuMaterial {
  vec3 color;
  uint type;   // MAT_*
  float fuzz;  // metal; pbr: transmission, negated when thin-walled
  float ior;   // dielectric, pbr
  uint base_color_texture;
  uint emission_texture;
  vec3 emission;
  uint metallic_roughness_texture;
  float metallic;   // pbr
  float roughness;  // pbr (perceptual: alpha = roughness^2)
  uint normal_texture;
  float normal_scale;
  uint alpha_mode;  // ALPHA_*
  float alpha_cutoff;
  float alpha;
  uint double_sided;
};

// 16 bytes. What a material's transmission reads besides GpuMaterial (which
// has no room left), in every precision variant: `absorption`, the
// absorption coefficient sigma per unit length of the solid it bounds
// (KHR_materials_volume: sigma = -ln(attenuationColor) /
// attenuationDistance; 0: clear; +Inf where a colour channel is 0), fp32
// (half's 65504 does not hold the sigma of a short attenuation distance);
// and the index of its transmission texture (KHR_materials_transmission's
// transmissionTexture, whose red channel, linear, multiplies the factor),
// or NO_TEXTURE.
struct GpuTransmission {
  vec3 absorption;
  uint transmission_texture;
};

// 16 bytes. One texture of the texture table: its texels are
// texels[first_texel + y * width + x], row y = 0 the top of the image (glTF's
// v = 0), each texel one uint of RGBA8 as the file stores it (r in the low
// byte: unpackUnorm4x8), so colour textures stay sRGB-encoded and are decoded
// where they are sampled (shading/texture.glsl). One buffer of texels for all
// textures keeps the pipeline's bindings fixed however many textures a scene
// has (it must fit one storage buffer: lavapipe allows 128 MiB); the table
// lets a material refer to a texture by index, and a future texture slot
// (metallic-roughness, normal map) add an index to the material, not a buffer.
struct GpuTexture {
  uint first_texel;
  uint width;
  uint height;
  uint wrap;  // WRAP_* along u (glTF's wrapS) | WRAP_* along v (wrapT) << 16
};

// The accumulation state is three arrays of one vec4 per pixel, in fp32 (three
// arrays rather than one struct so that each stays under a device's largest
// storage buffer for 4K images on lavapipe's 128 MiB):
//   accum_sum.rgb: Kahan-compensated sum of the samples; accum_sum.w: number of
//     samples added (exact as a float up to 2^24);
//   accum_comp.rgb: the Kahan compensation terms;
//   accum_sq.rgb: sum of squared deviations from the mean (Welford's M2), for
//     the per-pixel variance the golden tests use; accum_sq.w: the bits of a
//     uint, the ray segments the pixel's paths traced (camera rays and
//     bounces; NaN/Inf samples' not counted), for rays per second.

// 64 bytes: the material as the fp16 variants read it (16-bit storage).
// color_type: albedo, base colour or radiance, and the MAT_* type as a half
// (exact); params: fuzz, ior, metallic, roughness; emission: rgb, unused. The
// host writes half bit patterns. The texture indices stay 32-bit (a half
// holds integers exactly only up to 2048). Half is enough for roughness (its
// smallest non-zero value used, alpha = roughness^2, is clamped far above
// half's resolution near 0; shading/pbr.glsl).
#if defined(__cplusplus) || OCTRACE_PRECISION >= 1
struct GpuMaterialHalf {
  f16vec4 color_type;
  f16vec4 params;
  f16vec4 emission;
  uint base_color_texture;
  uint emission_texture;
  uint metallic_roughness_texture;
  uint normal_texture;
  float normal_scale;  // fp32: read once per hit, and the row has room
  uint pad2;
  uint alpha_mode;     // the last row as GpuMaterial's, fp32: the alpha test
  float alpha_cutoff;  // compares alpha with the cutoff exactly as the fp32
  float alpha;         // variant does
  uint double_sided;
};
#endif

// 32 bytes. One octree node; nodes[0] is the root. The octree is described in
// renderer/accel/octree.h (encoding, drawing, why).
//   lo, hi: the node's box: its cell clipped to the bounds of what it holds.
//   Internal node: `count_or_mask` = OCTREE_INTERNAL | child mask (bit k set =
//     octant k present; octant k = (x >= mid) | (y >= mid) << 1 | (z >= mid) << 2);
//     `first` = index of the first present child; present children are stored
//     consecutively in octant order.
//   Leaf: `count_or_mask` = number of primitive references (< OCTREE_INTERNAL),
//     `first` = index of the first reference in the refs array.
struct GpuOctreeNode {
  vec3 lo;
  uint first;
  vec3 hi;
  uint count_or_mask;
};
OCT_CONST(uint, OCTREE_INTERNAL, 0x80000000u);

// What the walks counted with --walk-stats (SPEC_WALK_STATS), each a 64-bit
// count in RenderStats.walk as words [2k] (low) and [2k + 1] (high):
OCT_CONST(uint, WALK_QUERIES, 0u);    // walks of the scene: closest-hit and shadow-ray queries
OCT_CONST(uint, WALK_NODES, 1u);      // internal nodes expanded (their children's boxes tested)
OCT_CONST(uint, WALK_LEAVES, 2u);     // leaves (and big lists) whose primitives were tested
OCT_CONST(uint, WALK_BOXES, 3u);      // ray/box tests
OCT_CONST(uint, WALK_PRIMITIVES, 4u); // ray/primitive tests (spheres, triangles)
OCT_CONST(uint, WALK_INSTANCES, 5u);  // mesh instances entered (their own trees walked)
// How full the subgroups were: at each step where lanes of a subgroup start a
// query, expand a node or test a primitive, the subgroup's size (its lanes,
// busy or not; accel/closest_hit.glsl, walk_slots). The count over these is
// the share of the lanes that were busy at such steps.
OCT_CONST(uint, WALK_QUERY_SLOTS, 6u);
OCT_CONST(uint, WALK_NODE_SLOTS, 7u);
OCT_CONST(uint, WALK_PRIMITIVE_SLOTS, 8u);
OCT_CONST(uint, WALK_COUNTERS, 9u);

// 88 bytes. Counters the passes update with atomics.
struct RenderStats {
  uint nonfinite_samples;  // samples that were NaN or Inf and were not added
  uint cut_paths;          // SPEC_LOOP_LIMIT_CHECK: invocations whose loops the driver's limit ended
  uint loop_bound;         // 2, set by the host (PathTracer::reset): check_loop_limit's loop bound
  uint pad2;
  uint walk[2u * WALK_COUNTERS];  // WALK_COUNTERS 64-bit counts, low word first (zeros without --walk-stats)
};

// 64 bytes. What the passes need of the scene besides its arrays; uploaded
// once with the scene (a camera move or a new bounce limit does not touch it).
struct SceneParams {
  vec3 sky_a;         // gradient: down; uniform: radiance; envmap: strength (all three)
  uint sky_type;      // SKY_*
  vec3 sky_b;         // gradient: up; envmap: x = rotate / 360 (a fraction of a turn)
  uint sphere_count;
  uint big_count;     // octree: refs[0, big_count) are primitives tested before traversal
  uint triangle_count;  // unique (object-space) triangles
  uint vertex_normals;  // 1: triangle_normals holds every triangle's normals; 0: it is empty
  uint instance_count;
  uint triangle_uvs;    // 1: triangle_uvs holds every triangle's uvs; 0: it is empty
  uint light_count;     // lights in the light list (0: nothing to sample)
  uint envmap_width;    // envmap: texels per row (0 without one)
  uint envmap_height;   // envmap: rows
};

// 128 bytes, the push constants of one dispatch of passes: everything that may change from
// one pass to the next without touching the scene (the camera, the image
// size, the bounce limit, the sampler's seed and the sample index). The camera
// is precomputed on the host (render/camera.h): a pixel (x, y) (top row
// first) maps to the point pixel00 + x*pixel_du + y*pixel_dv on the focus
// plane; the lens is a disc of lens_radius spanned by lens_u, lens_v.
struct PassParams {
  vec3 cam_origin;
  float lens_radius;  // aperture / 2
  vec3 lens_u;        // unit camera right
  uint width;
  vec3 lens_v;        // unit camera up
  uint height;
  vec3 pixel00;       // top-left corner of the focus-plane viewport
  uint bounce_limit;  // a path that reaches it contributes 0
  vec3 pixel_du;
  uint sample_seed;
  vec3 pixel_dv;
  uint sample_index;  // the first sample this dispatch adds to every pixel ...
  uint rr_depth;      // Russian roulette from this bounce on (0xffffffff: never)
  uint sample_count;  // ... and how many: sample_index .. sample_index + sample_count - 1
  uint sample_lanes;  // invocations per pixel (1, 2, 4 or 8): a workgroup covers an 8 x (8 / lanes) tile
  uint tail_depth;    // staged (head): paths still going at this bounce go to the tail queue (>= bounce_limit: none)
  uint tail_capacity; // the queue's entries (GpuTailPath); a head past them finishes its path itself
  uint tail_level;    // staged (tail): the level this tail dispatch runs (0: the paths the head queued)
  uint tail_end;      // staged (tail): paths still going at this bounce go to the next level's queue (>= bounce_limit: none)
  uint tail_fill;     // staged (tail): a level that takes fewer paths finishes them (RenderSettings::tail_fill)
};

// 96 bytes: a path in the tail queue (path_trace.comp PathState), in fp32
// whatever the precision (a half converts to float and back exactly).
struct GpuTailPath {
  vec3 origin;
  uint pixel;          // pixel index (y * width + x)
  vec3 dir;
  uint sample_offset;  // the sample's place in its dispatch (sample index - PassParams.sample_index)
  vec3 throughput;
  uint bounce_flags;   // the next bounce | 0x40000000 into_from | 0x80000000 prev_nee
  vec3 radiance;
  uint segments;
  vec3 direct;
  uint from_prim;
  vec3 prev_p;
  float prev_pdf;
};

// 32 bytes: a tail queue's fill and, from byte 4, the indirect dispatch of
// the tail level that takes it (a VkDispatchIndirectCommand), from byte 16
// that of its subgroup stage (STAGE_TAIL_SUBGROUP); one per level
// (PassParams.tail_level: the head fills level 0's, each level but the last
// the next one's), all reset before each head.
struct TailControl {
  uint count;     // paths the heads asked to queue (those past tail_capacity were not)
  uint groups_x;  // workgroups of 64 the tail needs: one per 64 slots taken
  uint groups_y;  // 1
  uint groups_z;  // 1
  // Workgroups of 64 the subgroup stage needs: one per 64 / subgroup size
  // slots among the first SPEC_TAIL_SUBGROUP taken (a level of more runs
  // in the tail stage, whose first invocation sets this to 0).
  uint subgroup_groups_x;
  uint subgroup_groups_y;  // 1
  uint subgroup_groups_z;  // 1
  uint fetched;  // with SPEC_TAIL_FETCH: the level's paths the tail stage's invocations have taken
};

// 16 bytes, the push constants of the resolve pass.
struct ResolveParams {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};

// Russian roulette draws from a stream of its own (bounce | RR_STREAM), so
// turning it on changes no other random number.
OCT_CONST(uint, RR_STREAM, 0x40000000u);
// BLEND's stochastic cut-out hashes a per-ray key (bounce | ALPHA_STREAM,
// with the pixel, sample and seed; path_trace.comp) with the triangle's id:
// no stream's numbers are drawn, so alpha changes no other random number.
OCT_CONST(uint, ALPHA_STREAM, 0x20000000u);
// Next-event estimation at bounce b draws from (bounce | NEE_STREAM), and
// its shadow ray's BLEND cut-out key from (bounce | NEE_STREAM |
// ALPHA_STREAM): turning it on or off changes no other random number.
OCT_CONST(uint, NEE_STREAM, 0x10000000u);
// A transmissive pbr surface's choice between reflecting and transmitting
// (shading/pbr.glsl) draws from a stream of its own (bounce |
// TRANSMISSION_STREAM), so transmission changes no other random number.
OCT_CONST(uint, TRANSMISSION_STREAM, 0x08000000u);

#ifdef __cplusplus
}  // namespace octrace::gpu
#undef OCT_CONST
#endif

#endif  // OCTRACE_SHARED_H
