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
  Buffer triangles;         // GpuTriangle per instanced triangle, world space
  Buffer triangle_normals;  // GpuTriangleNormals per triangle (placeholder without vertex normals)
  Buffer sphere_materials;  // material index per sphere
  Buffer materials;         // GpuMaterial per material (fp32)
  Buffer materials_half;    // GpuMaterialHalf per material (the fp16 variants)
  Buffer nodes, refs;       // the octree (16-byte placeholders without one)
  bool has_octree = false;
  OctreeStats octree;
  double accel_build_ms = 0;  // octree build on the CPU (wall)
  double upload_ms = 0;       // packing, buffer creation and copies (wall)
};

// Every instance's triangles in world space, in instance order then mesh
// order: the triangle primitives. An instance whose transform has a negative
// determinant (a mirror) gets its winding flipped, so that counter-clockwise
// stays the front; normals go through the inverse transpose.
std::vector<gpu::GpuTriangle> world_triangles(const Scene& scene);
std::vector<gpu::GpuTriangleNormals> world_triangle_normals(const Scene& scene);

// The primitives' boxes, in primitive-id order (spheres, then triangles):
// what the octree is built over.
std::vector<Aabb> primitive_boxes(const Scene& scene);
std::vector<Aabb> sphere_boxes(const std::vector<Sphere>& spheres);

// Packs and uploads `scene`; with Accel::Octree also builds and uploads its
// octree. Throws InputError when an array does not fit one storage buffer of
// the device (naming the array, its size and the limit).
void upload_scene(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel, const OctreeParams& params);

// Builds the octree over the scene's primitives and uploads it (for a scene
// uploaded with Accel::Brute that then switches to the octree).
void upload_octree(GpuScene& g, const VulkanContext& ctx, const Scene& scene, const OctreeParams& params);

// Throws InputError when a value of the scene does not fit the precision
// (a radiance beyond half's largest value, 65504, would be inf in fp16).
void check_precision(const Scene& scene, Precision precision);

}  // namespace octrace
