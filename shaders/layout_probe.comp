// Writes a distinct value into every field of every shared struct, as the
// GLSL compiler lays them out. The layout test reads the buffers back through
// the C++ structs: any disagreement in offsets shows as a wrong value.
// Compiled with OCTRACE_PRECISION=1 so that the half material exists too.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = 0) buffer B0 { SceneParams scene; };
layout(std430, binding = 1) buffer B1 { PassParams pass; };
layout(std430, binding = 2) buffer B2 { ResolveParams resolve; };
layout(std430, binding = 3) buffer B3 { GpuSphere spheres[2]; };
layout(std430, binding = 4) buffer B4 { GpuMaterial materials[2]; };
layout(std430, binding = 5) buffer B5 { GpuMaterialHalf materials_half[2]; };
layout(std430, binding = 6) buffer B6 { GpuOctreeNode nodes[2]; };
layout(std430, binding = 7) buffer B7 { RenderStats stats[2]; };
layout(std430, binding = 8) buffer B8 { GpuTriangle triangles[2]; };
layout(std430, binding = 9) buffer B9 { GpuTriangleNormals triangle_normals[2]; };
layout(std430, binding = 10) buffer B10 { GpuInstance instances[2]; };
layout(std430, binding = 11) buffer B11 { GpuMesh meshes[2]; };
layout(std430, binding = 12) buffer B12 { GpuTexture textures[2]; };
layout(std430, binding = 13) buffer B13 { GpuTriangleUvs triangle_uvs[2]; };
layout(std430, binding = 14) buffer B14 { GpuUvTransform uv_transforms[2]; };
layout(std430, binding = 15) buffer B15 { GpuLight lights[2]; };
layout(std430, binding = 16) buffer B16 { GpuTransmission transmissions[2]; };

