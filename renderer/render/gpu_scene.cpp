#include "render/gpu_scene.h"

#include "accel/bvh.h"
#include "accel/clip.h"
#include "accel/hidden_parts.h"

#include <algorithm>
#include <bit>
#include <optional>
#include <string>

#include <glm/gtc/packing.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "core/clock.h"
#include "core/hash.h"
#include "core/errors.h"
#include "core/text.h"
#include "render/gpu_layout.h"
#include "scene/envmap.h"
#include "render/lights.h"

namespace octrace {

namespace {

// Half's largest finite value.
constexpr float kHalfMax = 65504.0f;

// An array that must fit one storage-buffer binding of the device (`limit`
// bytes): say which one does not, and why, before asking the driver for memory.
void check_fits(uint64_t limit, uint64_t bytes, const std::string& what, const std::string& hint = "") {
  if (bytes > limit)
    throw SceneSizeError(what + " need " + byte_string(bytes) + ", the device allows " + byte_string(limit) +
                         " per buffer" + hint);
}

// Elements of an array split into parts (scene_buffers.glsl): a part of at
// most 2^part_log2 bytes holds 2^(part_log2 - ceil(log2 size)) elements. The
// shader has these exponents written in; they must match the structs.
template <typename T>
constexpr uint32_t size_log2() {
  return uint32_t(std::bit_width(sizeof(T) - 1));
}
static_assert(size_log2<gpu::GpuSphere>() == 4 && size_log2<uint32_t>() == 2 &&
                  size_log2<gpu::GpuTriangle>() == 6 && size_log2<gpu::GpuTriangleNormals>() == 6 &&
                  size_log2<gpu::GpuTriangleUvs>() == 5 && size_log2<gpu::GpuOctreeNode>() == 5 &&
                  size_log2<gpu::GpuMaterial>() == 7 && size_log2<gpu::GpuMaterialHalf>() == 6,
              "shaders/shared/scene_buffers.glsl's part shifts");

// Uploads `data` as the scene's array `array` (SPLIT_*): into `whole` for a
// scene in one buffer per array, else into parts, whose addresses go into
// g.part_addresses (`whole` is then a placeholder). `data` is freed once on
// the device (on a CPU device both are host memory: the peak stays lower).
template <typename T>
void upload_array(GpuScene& g, const VulkanContext& ctx, uint32_t array, Buffer& whole, std::vector<T>&& data,
                  const std::string& what) {
  const uint64_t bytes = data.size() * sizeof(T);
  if (g.part_log2 == 0) {
    create_buffer(whole, ctx, bytes, false, what);
    upload_buffer(ctx, whole, data.data(), bytes);
  } else {
    create_buffer(whole, ctx, 0, false, what);
    const uint64_t per_part = uint64_t(1) << (g.part_log2 - size_log2<T>());
    for (uint64_t first = 0, k = 0; first < data.size(); first += per_part, ++k) {
      const uint64_t n = std::min<uint64_t>(per_part, data.size() - first);
      Buffer& part = g.parts.emplace_back();
      create_buffer(part, ctx, n * sizeof(T), false, what + " part " + std::to_string(k), true);
      upload_buffer(ctx, part, data.data() + first, n * sizeof(T));
      const VkDeviceAddress a = buffer_address(part);
      g.part_addresses[array * gpu::MAX_PARTS + k] = {uint32_t(a), uint32_t(a >> 32)};
    }
  }
  std::vector<T>().swap(data);
}

void upload_part_table(GpuScene& g, const VulkanContext& ctx) {
  const uint64_t bytes = g.part_addresses.size() * sizeof(glm::uvec2);
  if (g.part_table.size < std::max<uint64_t>(bytes, 16)) create_buffer(g.part_table, ctx, bytes, false, "part table");
  upload_buffer(ctx, g.part_table, g.part_addresses.data(), bytes);
}


// The unit normal of triangle (a, b, c) by its winding (in double: thin
// triangles lose nothing to the cross product), +z for one of no area.
glm::vec3 face_normal(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::dvec3 g = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  const double len = glm::length(g);
  return len > 0.0 ? glm::vec3(g / len) : glm::vec3(0.0f, 0.0f, 1.0f);
}

// A material as the fp32 variant reads it, written field by field into `f`
// (zeroed by its owner, so that its bytes, which the checkpoint hash reads,
// are the same wherever it is made).
void fill_gpu_material(const Material& m, gpu::GpuMaterial& f) {
  f.type = uint32_t(m.type);
  f.color = m.type == MaterialType::Emissive ? m.radiance : m.albedo;
  // A pbr material's transmission sits in the fuzz slot, negated when thin-walled (shared.h).
  f.fuzz = m.type != MaterialType::Pbr ? m.fuzz : m.thin_walled ? -m.transmission : m.transmission;
  f.ior = m.ior;
  f.base_color_texture = m.base_color_texture.value_or(gpu::NO_TEXTURE);
  f.emission_texture = m.emission_texture.value_or(gpu::NO_TEXTURE);
  f.emission = m.emission;
  f.metallic_roughness_texture = m.metallic_roughness_texture.value_or(gpu::NO_TEXTURE);
  f.metallic = m.metallic;
  f.roughness = m.roughness;
  f.normal_texture = m.normal_texture.value_or(gpu::NO_TEXTURE);
  f.normal_scale = m.normal_scale;
  f.alpha_mode = uint32_t(m.alpha_mode);
  f.alpha_cutoff = m.alpha_cutoff;
  f.alpha = m.alpha;
  f.double_sided = m.double_sided ? 1u : 0u;
}

// The same material as the fp16 variants read it, into `h` (zeroed, as above).
void fill_gpu_material_half(const gpu::GpuMaterial& f, gpu::GpuMaterialHalf& h) {
  h.color_type = {glm::packHalf1x16(f.color.r), glm::packHalf1x16(f.color.g), glm::packHalf1x16(f.color.b),
                  glm::packHalf1x16(float(f.type))};
  h.params = {glm::packHalf1x16(f.fuzz), glm::packHalf1x16(f.ior), glm::packHalf1x16(f.metallic),
              glm::packHalf1x16(f.roughness)};
  h.emission = {glm::packHalf1x16(f.emission.r), glm::packHalf1x16(f.emission.g), glm::packHalf1x16(f.emission.b), 0};
  h.base_color_texture = f.base_color_texture;
  h.emission_texture = f.emission_texture;
  h.metallic_roughness_texture = f.metallic_roughness_texture;
  h.normal_texture = f.normal_texture;
  h.normal_scale = f.normal_scale;
  h.alpha_mode = f.alpha_mode;
  h.alpha_cutoff = f.alpha_cutoff;
  h.alpha = f.alpha;
  h.double_sided = f.double_sided;
}

// The scene's materials as the fp32 variant reads them, and as the fp16
// variants do.
std::vector<gpu::GpuMaterial> gpu_materials(const Scene& scene) {
  std::vector<gpu::GpuMaterial> out(scene.materials.size());
  for (size_t i = 0; i < out.size(); ++i) fill_gpu_material(scene.materials[i], out[i]);
  return out;
}
// With `full_hash`, each material's fp32 form, made on the way, is added to
// it as a piece (Hash64::add_piece; the caller ends the pieces).
std::vector<gpu::GpuMaterialHalf> gpu_materials_half(const Scene& scene, Hash64* full_hash = nullptr) {
  std::vector<gpu::GpuMaterialHalf> out(scene.materials.size());
  for (size_t i = 0; i < out.size(); ++i) {
    gpu::GpuMaterial f = gpu::GpuMaterial();
    fill_gpu_material(scene.materials[i], f);
    if (full_hash) full_hash->add_piece(&f, sizeof f);
    fill_gpu_material_half(f, out[i]);
  }
  return out;
}

// Refuses an array (`what`, `elements` of 2^size_log2 bytes or fewer, `bytes`
// in all) that needs more than MAX_PARTS parts of 2^part_log2 bytes, on a
// device that allows `limit` bytes per buffer.
void check_part_count(uint32_t part_log2, uint64_t elements, uint32_t size_log2, uint64_t bytes,
                      const std::string& what, uint64_t limit) {
  const uint64_t per_part = uint64_t(1) << (part_log2 - size_log2);
  if ((elements + per_part - 1) / per_part > gpu::MAX_PARTS)
    throw SceneSizeError(what + " need " + byte_string(bytes) + ", more than " + std::to_string(gpu::MAX_PARTS) +
                         " buffers of " + byte_string(per_part << size_log2) + " (the device allows " +
                         byte_string(limit) + " per buffer)");
}

// The scene's materials in the form the render's precision reads (`half`:
// into `stored_half`, else into `full`; the other stays empty), and both
// forms into `hash` as add_vector of each whole would add them (the hash of
// the days both were uploaded for every render: a checkpoint's scene hash
// stays what it was). Each material's fp32 form is made once; the form not
// stored is hashed piece by piece.
void make_materials(const Scene& scene, bool half, Hash64& hash, std::vector<gpu::GpuMaterial>& full,
                    std::vector<gpu::GpuMaterialHalf>& stored_half) {
  static_assert(sizeof(gpu::GpuMaterial) % 8 == 0 && sizeof(gpu::GpuMaterialHalf) % 8 == 0, "Hash64::add_piece");
  const size_t n = scene.materials.size();
  if (!half) {
    full = gpu_materials(scene);
    hash.add_vector(full);
    for (const gpu::GpuMaterial& f : full) {
      gpu::GpuMaterialHalf h = gpu::GpuMaterialHalf();
      fill_gpu_material_half(f, h);
      hash.add_piece(&h, sizeof h);
    }
    hash.end_pieces(n * sizeof(gpu::GpuMaterialHalf));
    return;
  }
  stored_half = gpu_materials_half(scene, &hash);
  hash.end_pieces(n * sizeof(gpu::GpuMaterial));
  hash.add_vector(stored_half);
}

uint64_t texel_count(const Scene& scene) {
  uint64_t n = 0;
  for (const Texture& t : scene.textures) n += t.texels.size();
  return n;
}

}  // namespace

// The octree or BVH (`accel`: both fill the same arrays) of the device's
// view of the scene (device_meshes applied), with the meshes' roots
// filled in and its statistics and build time in octree.stats, which
// upload_scene_octree puts in `g` with the arrays.
struct SceneOctree {
  Octree octree;
  std::vector<gpu::GpuMesh> meshes;
};

// The widths of a scene's BVHs, top level and meshes: params.bvh_width for
// both, or (0) the device's default (accel/bvh.h default_bvh_widths).
static BvhWidths bvh_widths(const VulkanContext& ctx, const Scene& scene, const OctreeParams& params) {
  if (params.bvh_width != 0) return {params.bvh_width, params.bvh_width};
  return default_bvh_widths(ctx.info.software, !scene.spheres.empty());
}

static SceneOctree build_scene_octree_once(const VulkanContext& ctx, const Scene& scene, Accel accel,
                                           const OctreeParams& params) {
  auto start = Clock::now();
  // The top level over spheres and instances, then one tree per mesh in
  // object space, appended: their `first` fields are moved by where they land.
  HiddenPartsStats hidden;
  const std::vector<Aabb> boxes = primitive_boxes(scene, params.hidden_parts, &hidden);
  // A BVH's widths per level, kept in its stats (below), which the
  // pipeline's SPEC_BVH_TOP_WIDE and SPEC_BVH_MESH_WIDE follow.
  const BvhWidths widths = bvh_widths(ctx, scene, params);
  // Where spheres' boxes were clipped to their visible parts (a dense field of
  // overlapping spheres), the octree also clips each sphere to its surface
  // in a cell: the middle of a visible column lies inside the ball, so the
  // cells can part its top cap from its bottom one (optimisation log 126;
  // OctreeParams::surface_cells: the tracer resolves auto by the device and
  // the render's samples, path_tracer.h default_surface_cells; a caller that
  // leaves it auto gets the boxes). Elsewhere the top level is the boxes, as
  // before.
  const bool clip_surfaces =
      accel == Accel::Octree && hidden.clipped > 0 && params.surface_cells == SurfaceCells::On;
  SceneOctree t{accel == Accel::Bvh ? build_bvh(boxes, widths.top, {}, kBvhSpatialRefs, kBvhTopNodeCost)
                                    : build_octree(boxes, params, clip_surfaces ? sphere_surface_clip(scene.spheres, boxes) : ClipFn{}, {},
                                                   clip_surfaces),
                gpu_meshes(scene)};
  Octree& octree = t.octree;
  OctreeStats& st = octree.stats;
  st.top_leaves = st.leaves;
  st.spheres_clipped = hidden.clipped;
  st.spheres_hidden = hidden.hidden;
  st.hidden_parts_ms = hidden.ms;
  st.surface_cells = clip_surfaces;
  st.top_refs = octree.refs.size();
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    // Triangles are clipped to the cells they reach (octree.h ClipFn), and
    // to the BVH's spatial splits (bvh.h).
    const auto clip = [&mesh](uint32_t t, const Aabb& cell, Aabb& part) {
      const uint32_t* v = &mesh.indices[3 * size_t(t)];
      return clip_triangle(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]], cell, part);
    };
    const auto clip_octants = [&mesh](uint32_t t, const Aabb& box, const glm::vec3& mid, uint32_t candidates,
                                      Aabb parts[8]) {
      const uint32_t* v = &mesh.indices[3 * size_t(t)];
      return clip_triangle_octants(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]], box, mid,
                                   candidates, parts);
    };
    const Octree mesh_tree =
        accel == Accel::Bvh ? build_bvh(mesh_triangle_boxes(mesh), widths.meshes, clip, params.bvh_spatial_refs)
                            : build_octree(mesh_triangle_boxes(mesh), params, clip, clip_octants);
    const uint32_t node_base = uint32_t(octree.nodes.size()), ref_base = uint32_t(octree.refs.size());
    for (gpu::GpuOctreeNode n : mesh_tree.nodes) {
      n.first += (n.count_or_mask & gpu::OCTREE_INTERNAL) ? node_base : ref_base;
      octree.nodes.push_back(n);
    }
    octree.refs.insert(octree.refs.end(), mesh_tree.refs.begin(), mesh_tree.refs.end());
    t.meshes[m].root = node_base;
    t.meshes[m].first_ref = ref_base;
    t.meshes[m].big_count = mesh_tree.big_count;
    st.leaves += mesh_tree.stats.leaves;
    st.max_depth_reached = std::max(st.max_depth_reached, mesh_tree.stats.max_depth_reached);
  }
  const uint64_t primitives = scene.spheres.size() + unique_triangle_count(scene);
  st.nodes = uint32_t(octree.nodes.size());
  st.refs = octree.refs.size();
  st.bytes = octree.nodes.size() * sizeof(gpu::GpuOctreeNode) + octree.refs.size() * sizeof(uint32_t);
  st.refs_per_primitive = primitives ? double(st.refs) / double(primitives) : 0.0;
  st.bytes_per_primitive = primitives ? double(st.bytes) / double(primitives) : 0.0;
  st.build_ms = ms_since(start);
  if (accel == Accel::Bvh) {
    st.bvh_top_width = widths.top;
    st.bvh_mesh_width = widths.meshes;
  }
  return t;
}

