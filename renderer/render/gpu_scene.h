// The scene on the device: the Scene's plain structs packed into the flat
// arrays of shaders/shared/shared.h and uploaded once, with the acceleration
// structure built over the primitives' boxes. Every pass, camera and pipeline
// of a PathTracer shares it.
#pragma once

#include <vector>

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
  Buffer materials;         // GpuMaterial per material (fp32)
  Buffer materials_half;    // GpuMaterialHalf per material (the fp16 variants)
  Buffer textures;          // GpuTexture per texture (the texture table)
  Buffer texels;            // every texture's texels, one uint (RGBA8) each
  Buffer triangle_uvs;      // GpuTriangleUvs per triangle (placeholder without textures)
  Buffer texture_transforms;  // GpuUvTransform per material and texture slot (placeholder without textures)
  Buffer nodes, refs;       // the octree (16-byte placeholders without one)
  // A hash of every array above but the octree, as uploaded (spheres,
  // materials, triangles, instances, textures, sky): the scene a checkpoint
  // belongs to.
  uint64_t content_hash = 0;
  Accel tree = Accel::Brute;  // what nodes and refs hold: Brute = placeholders, an octree or a BVH
  OctreeStats octree;  // of the octree or the BVH in nodes and refs
  double accel_build_ms = 0;  // octree or BVH build on the CPU (wall)
  double upload_ms = 0;       // packing, buffer creation and copies (wall)
};

// What the device holds of the meshes: a mesh placed by one instance only
// gains nothing from its own octree (and costs a transform and a second
// walk), so all of those are transformed into world space and baked into one
// mesh, placed once with no transform; meshes placed several times stay
// instanced. upload_scene and upload_octree apply it.
Scene bake_single_use_meshes(const Scene& scene);

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

// The top level's boxes in id order: spheres, then instances.
std::vector<Aabb> primitive_boxes(const Scene& scene);
std::vector<Aabb> sphere_boxes(const std::vector<Sphere>& spheres);

// The texture table and the texels of every texture, in the scene's order.
struct GpuTextures {
  std::vector<gpu::GpuTexture> table;
  std::vector<uint32_t> texels;
};
GpuTextures gpu_textures(const Scene& scene);

// Packs and uploads `scene`; with Accel::Octree or Accel::Bvh also builds and
// uploads that structure. Throws InputError when an array does not fit one storage buffer of
// the device (naming the array, its size and the limit).
void upload_scene(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel, const OctreeParams& params);

// Builds the octree (accel Octree) or the BVH (Bvh) over the scene's
// primitives and uploads it into nodes and refs (for a scene uploaded with
// another structure that then switches).
void upload_octree(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel,
                   const OctreeParams& params);

// Throws InputError when a value of the scene does not fit the precision
// (a radiance or emission beyond half's largest value, 65504, would be inf in fp16).
void check_precision(const Scene& scene, Precision precision);

}  // namespace octrace
