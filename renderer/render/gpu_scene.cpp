#include "render/gpu_scene.h"

#include <algorithm>
#include <string>

#include <glm/gtc/packing.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "core/clock.h"
#include "core/errors.h"
#include "core/text.h"
#include "render/gpu_layout.h"

namespace octrace {

namespace {

// Half's largest finite value.
constexpr float kHalfMax = 65504.0f;

// Every array must fit one storage-buffer binding of the device: say which
// one does not, and why, before asking the driver for memory.
void check_fits(const VulkanContext& ctx, uint64_t bytes, const std::string& what) {
  const uint64_t limit = ctx.limits.maxStorageBufferRange;
  if (bytes > limit)
    throw InputError(what + " need " + mib_string(bytes) + ", the device allows " + mib_string(limit) +
                     " per buffer");
}


}  // namespace

void upload_octree(GpuScene& g, const VulkanContext& ctx, const Scene& scene, const OctreeParams& params) {
  auto start = Clock::now();
  const std::vector<Aabb> boxes = primitive_boxes(scene);
  Octree octree = build_octree(boxes, params);
  g.accel_build_ms = ms_since(start);
  g.octree = octree.stats;
  check_fits(ctx, octree.nodes.size() * sizeof(gpu::GpuOctreeNode),
             "the octree nodes of " + std::to_string(boxes.size()) + " primitives (a larger leaf size needs fewer)");
  check_fits(ctx, octree.refs.size() * sizeof(uint32_t),
             "the octree references of " + std::to_string(boxes.size()) + " primitives (a larger leaf size needs fewer)");
  start = Clock::now();
  create_buffer(g.nodes, ctx, octree.nodes.size() * sizeof(gpu::GpuOctreeNode), false, "octree node buffer");
  create_buffer(g.refs, ctx, octree.refs.size() * sizeof(uint32_t), false, "octree reference buffer");
  upload_buffer(ctx, g.nodes, octree.nodes.data(), octree.nodes.size() * sizeof(gpu::GpuOctreeNode));
  upload_buffer(ctx, g.refs, octree.refs.data(), octree.refs.size() * sizeof(uint32_t));
  g.values.big_count = octree.big_count;
  upload_buffer(ctx, g.params, &g.values, sizeof g.values);
  g.has_octree = true;
  g.upload_ms += ms_since(start);
}

std::vector<Aabb> sphere_boxes(const std::vector<Sphere>& spheres) {
  std::vector<Aabb> boxes(spheres.size());
  for (size_t i = 0; i < spheres.size(); ++i)
    boxes[i] = {spheres[i].center - spheres[i].radius, spheres[i].center + spheres[i].radius};
  return boxes;
}

namespace {

// Calls f(instance, mesh, object->world in double, flip) for every instance.
template <typename F>
void for_each_instance(const Scene& scene, F&& f) {
  for (const Instance& inst : scene.instances) {
    const glm::dmat4 m(inst.transform);
    const bool flip = glm::determinant(glm::dmat3(m)) < 0.0;
    f(scene.meshes[inst.mesh], m, flip);
  }
}

glm::vec3 to_world(const glm::dmat4& m, glm::vec3 p) { return glm::vec3(m * glm::dvec4(glm::dvec3(p), 1.0)); }

}  // namespace

std::vector<gpu::GpuTriangle> world_triangles(const Scene& scene) {
  std::vector<gpu::GpuTriangle> out;
  out.reserve(instanced_triangle_count(scene));
  for_each_instance(scene, [&](const Mesh& mesh, const glm::dmat4& m, bool flip) {
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      const uint32_t* idx = &mesh.indices[3 * k];
      gpu::GpuTriangle t{};
      t.v0 = to_world(m, mesh.positions[idx[0]]);
      t.v1 = to_world(m, mesh.positions[idx[flip ? 2 : 1]]);
      t.v2 = to_world(m, mesh.positions[idx[flip ? 1 : 2]]);
      t.material = mesh.materials[k];
      out.push_back(t);
    }
  });
  return out;
}

std::vector<gpu::GpuTriangleNormals> world_triangle_normals(const Scene& scene) {
  std::vector<gpu::GpuTriangleNormals> out;
  out.reserve(instanced_triangle_count(scene));
  for_each_instance(scene, [&](const Mesh& mesh, const glm::dmat4& m, bool flip) {
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(m)));
    const auto world_normal = [&](glm::vec3 n) { return glm::vec3(glm::normalize(normal_matrix * glm::dvec3(n))); };
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      const uint32_t* idx = &mesh.indices[3 * k];
      glm::vec3 n[3];
      if (mesh.normals.empty()) {
        // Flat: the geometric normal of the world triangle, whatever the winding.
        const glm::dvec3 a = m * glm::dvec4(glm::dvec3(mesh.positions[idx[0]]), 1.0);
        const glm::dvec3 b = m * glm::dvec4(glm::dvec3(mesh.positions[idx[flip ? 2 : 1]]), 1.0);
        const glm::dvec3 c = m * glm::dvec4(glm::dvec3(mesh.positions[idx[flip ? 1 : 2]]), 1.0);
        const glm::dvec3 g = glm::cross(b - a, c - a);
        const double len = glm::length(g);
        n[0] = n[1] = n[2] = len > 0.0 ? glm::vec3(g / len) : glm::vec3(0.0f, 0.0f, 1.0f);
      } else {
        n[0] = world_normal(mesh.normals[idx[0]]);
        n[1] = world_normal(mesh.normals[idx[flip ? 2 : 1]]);
        n[2] = world_normal(mesh.normals[idx[flip ? 1 : 2]]);
      }
      out.push_back({n[0], 0, n[1], 0, n[2], 0});
    }
  });
  return out;
}