// The scene's tree; an octree with copy leaves (the tracer's auto for
// triangles on a GPU: path_tracer.h default_copy_leaf) over
// kOctreeBytesBound bytes a primitive is built again with kOctreeRefs
// references and none.
static SceneOctree build_scene_octree(const VulkanContext& ctx, const Scene& scene, Accel accel,
                                      const OctreeParams& params) {
  SceneOctree t = build_scene_octree_once(ctx, scene, accel, params);
  const OctreeStats& first = t.octree.stats;
  if (accel != Accel::Octree || params.copy_leaf == 0 || first.bytes_per_primitive <= kOctreeBytesBound) return t;
  OctreeParams measured = params;
  measured.max_refs = kOctreeRefs;
  measured.copy_leaf = 0;
  SceneOctree again = build_scene_octree_once(ctx, scene, accel, measured);
  again.octree.stats.build_ms += first.build_ms;
  again.octree.stats.first_bytes_per_primitive = first.bytes_per_primitive;
  return again;
}

// Where the octree's arrays would not fit one storage buffer: what the
// message names.
static std::string octree_what(const Scene& scene, const char* array) {
  return std::string("the octree ") + array + " of " +
         std::to_string(scene.spheres.size() + unique_triangle_count(scene)) +
         " primitives (a larger leaf size needs fewer)";
}

