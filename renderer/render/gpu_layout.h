// The C++ view of shaders/shared/shared.h, checked against std430: sizes and
// offsets of every field of every shared struct, and the enums of the scene
// tied to the constants the shaders switch on. The layout-probe test
// (tests/render/layout_test.cpp) checks that the GLSL compiler agrees.
#pragma once

#include <cstddef>

#include "scene/scene.h"
#include "shared/shared.h"

namespace octrace::gpu {

static_assert(sizeof(GpuSphere) == 16);
static_assert(offsetof(GpuSphere, radius) == 12);

static_assert(sizeof(GpuTriangle) == 48);
static_assert(offsetof(GpuTriangle, material) == 12);
static_assert(offsetof(GpuTriangle, v1) == 16);
static_assert(offsetof(GpuTriangle, pad0) == 28);
static_assert(offsetof(GpuTriangle, v2) == 32);
static_assert(offsetof(GpuTriangle, pad1) == 44);

static_assert(sizeof(GpuTriangleNormals) == 48);
static_assert(offsetof(GpuTriangleNormals, n1) == 16);
static_assert(offsetof(GpuTriangleNormals, n2) == 32);
static_assert(offsetof(GpuTriangleNormals, tangent2) == 44);

static_assert(sizeof(GpuTriangleUvs) == 24);
static_assert(offsetof(GpuTriangleUvs, uv1) == 8);
static_assert(offsetof(GpuTriangleUvs, uv2) == 16);

static_assert(sizeof(GpuTransmission) == 16);
static_assert(offsetof(GpuTransmission, transmission_texture) == 12);

static_assert(sizeof(GpuUvTransform) == 24);
static_assert(offsetof(GpuUvTransform, y_axis) == 8);
static_assert(offsetof(GpuUvTransform, offset) == 16);

static_assert(sizeof(GpuMaterial) == 80);
static_assert(ALPHA_OPAQUE == uint32_t(AlphaMode::Opaque) && ALPHA_MASK == uint32_t(AlphaMode::Mask) &&
              ALPHA_BLEND == uint32_t(AlphaMode::Blend));
static_assert(offsetof(GpuMaterial, type) == 12);
static_assert(offsetof(GpuMaterial, fuzz) == 16);
static_assert(offsetof(GpuMaterial, ior) == 20);
static_assert(offsetof(GpuMaterial, base_color_texture) == 24);
static_assert(offsetof(GpuMaterial, emission_texture) == 28);
static_assert(offsetof(GpuMaterial, emission) == 32);
static_assert(offsetof(GpuMaterial, metallic_roughness_texture) == 44);
static_assert(offsetof(GpuMaterial, metallic) == 48);
static_assert(offsetof(GpuMaterial, roughness) == 52);
static_assert(offsetof(GpuMaterial, normal_texture) == 56);
static_assert(offsetof(GpuMaterial, normal_scale) == 60);
static_assert(offsetof(GpuMaterial, alpha_mode) == 64);
static_assert(offsetof(GpuMaterial, alpha_cutoff) == 68);
static_assert(offsetof(GpuMaterial, alpha) == 72);
static_assert(offsetof(GpuMaterial, double_sided) == 76);

static_assert(sizeof(GpuMaterialHalf) == 64);
static_assert(offsetof(GpuMaterialHalf, params) == 8);
static_assert(offsetof(GpuMaterialHalf, emission) == 16);
static_assert(offsetof(GpuMaterialHalf, base_color_texture) == 24);
static_assert(offsetof(GpuMaterialHalf, emission_texture) == 28);
static_assert(offsetof(GpuMaterialHalf, metallic_roughness_texture) == 32);
static_assert(offsetof(GpuMaterialHalf, normal_texture) == 36);
static_assert(offsetof(GpuMaterialHalf, normal_scale) == 40);
static_assert(offsetof(GpuMaterialHalf, pad2) == 44);
static_assert(offsetof(GpuMaterialHalf, alpha_mode) == 48);
static_assert(offsetof(GpuMaterialHalf, alpha_cutoff) == 52);
static_assert(offsetof(GpuMaterialHalf, alpha) == 56);
static_assert(offsetof(GpuMaterialHalf, double_sided) == 60);

static_assert(sizeof(GpuTexture) == 16);
static_assert(offsetof(GpuTexture, width) == 4);
static_assert(offsetof(GpuTexture, height) == 8);
static_assert(offsetof(GpuTexture, wrap) == 12);

static_assert(sizeof(RenderStats) == 88);
static_assert(offsetof(RenderStats, walk) == 16 && sizeof(RenderStats::walk) == 8 * WALK_COUNTERS);
static_assert(offsetof(RenderStats, cut_paths) == 4);
static_assert(offsetof(RenderStats, loop_bound) == 8);
static_assert(offsetof(RenderStats, pad2) == 12);

static_assert(sizeof(GpuOctreeNode) == 32);
static_assert(offsetof(GpuOctreeNode, first) == 12);
static_assert(offsetof(GpuOctreeNode, hi) == 16);
static_assert(offsetof(GpuOctreeNode, count_or_mask) == 28);

static_assert(sizeof(SceneParams) == 64);
static_assert(offsetof(SceneParams, sky_type) == 12);
static_assert(offsetof(SceneParams, sky_b) == 16);
static_assert(offsetof(SceneParams, sphere_count) == 28);
static_assert(offsetof(SceneParams, big_count) == 32);
static_assert(offsetof(SceneParams, triangle_count) == 36);
static_assert(offsetof(SceneParams, vertex_normals) == 40);
static_assert(offsetof(SceneParams, instance_count) == 44);
static_assert(offsetof(SceneParams, triangle_uvs) == 48);
static_assert(offsetof(SceneParams, light_count) == 52);
static_assert(offsetof(SceneParams, envmap_width) == 56);
static_assert(offsetof(SceneParams, envmap_height) == 60);

static_assert(sizeof(GpuLight) == 80);
static_assert(offsetof(GpuLight, type) == 12);
static_assert(offsetof(GpuLight, direction) == 16);
static_assert(offsetof(GpuLight, radius) == 28);
static_assert(offsetof(GpuLight, intensity) == 32);
static_assert(offsetof(GpuLight, sphere) == 44);
static_assert(offsetof(GpuLight, cos_inner) == 48);
static_assert(offsetof(GpuLight, cos_outer) == 52);
static_assert(offsetof(GpuLight, pmf) == 56);
static_assert(offsetof(GpuLight, alias_q) == 60);
static_assert(offsetof(GpuLight, alias) == 64);
static_assert(offsetof(GpuLight, instance) == 68);
static_assert(offsetof(GpuLight, triangle) == 72);
static_assert(offsetof(GpuLight, pad0) == 76);
static_assert(uint32_t(LightType::Point) + 1 == LIGHT_POINT && uint32_t(LightType::Spot) + 1 == LIGHT_SPOT &&
              uint32_t(LightType::Directional) + 1 == LIGHT_DIRECTIONAL);
static_assert(sizeof(GpuInstance) == 80);
static_assert(offsetof(GpuInstance, to_object1) == 16);
static_assert(offsetof(GpuInstance, to_object2) == 32);
static_assert(offsetof(GpuInstance, lo) == 48);
static_assert(offsetof(GpuInstance, mesh) == 60);
static_assert(offsetof(GpuInstance, hi) == 64);
static_assert(offsetof(GpuInstance, first_id) == 76);

static_assert(sizeof(GpuMesh) == 32);
static_assert(offsetof(GpuMesh, first_ref) == 4);
static_assert(offsetof(GpuMesh, big_count) == 8);
static_assert(offsetof(GpuMesh, first_triangle) == 12);
static_assert(offsetof(GpuMesh, triangle_count) == 16);
static_assert(offsetof(GpuMesh, pad2) == 28);

static_assert(sizeof(PassParams) == 128);
static_assert(offsetof(PassParams, lens_radius) == 12);
static_assert(offsetof(PassParams, lens_u) == 16);
static_assert(offsetof(PassParams, width) == 28);
static_assert(offsetof(PassParams, lens_v) == 32);
static_assert(offsetof(PassParams, height) == 44);
static_assert(offsetof(PassParams, pixel00) == 48);
static_assert(offsetof(PassParams, bounce_limit) == 60);
static_assert(offsetof(PassParams, pixel_du) == 64);
static_assert(offsetof(PassParams, sample_seed) == 76);
static_assert(offsetof(PassParams, pixel_dv) == 80);
static_assert(offsetof(PassParams, sample_index) == 92);
static_assert(offsetof(PassParams, rr_depth) == 96);
static_assert(offsetof(PassParams, sample_count) == 100);
static_assert(offsetof(PassParams, sample_lanes) == 104);
static_assert(offsetof(PassParams, tail_depth) == 108);
static_assert(offsetof(PassParams, tail_capacity) == 112);
static_assert(offsetof(PassParams, tail_level) == 116);
static_assert(offsetof(PassParams, tail_end) == 120);
static_assert(offsetof(PassParams, tail_fill) == 124);

static_assert(sizeof(GpuTailPath) == 96);
static_assert(offsetof(GpuTailPath, pixel) == 12);
static_assert(offsetof(GpuTailPath, sample_offset) == 28);
static_assert(offsetof(GpuTailPath, bounce_flags) == 44);
static_assert(offsetof(GpuTailPath, segments) == 60);
static_assert(offsetof(GpuTailPath, from_prim) == 76);
static_assert(offsetof(GpuTailPath, prev_pdf) == 92);
static_assert(sizeof(TailControl) == 32);
static_assert(offsetof(TailControl, subgroup_groups_x) == 16);
// Vulkan guarantees at least 128 bytes of push constants on every device.
static_assert(sizeof(PassParams) <= 128);

static_assert(sizeof(ResolveParams) == 16);
static_assert(offsetof(ResolveParams, height) == 4);

// The scene's enums are the shaders' constants.
static_assert(uint32_t(MaterialType::Lambertian) == MAT_LAMBERTIAN);
static_assert(uint32_t(MaterialType::Metal) == MAT_METAL);
static_assert(uint32_t(MaterialType::Dielectric) == MAT_DIELECTRIC);
static_assert(uint32_t(MaterialType::Emissive) == MAT_EMISSIVE);
static_assert(uint32_t(MaterialType::Pbr) == MAT_PBR);
static_assert(uint32_t(SkyType::Gradient) == SKY_GRADIENT);
static_assert(uint32_t(SkyType::Uniform) == SKY_UNIFORM);
static_assert(uint32_t(SkyType::None) == SKY_NONE);
static_assert(uint32_t(SkyType::Envmap) == SKY_ENVMAP);
static_assert(uint32_t(Wrap::Repeat) == WRAP_REPEAT);
static_assert(uint32_t(Wrap::ClampToEdge) == WRAP_CLAMP_TO_EDGE);
static_assert(uint32_t(Wrap::MirroredRepeat) == WRAP_MIRRORED_REPEAT);

}  // namespace octrace::gpu