void main() {
  scene.sky_a = vec3(1, 2, 3);
  scene.sky_type = 4;
  scene.sky_b = vec3(5, 6, 7);
  scene.sphere_count = 8;
  scene.big_count = 9;
  scene.triangle_count = 10;
  scene.vertex_normals = 11;
  scene.instance_count = 12;
  scene.triangle_uvs = 13;
  scene.light_count = 14;
  scene.envmap_width = 15;
  scene.envmap_height = 16;

  pass.cam_origin = vec3(1, 2, 3);
  pass.lens_radius = 4;
  pass.lens_u = vec3(5, 6, 7);
  pass.width = 8;
  pass.lens_v = vec3(9, 10, 11);
  pass.height = 12;
  pass.pixel00 = vec3(13, 14, 15);
  pass.bounce_limit = 16;
  pass.pixel_du = vec3(17, 18, 19);
  pass.sample_seed = 20;
  pass.pixel_dv = vec3(21, 22, 23);
  pass.sample_index = 24;
  pass.rr_depth = 25;
  pass.sample_count = 26;
  pass.sample_lanes = 27;
  pass.pad2 = 28;

  resolve.width = 1;
  resolve.height = 2;
  resolve.pad0 = 3;
  resolve.pad1 = 4;

  for (int i = 0; i < 2; ++i) {
    float o = 100.0 * float(i + 1);
    uint u = uint(o);
    spheres[i].center = vec3(o + 1, o + 2, o + 3);
    spheres[i].radius = o + 4;
    materials[i].color = vec3(o + 5, o + 6, o + 7);
    materials[i].type = u + 8;
    materials[i].fuzz = o + 9;
    materials[i].ior = o + 10;
    materials[i].base_color_texture = u + 11;
    materials[i].emission_texture = u + 12;
    materials[i].emission = vec3(o + 81, o + 82, o + 83);
    materials[i].metallic_roughness_texture = u + 84;
    materials[i].metallic = o + 101;
    materials[i].roughness = o + 102;
    materials[i].normal_texture = u + 103;
    materials[i].normal_scale = o + 104;
    materials[i].alpha_mode = u + 121;
    materials[i].alpha_cutoff = o + 122;
    materials[i].alpha = o + 123;
    materials[i].double_sided = u + 124;
    stats[i].nonfinite_samples = u + 13;
    stats[i].pad0 = u + 14;
    stats[i].pad1 = u + 15;
    stats[i].pad2 = u + 16;
    for (int k = 0; k < 12; ++k) stats[i].walk[k] = u + 300 + k;
    materials_half[i].color_type = f16vec4(o + 17, o + 18, o + 19, o + 20);
    materials_half[i].params = f16vec4(o + 21, o + 22, o + 23, o + 24);
    materials_half[i].emission = f16vec4(o + 85, o + 86, o + 87, o + 88);
    materials_half[i].base_color_texture = u + 89;
    materials_half[i].emission_texture = u + 90;
    materials_half[i].metallic_roughness_texture = u + 105;
    materials_half[i].normal_texture = u + 106;
    materials_half[i].normal_scale = o + 107;
    materials_half[i].pad2 = u + 108;
    materials_half[i].alpha_mode = u + 125;
    materials_half[i].alpha_cutoff = o + 126;
    materials_half[i].alpha = o + 127;
    materials_half[i].double_sided = u + 128;
    nodes[i].lo = vec3(o + 25, o + 26, o + 27);
    nodes[i].first = u + 28;
    nodes[i].hi = vec3(o + 29, o + 30, o + 31);
    nodes[i].count_or_mask = u + 32;
    triangles[i].v0 = vec3(o + 33, o + 34, o + 35);
    triangles[i].material = u + 36;
    triangles[i].v1 = vec3(o + 37, o + 38, o + 39);
    triangles[i].pad0 = u + 40;
    triangles[i].v2 = vec3(o + 41, o + 42, o + 43);
    triangles[i].pad1 = u + 44;
    triangle_normals[i].n0 = vec3(o + 45, o + 46, o + 47);
    triangle_normals[i].tangent0 = u + 48;
    triangle_normals[i].n1 = vec3(o + 49, o + 50, o + 51);
    triangle_normals[i].tangent1 = u + 52;
    triangle_normals[i].n2 = vec3(o + 53, o + 54, o + 55);
    triangle_normals[i].tangent2 = u + 56;
    instances[i].to_object0 = vec4(o + 57, o + 58, o + 59, o + 60);
    instances[i].to_object1 = vec4(o + 61, o + 62, o + 63, o + 64);
    instances[i].to_object2 = vec4(o + 65, o + 66, o + 67, o + 68);
    instances[i].lo = vec3(o + 71, o + 72, o + 73);
    instances[i].mesh = u + 69;
    instances[i].hi = vec3(o + 74, o + 75, o + 76);
    instances[i].first_id = u + 70;
    meshes[i].root = u + 73;
    meshes[i].first_ref = u + 74;
    meshes[i].big_count = u + 75;
    meshes[i].first_triangle = u + 76;
    meshes[i].triangle_count = u + 77;
    meshes[i].pad0 = u + 78;
    meshes[i].pad1 = u + 79;
    meshes[i].pad2 = u + 80;
    textures[i].first_texel = u + 91;
    textures[i].width = u + 92;
    textures[i].height = u + 93;
    textures[i].wrap = u + 94;
    triangle_uvs[i].uv0 = vec2(o + 95, o + 96);
    triangle_uvs[i].uv1 = vec2(o + 97, o + 98);
    triangle_uvs[i].uv2 = vec2(o + 99, o + 100);
    uv_transforms[i].x_axis = vec2(o + 109, o + 110);
    uv_transforms[i].y_axis = vec2(o + 111, o + 112);
    uv_transforms[i].offset = vec2(o + 113, o + 114);
    lights[i].position = vec3(o + 121, o + 122, o + 123);
    lights[i].type = u + 124;
    lights[i].direction = vec3(o + 125, o + 126, o + 127);
    lights[i].radius = o + 128;
    lights[i].intensity = vec3(o + 129, o + 130, o + 131);
    lights[i].sphere = u + 132;
    lights[i].cos_inner = o + 133;
    lights[i].cos_outer = o + 134;
    lights[i].pmf = o + 135;
    lights[i].alias_q = o + 136;
    lights[i].alias = u + 137;
    lights[i].instance = u + 138;
    lights[i].triangle = u + 139;
    lights[i].pad0 = u + 140;
    transmissions[i].absorption = vec3(o + 141, o + 142, o + 143);
    transmissions[i].transmission_texture = u + 144;
  }
}