// The spheres as the device holds them, with their materials' indices.
struct SphereArrays {
  std::vector<gpu::GpuSphere> spheres;
  std::vector<uint32_t> materials;
};

static SphereArrays sphere_arrays(const Scene& scene) {
  SphereArrays a{std::vector<gpu::GpuSphere>(scene.spheres.size()), std::vector<uint32_t>(scene.spheres.size())};
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    a.spheres[i] = {scene.spheres[i].center, scene.spheres[i].radius};
    a.materials[i] = scene.spheres[i].material;
  }
  return a;
}

// The order the device holds the spheres in: the scene index of the sphere
// at each position, or empty for the scene's own order. Where the top level
// is a BVH over spheres alone (no instances), its references are a
// permutation of the spheres, and the spheres go in that order, so that a
// leaf's references [first, first + count) are the positions of its spheres
// themselves: the walk tests sphere k without reading refs[k] first (one
// dependent load fewer per leaf), and the spheres of neighbouring leaves are
// neighbours in memory (SPEC_SPHERES_IN_TREE_ORDER; optimisation log 61).
// refs, unchanged, then gives each position's scene index, which exact ties
// go by (test_sphere), so the image is the one of the scene's order. Not for
// a scene split into parts (scene_buffers.glsl): switching structures
// (reconfigure) uploads the spheres again, into the buffers they have.
static std::vector<uint32_t> device_sphere_order(const GpuScene& g, const VulkanContext& ctx, const Scene& scene,
                                                 Accel accel, const OctreeParams& params, const Octree& tree) {
  const bool tree_order = params.bvh_sphere_order == SphereOrder::Auto ? !ctx.info.software
                                                                        : params.bvh_sphere_order == SphereOrder::Tree;
  if (accel != Accel::Bvh || !tree_order || scene.spheres.empty() || !scene.instances.empty() || g.part_log2 != 0)
    return {};
  return {tree.refs.begin(), tree.refs.begin() + scene.spheres.size()};
}

// Puts the sphere arrays and the lights in `order` (device_sphere_order):
// position k holds scene sphere order[k], and a sphere's light names its position.
static void put_spheres_in_order(const std::vector<uint32_t>& order, SphereArrays& a, LightList& lights) {
  if (order.empty()) return;
  std::vector<uint32_t> position(order.size());
  SphereArrays b{std::vector<gpu::GpuSphere>(order.size()), std::vector<uint32_t>(order.size())};
  std::vector<uint32_t> sphere_lights(lights.sphere_lights.size());
  for (size_t k = 0; k < order.size(); ++k) {
    position[order[k]] = uint32_t(k);
    b.spheres[k] = a.spheres[order[k]];
    b.materials[k] = a.materials[order[k]];
    if (!sphere_lights.empty()) sphere_lights[k] = lights.sphere_lights[order[k]];
  }
  a = std::move(b);
  lights.sphere_lights = std::move(sphere_lights);
  for (gpu::GpuLight& l : lights.lights)
    if (l.sphere != gpu::NO_LIGHT) l.sphere = position[l.sphere];
}

// After a tree was built for a scene already on the device (reconfigure),
// before it replaces the one there (g.octree): the spheres, their materials
// and the lights again, where the new tree wants them in another order than
// the device holds them in.
static void order_spheres_for(GpuScene& g, const VulkanContext& ctx, const Scene& scene,
                              const std::vector<uint32_t>& order) {
  if (order.empty() && !g.octree.bvh_sphere_order) return;
  SphereArrays a = sphere_arrays(scene);
  LightList lights = build_light_list(scene);
  put_spheres_in_order(order, a, lights);
  upload_buffer(ctx, g.spheres, a.spheres.data(), a.spheres.size() * sizeof(gpu::GpuSphere));
  upload_buffer(ctx, g.sphere_materials, a.materials.data(), a.materials.size() * sizeof(uint32_t));
  upload_buffer(ctx, g.lights, lights.lights.data(), lights.lights.size() * sizeof(gpu::GpuLight));
  upload_buffer(ctx, g.sphere_lights, lights.sphere_lights.data(), lights.sphere_lights.size() * 4);
}

