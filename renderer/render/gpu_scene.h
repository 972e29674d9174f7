// The scene on the device: the Scene's plain structs packed into the flat
// arrays of shaders/shared/shared.h and uploaded once, with the acceleration
// structure built over the primitives' boxes. Every pass, camera and pipeline
// of a PathTracer shares it.
#pragma once

#include <deque>
#include <vector>

#include <glm/vec2.hpp>

#include "accel/hidden_parts.h"
#include "accel/octree.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "shared/shared.h"
#include "vk/resources.h"

namespace octrace {

struct GpuScene {
  gpu::SceneParams values{};  // what `params` holds
  Buffer params;            // SceneParams
  Buffer spheres;           // GpuSphere per sphere
  Buffer triangles;         // GpuTriangle per unique triangle, object space
  Buffer triangle_normals;  // GpuTriangleNormals per triangle (placeholder without vertex normals)
  Buffer instances;         // GpuInstance per instance
  Buffer meshes;            // GpuMesh per mesh (roots filled in with the octree)
  Buffer sphere_materials;  // material index per sphere
  Buffer materials;         // GpuMaterial per material (fp32 renders; a placeholder until one needs it)
  Buffer materials_half;    // GpuMaterialHalf per material (the fp16 variants; the same)
  bool has_materials = false, has_materials_half = false;  // which of the two hold the materials
  Buffer textures;          // GpuTexture per texture (the texture table)
  Buffer texels;            // every texture's texels, one uint (RGBA8) each
  Buffer triangle_uvs;      // GpuTriangleUvs per triangle (placeholder without textures)
  Buffer texture_transforms;  // GpuUvTransform per material and texture slot (placeholder without textures)
  Buffer transmission;        // GpuTransmission per material (placeholder without transmission)
  Buffer nodes, refs;       // the octree (16-byte placeholders without one)
  Buffer lights;            // GpuLight per light (render/lights.h; placeholder without lights)
  Buffer sphere_lights;     // per sphere, its light's index (placeholder when no sphere emits)
  Buffer triangle_lights;   // per instance and triangle, its light's index (shared.h; {0} when no triangle emits)
  // The environment map's texels (3 floats each) and sampling tables
  // (scene/envmap.h; placeholders without an envmap).
  Buffer envmap_texels, envmap_marginal, envmap_conditional;
  // A scene larger than one storage buffer (shaders/shared/scene_buffers.glsl):
  // log2 of the largest part in bytes, 0 when every array has one buffer
  // (spheres ... refs above). Split, those are 16-byte placeholders and the
  // arrays lie in `parts`, whose addresses `part_table` holds (uvec2 per
  // [SPLIT_* * MAX_PARTS + part]; a placeholder when not split).
  uint32_t part_log2 = 0;
  std::deque<Buffer> parts;
  std::vector<glm::uvec2> part_addresses;
  Buffer part_table;
  // A hash of every array above but the octree, as uploaded (spheres,
  // materials, triangles, instances, textures, sky, lights; the spheres in
  // the scene's order): the scene a checkpoint belongs to.
  uint64_t content_hash = 0;
  Accel tree = Accel::Brute;  // what nodes and refs hold: Brute = placeholders, an octree or a BVH
  // Of the octree or the BVH in nodes and refs; its bvh_sphere_order: whether
  // spheres, their materials and lights are in that BVH's reference order
  // instead of the scene's (gpu_scene.cpp device_sphere_order).
  OctreeStats octree;
  double accel_build_ms = 0;  // octree or BVH build on the CPU (wall)
  double upload_ms = 0;       // packing, buffer creation and copies (wall)
};

// What the device holds of the meshes: a mesh placed by one instance only
// gains nothing from its own octree (and costs a transform and a second
// walk), so all of those are transformed into world space and baked into one
// mesh, placed once with no transform; meshes placed several times stay
// instanced. With `every_instance`, the placements of shared meshes are
// baked too (a copy of the mesh for each), and the scene has no instance
// left but the baked mesh's.
Scene bake_single_use_meshes(const Scene& scene, bool every_instance = false);

// Whether `instancing` bakes every instance of `scene`: bakes_every_instance
// (render/settings.h) of its stored and placed triangles.
bool bakes_every_instance(const Scene& scene, Instancing instancing);

// The device's view of the scene's meshes (upload_scene and upload_octree
// apply it): bake_single_use_meshes, every instance baked where
// bakes_every_instance says so.
Scene device_meshes(const Scene& scene, Instancing instancing);

// Meshes are stored once, in object space (mesh order, then triangle order);
// instances refer to them. Two levels of octree: the top over spheres and
// instances' world boxes, one per mesh over its triangles (upload_octree).
std::vector<gpu::GpuTriangle> object_triangles(const Scene& scene);
std::vector<gpu::GpuTriangleNormals> object_triangle_normals(const Scene& scene);
std::vector<gpu::GpuTriangleUvs> object_triangle_uvs(const Scene& scene);
std::vector<gpu::GpuInstance> gpu_instances(const Scene& scene);
std::vector<gpu::GpuMesh> gpu_meshes(const Scene& scene);  // roots not filled in
// A mesh's triangle boxes in object space; each instance's world box (its
// mesh's object box, transformed).
std::vector<Aabb> mesh_triangle_boxes(const Mesh& mesh);
std::vector<Aabb> instance_boxes(const Scene& scene);

// Whether rays never enter a sphere of material m (lambertian, metal,
// emissive; pbr without transmission or alpha): what may hide another
// sphere's parts (accel/hidden_parts.h).
bool occludes(const Material& m);
// Per sphere: whether it occludes (opaque, and its ball keeps clear of the
// camera's lens, from which rays start).
std::vector<uint8_t> sphere_occluders(const Scene& scene);
// The top level's boxes in id order: spheres, then instances. With
// HiddenParts::Cull a sphere's box holds only the parts of it that no
// occluder holds (visible_sphere_boxes), for the scene's camera; `stats`
// says how many shrank.
std::vector<Aabb> primitive_boxes(const Scene& scene, HiddenParts hidden = HiddenParts::Cull,
                                  HiddenPartsStats* stats = nullptr);
std::vector<Aabb> sphere_boxes(const std::vector<Sphere>& spheres);
// The top level's ClipFn over the spheres' surfaces (optimisation log 126):
// primitive i < spheres.size() reaches a cell where its surface does within
// boxes[i] (its visible box, primitive_boxes), with the box of that part
// (accel/clip.h clip_sphere_surface); a primitive past the spheres (an
// instance) is its box within the cell. Holds references to both.
ClipFn sphere_surface_clip(std::span<const Sphere> spheres, std::span<const Aabb> boxes);

// The texture table and the texels of every texture, in the scene's order.
struct GpuTextures {
  std::vector<gpu::GpuTexture> table;
  std::vector<uint32_t> texels;
};
GpuTextures gpu_textures(const Scene& scene);

// Packs and uploads `scene`; with Accel::Octree or Accel::Bvh also builds
// and uploads that structure. An array larger than one storage buffer
// (max_buffer_bytes) splits the whole scene into parts (GpuScene::part_log2),
// where the device has buffer device addresses. Throws InputError when the
// scene, with the `reserved_bytes` already allocated for the render (the
// accumulation), needs more than the device's memory (device_memory), when an
// array needs more than MAX_PARTS parts, or, without buffer device addresses,
// when an array does not fit one storage buffer (naming the array, its size
// and the limit). The materials go up as `precision` reads them only
// (GpuMaterial for fp32, GpuMaterialHalf for the fp16 variants); another
// precision later needs upload_materials. content_hash covers both forms
// either way, as it always has.
void upload_scene(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel, const OctreeParams& params,
                  uint64_t reserved_bytes = 0, Precision precision = Precision::FP32);

// The materials as `precision` reads them, for a scene on the device that
// lacks that form (a reconfigure to another precision); nothing where it
// has it. Throws InputError, leaving the device as it was, where the scene
// was uploaded whole and the form would not fit one storage buffer.
void upload_materials(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Precision precision);

// Builds the octree (accel Octree) or the BVH (Bvh) over the scene's
// primitives and uploads it into nodes and refs (for a scene uploaded with
// another structure that then switches; a scene uploaded whole whose tree
// would need splitting is refused: render it with that structure from the
// start).
void upload_octree(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel,
                   const OctreeParams& params);

// Throws InputError when a value of the scene does not fit the precision
// (a radiance or emission beyond half's largest value, 65504, would be inf in
// fp16; so would an envmap texel whose strength x value exceeds it: the fp16
// variants carry the sky's radiance in half, while the texels and the
// sampling tables stay fp32).
void check_precision(const Scene& scene, Precision precision);

}  // namespace octrace