std::vector<Aabb> primitive_boxes(const Scene& scene) {
  std::vector<Aabb> boxes = sphere_boxes(scene.spheres);
  for (const gpu::GpuTriangle& t : world_triangles(scene))
    boxes.push_back({glm::min(t.v0, glm::min(t.v1, t.v2)), glm::max(t.v0, glm::max(t.v1, t.v2))});
  return boxes;
}

void upload_scene(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel, const OctreeParams& params) {
  const uint64_t sphere_bytes = scene.spheres.size() * sizeof(gpu::GpuSphere);
  check_fits(ctx, sphere_bytes, std::to_string(scene.spheres.size()) + " spheres");

  auto start = Clock::now();
  std::vector<gpu::GpuSphere> spheres(scene.spheres.size());
  std::vector<uint32_t> sphere_materials(scene.spheres.size());
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    spheres[i] = {scene.spheres[i].center, scene.spheres[i].radius};
    sphere_materials[i] = scene.spheres[i].material;
  }
  std::vector<gpu::GpuMaterial> materials(scene.materials.size());
  std::vector<gpu::GpuMaterialHalf> materials_half(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    gpu::GpuMaterial& f = materials[i];
    f.type = uint32_t(m.type);
    f.color = m.type == MaterialType::Emissive ? m.radiance : m.albedo;
    f.fuzz = m.fuzz;
    f.ior = m.ior;
    materials_half[i].color_type = {glm::packHalf1x16(f.color.r), glm::packHalf1x16(f.color.g),
                                    glm::packHalf1x16(f.color.b), glm::packHalf1x16(float(f.type))};
    materials_half[i].params = {glm::packHalf1x16(f.fuzz), glm::packHalf1x16(f.ior), 0, 0};
  }
  gpu::SceneParams& p = g.values;
  p = {};
  const Sky& sky = scene.sky;
  p.sky_type = uint32_t(sky.type);
  p.sky_a = sky.type == SkyType::Uniform ? sky.radiance : sky.down;
  p.sky_b = sky.up;
  p.sphere_count = uint32_t(scene.spheres.size());

  const std::vector<gpu::GpuTriangle> triangles = world_triangles(scene);
  const uint64_t triangle_bytes = triangles.size() * sizeof(gpu::GpuTriangle);
  check_fits(ctx, triangle_bytes, std::to_string(triangles.size()) + " triangles");
  std::vector<gpu::GpuTriangleNormals> normals;
  bool any_normals = false;
  for (const Mesh& mesh : scene.meshes) any_normals |= !mesh.normals.empty();
  if (any_normals) normals = world_triangle_normals(scene);
  p.triangle_count = uint32_t(triangles.size());
  p.vertex_normals = any_normals ? 1u : 0u;

  create_buffer(g.params, ctx, sizeof p, false, "scene parameters");
  create_buffer(g.triangles, ctx, triangle_bytes, false, "triangle buffer");
  create_buffer(g.triangle_normals, ctx, normals.size() * sizeof(gpu::GpuTriangleNormals), false,
                "triangle normal buffer");
  upload_buffer(ctx, g.triangles, triangles.data(), triangle_bytes);
  upload_buffer(ctx, g.triangle_normals, normals.data(), normals.size() * sizeof(gpu::GpuTriangleNormals));
  create_buffer(g.spheres, ctx, sphere_bytes, false, "sphere buffer");
  create_buffer(g.sphere_materials, ctx, sphere_materials.size() * 4, false, "sphere material buffer");
  create_buffer(g.materials, ctx, materials.size() * sizeof(gpu::GpuMaterial), false, "material buffer");
  create_buffer(g.materials_half, ctx, materials_half.size() * sizeof(gpu::GpuMaterialHalf), false,
                "material buffer");
  create_buffer(g.nodes, ctx, 0, false, "octree node buffer");
  create_buffer(g.refs, ctx, 0, false, "octree reference buffer");
  upload_buffer(ctx, g.params, &p, sizeof p);
  upload_buffer(ctx, g.spheres, spheres.data(), sphere_bytes);
  upload_buffer(ctx, g.sphere_materials, sphere_materials.data(), sphere_materials.size() * 4);
  upload_buffer(ctx, g.materials, materials.data(), materials.size() * sizeof(gpu::GpuMaterial));
  upload_buffer(ctx, g.materials_half, materials_half.data(), materials_half.size() * sizeof(gpu::GpuMaterialHalf));
  g.upload_ms = ms_since(start);
  if (accel == Accel::Octree) upload_octree(g, ctx, scene, params);
}

void check_precision(const Scene& scene, Precision precision) {
  if (precision == Precision::FP32) return;
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const glm::vec3 color = m.type == MaterialType::Emissive ? m.radiance : m.albedo;
    if (std::max({color.r, color.g, color.b}) > kHalfMax)
      throw SettingError("precision", std::string(" ") + precision_name(precision) + ": materials[" +
                                          std::to_string(i) + "]: radiance above 65504 does not fit half");
  }
}

}  // namespace octrace