static void upload_scene_octree(GpuScene& g, const VulkanContext& ctx, SceneOctree&& t, Accel accel) {
  const auto start = Clock::now();
  Octree& octree = t.octree;
  upload_array(g, ctx, gpu::SPLIT_OCTREE_NODES, g.nodes, std::move(octree.nodes), "octree node buffer");
  upload_array(g, ctx, gpu::SPLIT_OCTREE_REFS, g.refs, std::move(octree.refs), "octree reference buffer");
  upload_buffer(ctx, g.meshes, t.meshes.data(), t.meshes.size() * sizeof(gpu::GpuMesh));
  g.values.big_count = octree.big_count;
  upload_buffer(ctx, g.params, &g.values, sizeof g.values);
  upload_part_table(g, ctx);
  g.tree = accel;
  g.octree = octree.stats;
  g.accel_build_ms = octree.stats.build_ms;
  g.upload_ms += ms_since(start);
}

static void upload_octree_of(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel,
                             const OctreeParams& params) {
  SceneOctree t = build_scene_octree(ctx, scene, accel, params);
  if (g.part_log2 == 0) {
    // Uploaded whole, the scene's pipeline reads one buffer per array.
    check_fits(max_buffer_bytes(ctx), t.octree.nodes.size() * sizeof(gpu::GpuOctreeNode), octree_what(scene, "nodes"),
               " (render with the octree from the start to split the scene)");
    check_fits(max_buffer_bytes(ctx), t.octree.refs.size() * sizeof(uint32_t), octree_what(scene, "references"),
               " (render with the octree from the start to split the scene)");
  }
  // Only once the new tree fits: a refused one leaves the device as it was.
  const std::vector<uint32_t> order = device_sphere_order(g, ctx, scene, accel, params, t.octree);
  order_spheres_for(g, ctx, scene, order);
  t.octree.stats.bvh_sphere_order = !order.empty();
  upload_scene_octree(g, ctx, std::move(t), accel);
}

std::vector<gpu::GpuMesh> gpu_meshes(const Scene& scene) {
  std::vector<gpu::GpuMesh> out;
  uint32_t first = 0;
  for (const Mesh& mesh : scene.meshes) {
    gpu::GpuMesh m{};
    m.first_triangle = first;
    m.triangle_count = uint32_t(mesh.triangle_count());
    first += m.triangle_count;
    out.push_back(m);
  }
  return out;
}

std::vector<Aabb> sphere_boxes(const std::vector<Sphere>& spheres) {
  std::vector<Aabb> boxes(spheres.size());
  for (size_t i = 0; i < spheres.size(); ++i)
    boxes[i] = {spheres[i].center - spheres[i].radius, spheres[i].center + spheres[i].radius};
  return boxes;
}

std::vector<gpu::GpuTriangle> object_triangles(const Scene& scene) {
  std::vector<gpu::GpuTriangle> out;
  out.reserve(unique_triangle_count(scene));
  for (const Mesh& mesh : scene.meshes)
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      const uint32_t* idx = &mesh.indices[3 * k];
      out.push_back({mesh.positions[idx[0]], mesh.materials[k], mesh.positions[idx[1]], 0, mesh.positions[idx[2]], 0});
    }
  return out;
}

uint32_t pack_tangent(glm::vec4 t) {
  // Octahedral encoding (shared.h): project onto the octahedron |x| + |y| +
  // |z| = 1, fold the lower half over the upper (Cigolle et al. 2014,
  // listing 1), quantise each coordinate to 15 bits.
  const glm::vec3 v(t);
  const float l1 = std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
  if (!(l1 > 0.0f) || t.w == 0.0f) return 0;  // none, or no direction: the uvs' frame
  glm::vec2 p = glm::vec2(v) / l1;
  if (v.z < 0.0f) {
    const glm::vec2 sign(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    p = (1.0f - glm::abs(glm::vec2(p.y, p.x))) * sign;
  }
  const auto unorm = [](float x) {
    return uint32_t(std::lround(std::clamp(0.5f * x + 0.5f, 0.0f, 1.0f) * float(gpu::TANGENT_UNORM_MAX)));
  };
  return gpu::TANGENT_PRESENT | (t.w < 0.0f ? gpu::TANGENT_NEGATIVE_W : 0u) | unorm(p.x) | unorm(p.y) << 15;
}

std::vector<gpu::GpuTriangleNormals> object_triangle_normals(const Scene& scene) {
  std::vector<gpu::GpuTriangleNormals> out;
  out.reserve(unique_triangle_count(scene));
  for (const Mesh& mesh : scene.meshes)
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      const uint32_t* idx = &mesh.indices[3 * k];
      glm::vec3 n[3];
      if (mesh.normals.empty()) {
        // Flat: the geometric normal, so that a flat mesh beside smooth ones shades as itself.
        n[0] = n[1] = n[2] = face_normal(mesh.positions[idx[0]], mesh.positions[idx[1]], mesh.positions[idx[2]]);
      } else {
        for (int v = 0; v < 3; ++v) n[v] = mesh.normals[idx[v]];
      }
      uint32_t t[3] = {0, 0, 0};
      if (!mesh.tangents.empty())
        for (int v = 0; v < 3; ++v) t[v] = pack_tangent(mesh.tangents[idx[v]]);
      out.push_back({n[0], t[0], n[1], t[1], n[2], t[2]});
    }
  return out;
}

std::vector<gpu::GpuTriangleUvs> object_triangle_uvs(const Scene& scene) {
  std::vector<gpu::GpuTriangleUvs> out;
  out.reserve(unique_triangle_count(scene));
  for (const Mesh& mesh : scene.meshes)
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      gpu::GpuTriangleUvs t{};
      if (!mesh.uvs.empty()) {
        const uint32_t* idx = &mesh.indices[3 * k];
        t = {mesh.uvs[idx[0]], mesh.uvs[idx[1]], mesh.uvs[idx[2]]};
      }
      out.push_back(t);
    }
  return out;
}

GpuTextures gpu_textures(const Scene& scene) {
  GpuTextures out;
  out.texels.reserve(texel_count(scene));
  for (const Texture& t : scene.textures) {
    const uint32_t wrap = uint32_t(t.wrap_s) | uint32_t(t.wrap_t) << 16;
    out.table.push_back({uint32_t(out.texels.size()), t.width, t.height, wrap});
    out.texels.insert(out.texels.end(), t.texels.begin(), t.texels.end());
  }
  return out;
}

std::vector<Aabb> mesh_triangle_boxes(const Mesh& mesh) {
  std::vector<Aabb> boxes(mesh.triangle_count());
  for (size_t k = 0; k < boxes.size(); ++k)
    for (int v = 0; v < 3; ++v) boxes[k].extend({mesh.positions[mesh.indices[3 * k + v]], mesh.positions[mesh.indices[3 * k + v]]});
  return boxes;
}

std::vector<Aabb> instance_boxes(const Scene& scene) {
  std::vector<Aabb> mesh_bounds(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (uint32_t i : scene.meshes[m].indices) mesh_bounds[m].extend({scene.meshes[m].positions[i], scene.meshes[m].positions[i]});
  std::vector<Aabb> boxes;
  boxes.reserve(scene.instances.size());
  for (const Instance& inst : scene.instances) {
    const Aabb& b = mesh_bounds[inst.mesh];
    Aabb world;
    if (!b.empty())
      for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p(corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z);
        const glm::vec3 w(glm::dmat4(inst.transform) * glm::dvec4(p, 1.0));
        world.extend({w, w});
      }
    else
      world = {glm::vec3(inst.transform[3]), glm::vec3(inst.transform[3])};  // nothing to hit: a point
    boxes.push_back(world);
  }
  return boxes;
}

std::vector<gpu::GpuInstance> gpu_instances(const Scene& scene) {
  std::vector<gpu::GpuInstance> out;
  uint64_t next_id = scene.spheres.size() + scene.instances.size();
  // The boxes the top level places the instances by (primitive_boxes).
  const std::vector<Aabb> boxes = instance_boxes(scene);
  for (const Instance& inst : scene.instances) {
    const glm::dmat4 to_object = glm::inverse(glm::dmat4(inst.transform));
    gpu::GpuInstance g{};
    // glm is column-major: row r is (m[0][r], m[1][r], m[2][r], m[3][r]).
    glm::vec4* rows[3] = {&g.to_object0, &g.to_object1, &g.to_object2};
    for (int r = 0; r < 3; ++r) *rows[r] = glm::vec4(to_object[0][r], to_object[1][r], to_object[2][r], to_object[3][r]);
    g.lo = boxes[out.size()].lo;
    g.hi = boxes[out.size()].hi;
    g.mesh = inst.mesh;
    g.first_id = uint32_t(next_id);
    next_id += scene.meshes[inst.mesh].triangle_count();
    out.push_back(g);
  }
  if (next_id >= (uint64_t(1) << 32))
    throw InputError(std::to_string(next_id) + " primitives (spheres, instances and instanced triangles): "
                     "more than 2^32 ids");
  return out;
}

bool occludes(const Material& m) {
  switch (m.type) {
    case MaterialType::Lambertian:
    case MaterialType::Metal:
    case MaterialType::Emissive: return true;
    case MaterialType::Dielectric: return false;
    case MaterialType::Pbr:
      return !(m.transmission > 0.0f) && !m.transmission_texture && m.alpha_mode == AlphaMode::Opaque;
  }
  return false;
}

std::vector<uint8_t> sphere_occluders(const Scene& scene) {
  std::vector<uint8_t> out(scene.spheres.size());
  // A ray that starts inside an occluder could hit what it hides: a sphere
  // that reaches the lens (with a margin of a thousandth of the distance)
  // occludes nothing.
  const glm::dvec3 eye(scene.camera.lookfrom);
  const double lens = 0.5 * double(scene.camera.aperture);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const double d = glm::length(glm::dvec3(s.center) - eye);
    out[i] = occludes(scene.materials[s.material]) && d > (double(s.radius) + lens) * 1.001 + 1e-6;
  }
  return out;
}

ClipFn sphere_surface_clip(std::span<const Sphere> spheres, std::span<const Aabb> boxes) {
  return [spheres, boxes](uint32_t prim, const Aabb& cell, Aabb& part) {
    const Aabb& b = boxes[prim];
    const Aabb within{glm::max(cell.lo, b.lo), glm::min(cell.hi, b.hi)};
    if (prim >= spheres.size()) {
      part = within;
      return true;
    }
    if (!(within.lo.x <= within.hi.x && within.lo.y <= within.hi.y && within.lo.z <= within.hi.z)) return false;
    return clip_sphere_surface(spheres[prim].center, spheres[prim].radius, within, part);
  };
}

std::vector<Aabb> primitive_boxes(const Scene& scene, HiddenParts hidden, HiddenPartsStats* stats) {
  std::vector<Aabb> boxes;
  if (hidden == HiddenParts::Cull) {
    std::vector<Ball> balls(scene.spheres.size());
    for (size_t i = 0; i < balls.size(); ++i) balls[i] = {scene.spheres[i].center, scene.spheres[i].radius};
    boxes = visible_sphere_boxes(balls, sphere_occluders(scene), stats);
  } else {
    boxes = sphere_boxes(scene.spheres);
    if (stats) *stats = {};
  }
  const std::vector<Aabb> inst = instance_boxes(scene);
  boxes.insert(boxes.end(), inst.begin(), inst.end());
  return boxes;
}

static void upload_scene_of(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel,
                            const OctreeParams& params, uint64_t reserved_bytes, Precision precision) {
  auto start = Clock::now();
  SphereArrays sphere_data = sphere_arrays(scene);
  std::vector<gpu::GpuSphere>& spheres = sphere_data.spheres;
  std::vector<uint32_t>& sphere_materials = sphere_data.materials;
  // The materials as the render's precision reads them only (the other
  // form is hashed below, not stored).
  const bool half = precision != Precision::FP32;
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuMaterialHalf> materials_half;
  const size_t texture_count = scene.textures.size();
  check_fits(ctx.limits.maxStorageBufferRange, texel_count(scene) * sizeof(uint32_t),
             "the texels of " + std::to_string(texture_count) + (texture_count == 1 ? " texture" : " textures"));
  const GpuTextures textures = gpu_textures(scene);
  // The uv transforms of every material's texture slots, only where a texture can be sampled.
  std::vector<gpu::GpuUvTransform> uv_transforms;
  if (!textures.table.empty()) {
    uv_transforms.reserve(scene.materials.size() * gpu::TEXTURE_SLOTS);
    for (const Material& m : scene.materials)
      for (const glm::mat3x2& t :
           {m.base_color_uv, m.metallic_roughness_uv, m.emission_uv, m.normal_uv, m.transmission_uv})
        uv_transforms.push_back({t[0], t[1], t[2]});
    static_assert(gpu::TEXTURE_SLOTS == 5, "one uv transform per slot, in TEXTURE_SLOT_* order");
  }
  // What transmission reads besides the material, only where some material transmits.
  std::vector<gpu::GpuTransmission> transmission;
  if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.type == MaterialType::Pbr && m.transmission > 0.0f;
      })) {
    check_fits(ctx.limits.maxStorageBufferRange, scene.materials.size() * sizeof(gpu::GpuTransmission),
               "the transmission parameters of " + std::to_string(scene.materials.size()) + " materials");
    transmission.reserve(scene.materials.size());
    for (const Material& m : scene.materials)
      transmission.push_back({absorption_coefficient(m), m.transmission_texture.value_or(gpu::NO_TEXTURE)});
  }
  gpu::SceneParams& p = g.values;
  p = {};
  const Sky& sky = scene.sky;
  p.sky_type = uint32_t(sky.type);
  p.sky_a = sky.type == SkyType::Uniform ? sky.radiance : sky.down;
  p.sky_b = sky.up;
  // The envmap: strength, rotation in turns, and its tables (scene/envmap.h).
  EnvmapTables envmap_tables;
  if (sky.type == SkyType::Envmap) {
    p.sky_a = glm::vec3(sky.strength);
    p.sky_b = glm::vec3(sky.rotate / 360.0f, 0.0f, 0.0f);
    p.envmap_width = sky.image.width;
    p.envmap_height = sky.image.height;
    const std::string size = std::to_string(sky.image.width) + "x" + std::to_string(sky.image.height);
    check_fits(ctx.limits.maxStorageBufferRange, sky.image.rgb.size() * sizeof(float), sky.file + ": the environment map's " + size + " texels");
    check_fits(ctx.limits.maxStorageBufferRange, uint64_t(sky.image.height) * (sky.image.width + 1) * sizeof(float),
               sky.file + ": the sampling table of the " + size + " environment map");
    envmap_tables = build_envmap_tables(sky.image);
  }
  const std::vector<float>& envmap_texels = sky.image.rgb;
  p.sphere_count = uint32_t(scene.spheres.size());

  std::vector<gpu::GpuTriangle> triangles = object_triangles(scene);
  std::vector<gpu::GpuTriangleNormals> normals;
  bool any_normals = false;
  for (const Mesh& mesh : scene.meshes) any_normals |= !mesh.normals.empty();
  if (any_normals) normals = object_triangle_normals(scene);
  // Uvs only where a material can sample a texture with them.
  std::vector<gpu::GpuTriangleUvs> uvs;
  bool any_uvs = false;
  for (const Mesh& mesh : scene.meshes) any_uvs |= !mesh.uvs.empty();
  if (any_uvs && !textures.table.empty()) uvs = object_triangle_uvs(scene);
  const std::vector<gpu::GpuInstance> instances = gpu_instances(scene);
  const std::vector<gpu::GpuMesh> meshes = gpu_meshes(scene);
  p.triangle_count = uint32_t(triangles.size());
  p.vertex_normals = any_normals ? 1u : 0u;
  p.instance_count = uint32_t(instances.size());
  p.triangle_uvs = uvs.empty() ? 0u : 1u;
  LightList lights = build_light_list(scene);
  check_fits(ctx.limits.maxStorageBufferRange, lights.lights.size() * sizeof(gpu::GpuLight), std::to_string(lights.lights.size()) + " lights");
  check_fits(ctx.limits.maxStorageBufferRange, lights.sphere_lights.size() * 4, "the light indices of " + std::to_string(scene.spheres.size()) + " spheres");
  check_fits(ctx.limits.maxStorageBufferRange, lights.triangle_lights.size() * 4, "the light indices of the emissive triangles");
  p.light_count = uint32_t(lights.lights.size());

  Hash64 hash;
  // Scenes without lights keep the hash they had before lights existed (checkpoints).
  if (!lights.lights.empty()) hash.add_vector(lights.lights);
  // Scenes without textures keep the hash they had before transforms existed (checkpoints).
  if (!uv_transforms.empty()) hash.add_vector(uv_transforms);
  // Nor do scenes without an envmap (its tables follow from its texels).
  if (!envmap_texels.empty()) hash.add_vector(envmap_texels);
  // Nor scenes without transmission.
  if (!transmission.empty()) hash.add_vector(transmission);
  g.content_hash = hash.add(&p, sizeof p)
                      .add_vector(triangles)
                      .add_vector(normals)
                      .add_vector(uvs)
                      .add_vector(instances)
                      .add_vector(meshes)
                      .add_vector(textures.table)
                      .add_vector(textures.texels)
                      .add_vector(spheres)
                      .add_vector(sphere_materials)
                      .value();
  make_materials(scene, half, hash, materials, materials_half);
  g.content_hash = hash.value();
  const double pack_ms = ms_since(start);
  std::optional<SceneOctree> tree;
  if (accel != Accel::Brute) tree = build_scene_octree(ctx, scene, accel, params);
  start = Clock::now();

  // The big arrays, each in one storage buffer, or the whole scene split
  // into parts when one of them does not fit (scene_buffers.glsl).
  const uint64_t node_bytes = tree ? tree->octree.nodes.size() * sizeof(gpu::GpuOctreeNode) : 0;
  const uint64_t ref_bytes = tree ? tree->octree.refs.size() * sizeof(uint32_t) : 0;
  const struct {
    uint64_t bytes, elements;
    uint32_t size_log2;
    std::string what;
  } arrays[] = {
      {spheres.size() * sizeof(gpu::GpuSphere), spheres.size(), size_log2<gpu::GpuSphere>(),
       std::to_string(spheres.size()) + " spheres"},
      {sphere_materials.size() * sizeof(uint32_t), sphere_materials.size(), size_log2<uint32_t>(),
       "the material indices of " + std::to_string(spheres.size()) + " spheres"},
      {materials.size() * sizeof(gpu::GpuMaterial), materials.size(), size_log2<gpu::GpuMaterial>(),
       std::to_string(scene.materials.size()) + " materials"},
      {materials_half.size() * sizeof(gpu::GpuMaterialHalf), materials_half.size(), size_log2<gpu::GpuMaterialHalf>(),
       std::to_string(scene.materials.size()) + " materials (fp16)"},
      {triangles.size() * sizeof(gpu::GpuTriangle), triangles.size(), size_log2<gpu::GpuTriangle>(),
       std::to_string(triangles.size()) + " triangles"},
      {normals.size() * sizeof(gpu::GpuTriangleNormals), normals.size(), size_log2<gpu::GpuTriangleNormals>(),
       "the vertex normals of " + std::to_string(triangles.size()) + " triangles"},
      {uvs.size() * sizeof(gpu::GpuTriangleUvs), uvs.size(), size_log2<gpu::GpuTriangleUvs>(),
       "the texture coordinates of " + std::to_string(triangles.size()) + " triangles"},
      {node_bytes, node_bytes / sizeof(gpu::GpuOctreeNode), size_log2<gpu::GpuOctreeNode>(), octree_what(scene, "nodes")},
      {ref_bytes, ref_bytes / sizeof(uint32_t), size_log2<uint32_t>(), octree_what(scene, "references")},
  };
  const uint64_t limit = max_buffer_bytes(ctx);
  bool split = false;
  for (const auto& a : arrays) split |= a.bytes > limit;
  g.part_log2 = 0;
  g.part_addresses.clear();
  g.parts.clear();
  if (split && !ctx.buffer_device_address)
    for (const auto& a : arrays) check_fits(limit, a.bytes, a.what, " (and it lacks bufferDeviceAddress to split it)");
  if (split) {
    g.part_log2 = uint32_t(std::bit_width(limit)) - 1;
    // A part holds at least one of the largest elements (GpuMaterial, 2^7).
    if (g.part_log2 < size_log2<gpu::GpuMaterial>())
      throw SceneSizeError("the device allows " + std::to_string(limit) + " bytes per buffer, too few to split a scene");
    g.part_addresses.assign(gpu::SPLIT_ARRAYS * gpu::MAX_PARTS, glm::uvec2(0));
    for (const auto& a : arrays) check_part_count(g.part_log2, a.elements, a.size_log2, a.bytes, a.what, limit);
  }
  // Everything on the device against its memory (device_memory), before
  // asking the driver for any of it.
  uint64_t total = reserved_bytes + sizeof p + instances.size() * sizeof(gpu::GpuInstance) +
                   meshes.size() * sizeof(gpu::GpuMesh) + textures.table.size() * sizeof(gpu::GpuTexture) + textures.texels.size() * sizeof(uint32_t) +
                   uv_transforms.size() * sizeof(gpu::GpuUvTransform) + g.part_addresses.size() * sizeof(glm::uvec2) +
                   transmission.size() * sizeof(gpu::GpuTransmission) +
                   (envmap_texels.size() + envmap_tables.marginal.size() + envmap_tables.conditional.size()) *
                       sizeof(float) +
                   lights.lights.size() * sizeof(gpu::GpuLight) + lights.sphere_lights.size() * sizeof(uint32_t) +
                   lights.triangle_lights.size() * sizeof(uint32_t);
  for (const auto& a : arrays) total += a.bytes;
  const DeviceMemory memory = device_memory(ctx);
  if (total > memory.bytes) {
    std::string what = std::to_string(spheres.size()) + " spheres";
    if (!triangles.empty()) what += " and " + std::to_string(triangles.size()) + " triangles";
    throw SceneSizeError(what + (tree ? " with their octree" : "") + " need " + byte_string(total) +
                         " of device memory, the device has " + byte_string(memory.bytes) + " (" + memory.source +
                         ")");
  }

  // The hash above has the spheres in the scene's order; the device may hold them in the tree's.
  if (tree) {
    const std::vector<uint32_t> order = device_sphere_order(g, ctx, scene, accel, params, tree->octree);
    put_spheres_in_order(order, sphere_data, lights);
    tree->octree.stats.bvh_sphere_order = !order.empty();
  }
  create_buffer(g.params, ctx, sizeof p, false, "scene parameters");
  upload_array(g, ctx, gpu::SPLIT_TRIANGLES, g.triangles, std::move(triangles), "triangle buffer");
  upload_array(g, ctx, gpu::SPLIT_TRIANGLE_NORMALS, g.triangle_normals, std::move(normals), "triangle normal buffer");
  create_buffer(g.instances, ctx, instances.size() * sizeof(gpu::GpuInstance), false, "instance buffer");
  create_buffer(g.meshes, ctx, meshes.size() * sizeof(gpu::GpuMesh), false, "mesh buffer");
  upload_buffer(ctx, g.instances, instances.data(), instances.size() * sizeof(gpu::GpuInstance));
  upload_buffer(ctx, g.meshes, meshes.data(), meshes.size() * sizeof(gpu::GpuMesh));
  upload_array(g, ctx, gpu::SPLIT_SPHERES, g.spheres, std::move(spheres), "sphere buffer");
  upload_array(g, ctx, gpu::SPLIT_SPHERE_MATERIALS, g.sphere_materials, std::move(sphere_materials),
               "sphere material buffer");
  upload_array(g, ctx, gpu::SPLIT_MATERIALS, g.materials, std::move(materials), "material buffer");
  upload_array(g, ctx, gpu::SPLIT_MATERIALS_HALF, g.materials_half, std::move(materials_half), "material buffer");
  g.has_materials = !half;
  g.has_materials_half = half;
  create_buffer(g.textures, ctx, textures.table.size() * sizeof(gpu::GpuTexture), false, "texture table");
  create_buffer(g.texels, ctx, textures.texels.size() * sizeof(uint32_t), false, "texel buffer");
  upload_array(g, ctx, gpu::SPLIT_TRIANGLE_UVS, g.triangle_uvs, std::move(uvs), "triangle uv buffer");
  upload_buffer(ctx, g.textures, textures.table.data(), textures.table.size() * sizeof(gpu::GpuTexture));
  upload_buffer(ctx, g.texels, textures.texels.data(), textures.texels.size() * sizeof(uint32_t));
  create_buffer(g.texture_transforms, ctx, uv_transforms.size() * sizeof(gpu::GpuUvTransform), false,
                "texture transform buffer");
  upload_buffer(ctx, g.texture_transforms, uv_transforms.data(), uv_transforms.size() * sizeof(gpu::GpuUvTransform));
  create_buffer(g.transmission, ctx, transmission.size() * sizeof(gpu::GpuTransmission), false, "transmission buffer");
  upload_buffer(ctx, g.transmission, transmission.data(), transmission.size() * sizeof(gpu::GpuTransmission));
  create_buffer(g.envmap_texels, ctx, envmap_texels.size() * sizeof(float), false, "envmap texel buffer");
  create_buffer(g.envmap_marginal, ctx, envmap_tables.marginal.size() * sizeof(float), false, "envmap table");
  create_buffer(g.envmap_conditional, ctx, envmap_tables.conditional.size() * sizeof(float), false, "envmap table");
  upload_buffer(ctx, g.envmap_texels, envmap_texels.data(), envmap_texels.size() * sizeof(float));
  upload_buffer(ctx, g.envmap_marginal, envmap_tables.marginal.data(), envmap_tables.marginal.size() * sizeof(float));
  upload_buffer(ctx, g.envmap_conditional, envmap_tables.conditional.data(),
                envmap_tables.conditional.size() * sizeof(float));
  create_buffer(g.lights, ctx, lights.lights.size() * sizeof(gpu::GpuLight), false, "light buffer");
  create_buffer(g.sphere_lights, ctx, lights.sphere_lights.size() * 4, false, "sphere light buffer");
  upload_buffer(ctx, g.lights, lights.lights.data(), lights.lights.size() * sizeof(gpu::GpuLight));
  upload_buffer(ctx, g.sphere_lights, lights.sphere_lights.data(), lights.sphere_lights.size() * 4);
  create_buffer(g.triangle_lights, ctx, lights.triangle_lights.size() * 4, false, "triangle light buffer");
  upload_buffer(ctx, g.triangle_lights, lights.triangle_lights.data(), lights.triangle_lights.size() * 4);
  create_buffer(g.nodes, ctx, 0, false, "octree node buffer");
  create_buffer(g.refs, ctx, 0, false, "octree reference buffer");
  upload_buffer(ctx, g.params, &p, sizeof p);
  upload_part_table(g, ctx);
  g.upload_ms = pack_ms + ms_since(start);
  if (tree) upload_scene_octree(g, ctx, std::move(*tree), accel);
}

bool bakes_every_instance(const Scene& scene, Instancing instancing) {
  return bakes_every_instance(instancing, unique_triangle_count(scene), instanced_triangle_count(scene));
}

Scene device_meshes(const Scene& scene, Instancing instancing) {
  return bake_single_use_meshes(scene, bakes_every_instance(scene, instancing));
}

Scene bake_single_use_meshes(const Scene& scene, bool every_instance) {
  std::vector<uint32_t> uses(scene.meshes.size(), 0);
  for (const Instance& inst : scene.instances) ++uses[inst.mesh];
  // Baking every instance: each counts as the one use of its own copy.
  if (every_instance) std::fill(uses.begin(), uses.end(), 1u);
  Scene out;
  out.camera = scene.camera;
  out.sky = scene.sky;
  out.materials = scene.materials;
  out.textures = scene.textures;
  out.spheres = scene.spheres;
  out.lights = scene.lights;
  // Meshes placed more than once stay instanced, in their order.
  std::vector<uint32_t> remap(scene.meshes.size(), UINT32_MAX);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (uses[m] > 1) {
      remap[m] = uint32_t(out.meshes.size());
      out.meshes.push_back(scene.meshes[m]);
    }
  // The baked mesh has vertex normals (uvs) if any mesh baked into it has them.
  bool single_smooth = false, single_uvs = false, single_tangents = false;
  for (const Instance& inst : scene.instances) {
    single_smooth |= uses[inst.mesh] == 1 && !scene.meshes[inst.mesh].normals.empty();
    single_uvs |= uses[inst.mesh] == 1 && !scene.meshes[inst.mesh].uvs.empty();
    single_tangents |= uses[inst.mesh] == 1 && !scene.meshes[inst.mesh].tangents.empty();
  }
  Mesh baked;
  baked.name = "baked";
  for (const Instance& inst : scene.instances) {
    if (uses[inst.mesh] != 1) {
      out.instances.push_back({remap[inst.mesh], inst.transform});
      continue;
    }
    // Into world space: positions by the placement, normals by its inverse
    // transpose, and a mirror's winding flipped so that counter-clockwise is
    // still the front.
    const Mesh& mesh = scene.meshes[inst.mesh];
    const glm::dmat4 m(inst.transform);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(m)));
    const bool flip = glm::determinant(glm::dmat3(m)) < 0.0;
    const auto world = [&](glm::vec3 p) { return glm::vec3(m * glm::dvec4(glm::dvec3(p), 1.0)); };
    const auto world_normal = [&](glm::vec3 n) { return glm::vec3(glm::normalize(normal_matrix * glm::dvec3(n))); };
    // A tangent is a direction (the placement's 3x3, not its inverse
    // transpose); a mirror turns cross(normal, tangent) around, so w flips
    // to keep the bitangent where the placement puts it.
    const auto world_tangent = [&](glm::vec4 t) {
      if (t.w == 0.0f) return t;
      const glm::dvec3 d = glm::dmat3(m) * glm::dvec3(t);
      const double l = glm::length(d);
      return l > 0.0 ? glm::vec4(glm::vec3(d / l), flip ? -t.w : t.w) : glm::vec4(0.0f);
    };
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
      uint32_t idx[3] = {mesh.indices[3 * k], mesh.indices[3 * k + (flip ? 2 : 1)], mesh.indices[3 * k + (flip ? 1 : 2)]};
      const uint32_t base = uint32_t(baked.positions.size());
      glm::vec3 p[3];
      for (int v = 0; v < 3; ++v) p[v] = world(mesh.positions[idx[v]]);
      baked.positions.insert(baked.positions.end(), {p[0], p[1], p[2]});
      if (single_smooth) {
        if (mesh.normals.empty()) {
          // Beside smooth meshes a flat one keeps its face normal at each vertex.
          const glm::vec3 n = face_normal(p[0], p[1], p[2]);
          baked.normals.insert(baked.normals.end(), {n, n, n});
        } else {
          for (int v = 0; v < 3; ++v) baked.normals.push_back(world_normal(mesh.normals[idx[v]]));
        }
      }
      if (single_uvs)
        for (int v = 0; v < 3; ++v) baked.uvs.push_back(mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[idx[v]]);
      if (single_tangents)
        for (int v = 0; v < 3; ++v)
          baked.tangents.push_back(mesh.tangents.empty() ? glm::vec4(0.0f) : world_tangent(mesh.tangents[idx[v]]));
      baked.indices.insert(baked.indices.end(), {base, base + 1, base + 2});
      baked.materials.push_back(mesh.materials[k]);
    }
  }
  if (!baked.indices.empty()) {
    out.meshes.push_back(std::move(baked));
    out.instances.push_back({uint32_t(out.meshes.size() - 1), glm::mat4(1.0f)});
  }
  return out;
}

void upload_octree(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel,
                   const OctreeParams& params) {
  if (scene.meshes.empty()) upload_octree_of(g, ctx, scene, accel, params);
  else upload_octree_of(g, ctx, device_meshes(scene, params.instancing), accel, params);
}

void upload_scene(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Accel accel, const OctreeParams& params,
                  uint64_t reserved_bytes, Precision precision) {
  if (scene.meshes.empty()) upload_scene_of(g, ctx, scene, accel, params, reserved_bytes, precision);
  else upload_scene_of(g, ctx, device_meshes(scene, params.instancing), accel, params, reserved_bytes, precision);
}

void upload_materials(GpuScene& g, const VulkanContext& ctx, const Scene& scene, Precision precision) {
  const bool half = precision != Precision::FP32;
  if (half ? g.has_materials_half : g.has_materials) return;
  const auto start = Clock::now();
  const size_t n = scene.materials.size();
  const uint64_t bytes = n * (half ? sizeof(gpu::GpuMaterialHalf) : sizeof(gpu::GpuMaterial));
  const std::string what = std::to_string(n) + (half ? " materials (fp16)" : " materials");
  const uint64_t limit = max_buffer_bytes(ctx);
  if (g.part_log2 == 0)
    check_fits(limit, bytes, what, std::string(" (render in ") + precision_name(precision) +
                                       " from the start to split the scene)");
  else
    check_part_count(g.part_log2, n, half ? size_log2<gpu::GpuMaterialHalf>() : size_log2<gpu::GpuMaterial>(), bytes,
                     what, limit);
  if (half) {
    upload_array(g, ctx, gpu::SPLIT_MATERIALS_HALF, g.materials_half, gpu_materials_half(scene), "material buffer");
    g.has_materials_half = true;
  } else {
    upload_array(g, ctx, gpu::SPLIT_MATERIALS, g.materials, gpu_materials(scene), "material buffer");
    g.has_materials = true;
  }
  if (g.part_log2 != 0) upload_part_table(g, ctx);
  g.upload_ms += ms_since(start);
}

void check_precision(const Scene& scene, Precision precision) {
  if (precision == Precision::FP32) return;
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const glm::vec3 color = m.type == MaterialType::Emissive ? m.radiance : m.albedo;
    for (const auto& [c, name] : {std::pair{color, "radiance"}, std::pair{m.emission, "emission"}})
      if (std::max({c.r, c.g, c.b}) > kHalfMax)
        throw SettingError("precision", std::string(" ") + precision_name(precision) + ": materials[" +
                                            std::to_string(i) + "]: " + name + " above 65504 does not fit half");
  }
  if (scene.sky.type == SkyType::Envmap) {
    const std::vector<float>& rgb = scene.sky.image.rgb;
    const float brightest = rgb.empty() ? 0.0f : *std::max_element(rgb.begin(), rgb.end());
    if (double(brightest) * scene.sky.strength > kHalfMax)
      throw SettingError("precision", std::string(" ") + precision_name(precision) + ": sky: " + scene.sky.file +
                                          ": strength x brightest texel = " +
                                          float_string(float(double(brightest) * scene.sky.strength)) +
                                          " is above 65504 and does not fit half (use --precision fp32)");
  }
}

}  // namespace octrace
