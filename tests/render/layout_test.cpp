// The C++ structs of shaders/shared/shared.h agree with the GLSL compiler's
// std430 layout: a probe shader writes a distinct value into every field of
// every shared struct, and the host reads each one back through the C++ struct.
#include <vector>

#include <glm/gtc/packing.hpp>

#include "layout_probe.h"
#include "render/gpu_layout.h"
#include "test_util.h"
#include "vk/resources.h"

namespace octrace {
namespace {

class LayoutTest : public test::VulkanTest {};

TEST_F(LayoutTest, HostAndShaderAgreeOnEveryField) {
  VulkanContext& ctx = test::shared_context();
  // The probe writes the half material too: it needs 16-bit storage, which
  // every device the suite runs on (lavapipe, the H100) has.
  ASSERT_TRUE(ctx.fp16_enabled) << ctx.info.name << " lacks 16-bit storage";
  Buffer scene_buf, pass_buf, resolve_buf, sphere_buf, material_buf, half_buf, node_buf, stats_buf, tri_buf, normal_buf,
      inst_buf, mesh_buf, texture_buf, uv_buf, uv_transform_buf, light_buf, transmission_buf,
      tail_buf, tail_control_buf;
  create_buffer(scene_buf, ctx, sizeof(gpu::SceneParams), false, "probe");
  create_buffer(pass_buf, ctx, sizeof(gpu::PassParams), false, "probe");
  create_buffer(resolve_buf, ctx, sizeof(gpu::ResolveParams), false, "probe");
  create_buffer(sphere_buf, ctx, 2 * sizeof(gpu::GpuSphere), false, "probe");
  create_buffer(material_buf, ctx, 2 * sizeof(gpu::GpuMaterial), false, "probe");
  create_buffer(half_buf, ctx, 2 * sizeof(gpu::GpuMaterialHalf), false, "probe");
  create_buffer(node_buf, ctx, 2 * sizeof(gpu::GpuOctreeNode), false, "probe");
  create_buffer(stats_buf, ctx, 2 * sizeof(gpu::RenderStats), false, "probe");
  create_buffer(tri_buf, ctx, 2 * sizeof(gpu::GpuTriangle), false, "probe");
  create_buffer(normal_buf, ctx, 2 * sizeof(gpu::GpuTriangleNormals), false, "probe");
  create_buffer(inst_buf, ctx, 2 * sizeof(gpu::GpuInstance), false, "probe");
  create_buffer(mesh_buf, ctx, 2 * sizeof(gpu::GpuMesh), false, "probe");
  create_buffer(texture_buf, ctx, 2 * sizeof(gpu::GpuTexture), false, "probe");
  create_buffer(uv_buf, ctx, 2 * sizeof(gpu::GpuTriangleUvs), false, "probe");
  create_buffer(uv_transform_buf, ctx, 2 * sizeof(gpu::GpuUvTransform), false, "probe");
  create_buffer(light_buf, ctx, 2 * sizeof(gpu::GpuLight), false, "probe");
  create_buffer(transmission_buf, ctx, 2 * sizeof(gpu::GpuTransmission), false, "probe");
  create_buffer(tail_buf, ctx, 2 * sizeof(gpu::GpuTailPath), false, "probe");
  create_buffer(tail_control_buf, ctx, sizeof(gpu::TailControl), false, "probe");
  ComputePipeline pipeline;
  create_compute_pipeline(pipeline, ctx, layout_probe_spv, sizeof(layout_probe_spv), 19, 0);
  bind_buffers(pipeline, {{0, &scene_buf}, {1, &pass_buf}, {2, &resolve_buf}, {3, &sphere_buf},
                          {4, &material_buf}, {5, &half_buf}, {6, &node_buf}, {7, &stats_buf},
                          {8, &tri_buf},   {9, &normal_buf}, {10, &inst_buf}, {11, &mesh_buf},
                          {12, &texture_buf}, {13, &uv_buf}, {14, &uv_transform_buf}, {15, &light_buf},
                          {16, &transmission_buf}, {17, &tail_buf}, {18, &tail_control_buf}});
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, 1, &pipeline.set, 0, nullptr);
    vkCmdDispatch(cmd, 1, 1, 1);
    compute_barrier(cmd);
  });

  gpu::SceneParams sc{};
  download_buffer(ctx, scene_buf, &sc, sizeof sc);
  EXPECT_EQ(sc.sky_a, glm::vec3(1, 2, 3));
  EXPECT_EQ(sc.sky_type, 4u);
  EXPECT_EQ(sc.sky_b, glm::vec3(5, 6, 7));
  EXPECT_EQ(sc.sphere_count, 8u);
  EXPECT_EQ(sc.big_count, 9u);
  EXPECT_EQ(sc.triangle_count, 10u);
  EXPECT_EQ(sc.vertex_normals, 11u);
  EXPECT_EQ(sc.instance_count, 12u);
  EXPECT_EQ(sc.triangle_uvs, 13u);
  EXPECT_EQ(sc.light_count, 14u);
  EXPECT_EQ(sc.envmap_width, 15u);
  EXPECT_EQ(sc.envmap_height, 16u);

  gpu::PassParams f{};
  download_buffer(ctx, pass_buf, &f, sizeof f);
  EXPECT_EQ(f.cam_origin, glm::vec3(1, 2, 3));
  EXPECT_EQ(f.lens_radius, 4);
  EXPECT_EQ(f.lens_u, glm::vec3(5, 6, 7));
  EXPECT_EQ(f.width, 8u);
  EXPECT_EQ(f.lens_v, glm::vec3(9, 10, 11));
  EXPECT_EQ(f.height, 12u);
  EXPECT_EQ(f.pixel00, glm::vec3(13, 14, 15));
  EXPECT_EQ(f.bounce_limit, 16u);
  EXPECT_EQ(f.pixel_du, glm::vec3(17, 18, 19));
  EXPECT_EQ(f.sample_seed, 20u);
  EXPECT_EQ(f.pixel_dv, glm::vec3(21, 22, 23));
  EXPECT_EQ(f.sample_index, 24u);
  EXPECT_EQ(f.rr_depth, 25u);
  EXPECT_EQ(f.sample_count, 26u);
  EXPECT_EQ(f.sample_lanes, 27u);
  EXPECT_EQ(f.tail_depth, 28u);
  EXPECT_EQ(f.tail_capacity, 29u);
  EXPECT_EQ(f.tail_level, 30u);
  EXPECT_EQ(f.tail_end, 31u);
  EXPECT_EQ(f.tail_fill, 32u);

  gpu::TailControl tc{};
  download_buffer(ctx, tail_control_buf, &tc, sizeof tc);
  EXPECT_EQ(tc.count, 41u);
  EXPECT_EQ(tc.groups_x, 42u);
  EXPECT_EQ(tc.groups_y, 43u);
  EXPECT_EQ(tc.groups_z, 44u);
  EXPECT_EQ(tc.subgroup_groups_x, 45u);
  EXPECT_EQ(tc.subgroup_groups_y, 46u);
  EXPECT_EQ(tc.subgroup_groups_z, 47u);
  EXPECT_EQ(tc.fetched, 48u);
  gpu::GpuTailPath tails[2];
  download_buffer(ctx, tail_buf, tails, sizeof tails);

  gpu::ResolveParams r{};
  download_buffer(ctx, resolve_buf, &r, sizeof r);
  EXPECT_EQ(r.width, 1u);
  EXPECT_EQ(r.height, 2u);
  EXPECT_EQ(r.pad0, 3u);
  EXPECT_EQ(r.pad1, 4u);

  gpu::GpuSphere spheres[2];
  gpu::GpuMaterial materials[2];
  gpu::GpuMaterialHalf halves[2];
  gpu::GpuOctreeNode nodes[2];
  gpu::RenderStats stats[2];
  gpu::GpuTriangle tris[2];
  gpu::GpuTriangleNormals normals[2];
  download_buffer(ctx, tri_buf, tris, sizeof tris);
  download_buffer(ctx, normal_buf, normals, sizeof normals);
  gpu::GpuInstance insts[2];
  gpu::GpuMesh meshes[2];
  gpu::GpuTexture textures[2];
  gpu::GpuTriangleUvs uvs[2];
  download_buffer(ctx, inst_buf, insts, sizeof insts);
  download_buffer(ctx, mesh_buf, meshes, sizeof meshes);
  download_buffer(ctx, texture_buf, textures, sizeof textures);
  download_buffer(ctx, uv_buf, uvs, sizeof uvs);
  gpu::GpuUvTransform uv_transforms[2];
  download_buffer(ctx, uv_transform_buf, uv_transforms, sizeof uv_transforms);
  gpu::GpuLight lights[2];
  download_buffer(ctx, light_buf, lights, sizeof lights);
  gpu::GpuTransmission transmissions[2];
  download_buffer(ctx, transmission_buf, transmissions, sizeof transmissions);
  download_buffer(ctx, sphere_buf, spheres, sizeof spheres);
  download_buffer(ctx, material_buf, materials, sizeof materials);
  download_buffer(ctx, half_buf, halves, sizeof halves);
  download_buffer(ctx, node_buf, nodes, sizeof nodes);
  download_buffer(ctx, stats_buf, stats, sizeof stats);
  const auto half = [](uint16_t bits) { return glm::unpackHalf1x16(bits); };
  for (int i = 0; i < 2; ++i) {
    float o = 100.0f * float(i + 1);
    uint32_t u = uint32_t(o);
    EXPECT_EQ(spheres[i].center, glm::vec3(o + 1, o + 2, o + 3)) << "sphere " << i;
    EXPECT_EQ(spheres[i].radius, o + 4) << "sphere " << i;
    EXPECT_EQ(materials[i].color, glm::vec3(o + 5, o + 6, o + 7)) << "material " << i;
    EXPECT_EQ(materials[i].type, u + 8) << "material " << i;
    EXPECT_EQ(materials[i].fuzz, o + 9) << "material " << i;
    EXPECT_EQ(materials[i].ior, o + 10) << "material " << i;
    EXPECT_EQ(materials[i].base_color_texture, u + 11) << "material " << i;
    EXPECT_EQ(materials[i].emission_texture, u + 12) << "material " << i;
    EXPECT_EQ(materials[i].emission, glm::vec3(o + 81, o + 82, o + 83)) << "material " << i;
    EXPECT_EQ(materials[i].metallic_roughness_texture, u + 84) << "material " << i;
    EXPECT_EQ(materials[i].metallic, o + 101) << "material " << i;
    EXPECT_EQ(materials[i].roughness, o + 102) << "material " << i;
    EXPECT_EQ(materials[i].normal_texture, u + 103) << "material " << i;
    EXPECT_EQ(materials[i].normal_scale, o + 104) << "material " << i;
    EXPECT_EQ(materials[i].alpha_mode, u + 121) << "material " << i;
    EXPECT_EQ(materials[i].alpha_cutoff, o + 122) << "material " << i;
    EXPECT_EQ(materials[i].alpha, o + 123) << "material " << i;
    EXPECT_EQ(materials[i].double_sided, u + 124) << "material " << i;
    EXPECT_EQ(stats[i].nonfinite_samples, u + 13) << "stats " << i;
    EXPECT_EQ(stats[i].cut_paths, u + 14) << "stats " << i;
    EXPECT_EQ(stats[i].loop_bound, u + 15) << "stats " << i;
    EXPECT_EQ(stats[i].pad2, u + 16) << "stats " << i;
    for (int k = 0; k < int(2 * gpu::WALK_COUNTERS); ++k) EXPECT_EQ(stats[i].walk[k], u + 300 + k) << "stats " << i << " walk " << k;
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(half(halves[i].color_type[c]), o + 17 + float(c)) << "half material " << i << " color_type " << c;
      EXPECT_EQ(half(halves[i].params[c]), o + 21 + float(c)) << "half material " << i << " params " << c;
      EXPECT_EQ(half(halves[i].emission[c]), o + 85 + float(c)) << "half material " << i << " emission " << c;
    }
    EXPECT_EQ(halves[i].base_color_texture, u + 89) << "half material " << i;
    EXPECT_EQ(halves[i].emission_texture, u + 90) << "half material " << i;
    EXPECT_EQ(halves[i].metallic_roughness_texture, u + 105) << "half material " << i;
    EXPECT_EQ(halves[i].normal_texture, u + 106) << "half material " << i;
    EXPECT_EQ(halves[i].normal_scale, o + 107) << "half material " << i;
    EXPECT_EQ(halves[i].pad2, u + 108) << "half material " << i;
    EXPECT_EQ(halves[i].alpha_mode, u + 125) << "half material " << i;
    EXPECT_EQ(halves[i].alpha_cutoff, o + 126) << "half material " << i;
    EXPECT_EQ(halves[i].alpha, o + 127) << "half material " << i;
    EXPECT_EQ(halves[i].double_sided, u + 128) << "half material " << i;
    EXPECT_EQ(nodes[i].lo, glm::vec3(o + 25, o + 26, o + 27)) << "node " << i;
    EXPECT_EQ(nodes[i].first, u + 28) << "node " << i;
    EXPECT_EQ(nodes[i].hi, glm::vec3(o + 29, o + 30, o + 31)) << "node " << i;
    EXPECT_EQ(nodes[i].count_or_mask, u + 32) << "node " << i;
    EXPECT_EQ(tris[i].v0, glm::vec3(o + 33, o + 34, o + 35)) << "triangle " << i;
    EXPECT_EQ(tris[i].material, u + 36) << "triangle " << i;
    EXPECT_EQ(tris[i].v1, glm::vec3(o + 37, o + 38, o + 39)) << "triangle " << i;
    EXPECT_EQ(tris[i].pad0, u + 40) << "triangle " << i;
    EXPECT_EQ(tris[i].v2, glm::vec3(o + 41, o + 42, o + 43)) << "triangle " << i;
    EXPECT_EQ(tris[i].pad1, u + 44) << "triangle " << i;
    EXPECT_EQ(normals[i].n0, glm::vec3(o + 45, o + 46, o + 47)) << "normals " << i;
    EXPECT_EQ(normals[i].tangent0, u + 48) << "normals " << i;
    EXPECT_EQ(normals[i].n1, glm::vec3(o + 49, o + 50, o + 51)) << "normals " << i;
    EXPECT_EQ(normals[i].tangent1, u + 52) << "normals " << i;
    EXPECT_EQ(normals[i].n2, glm::vec3(o + 53, o + 54, o + 55)) << "normals " << i;
    EXPECT_EQ(normals[i].tangent2, u + 56) << "normals " << i;
    EXPECT_EQ(insts[i].to_object0, glm::vec4(o + 57, o + 58, o + 59, o + 60)) << "instance " << i;
    EXPECT_EQ(insts[i].to_object1, glm::vec4(o + 61, o + 62, o + 63, o + 64)) << "instance " << i;
    EXPECT_EQ(insts[i].to_object2, glm::vec4(o + 65, o + 66, o + 67, o + 68)) << "instance " << i;
    EXPECT_EQ(insts[i].mesh, u + 69) << "instance " << i;
    EXPECT_EQ(insts[i].first_id, u + 70) << "instance " << i;
    EXPECT_EQ(insts[i].lo, glm::vec3(o + 71, o + 72, o + 73)) << "instance " << i;
    EXPECT_EQ(insts[i].hi, glm::vec3(o + 74, o + 75, o + 76)) << "instance " << i;
    EXPECT_EQ(meshes[i].root, u + 73) << "mesh " << i;
    EXPECT_EQ(meshes[i].first_ref, u + 74) << "mesh " << i;
    EXPECT_EQ(meshes[i].big_count, u + 75) << "mesh " << i;
    EXPECT_EQ(meshes[i].first_triangle, u + 76) << "mesh " << i;
    EXPECT_EQ(meshes[i].triangle_count, u + 77) << "mesh " << i;
    EXPECT_EQ(meshes[i].pad0, u + 78) << "mesh " << i;
    EXPECT_EQ(meshes[i].pad1, u + 79) << "mesh " << i;
    EXPECT_EQ(meshes[i].pad2, u + 80) << "mesh " << i;
    EXPECT_EQ(textures[i].first_texel, u + 91) << "texture " << i;
    EXPECT_EQ(textures[i].width, u + 92) << "texture " << i;
    EXPECT_EQ(textures[i].height, u + 93) << "texture " << i;
    EXPECT_EQ(textures[i].wrap, u + 94) << "texture " << i;
    EXPECT_EQ(uvs[i].uv0, glm::vec2(o + 95, o + 96)) << "uvs " << i;
    EXPECT_EQ(uvs[i].uv1, glm::vec2(o + 97, o + 98)) << "uvs " << i;
    EXPECT_EQ(uvs[i].uv2, glm::vec2(o + 99, o + 100)) << "uvs " << i;
    EXPECT_EQ(uv_transforms[i].x_axis, glm::vec2(o + 109, o + 110)) << "uv transform " << i;
    EXPECT_EQ(uv_transforms[i].y_axis, glm::vec2(o + 111, o + 112)) << "uv transform " << i;
    EXPECT_EQ(uv_transforms[i].offset, glm::vec2(o + 113, o + 114)) << "uv transform " << i;
    EXPECT_EQ(lights[i].position, glm::vec3(o + 121, o + 122, o + 123)) << "light " << i;
    EXPECT_EQ(lights[i].type, u + 124) << "light " << i;
    EXPECT_EQ(lights[i].direction, glm::vec3(o + 125, o + 126, o + 127)) << "light " << i;
    EXPECT_EQ(lights[i].radius, o + 128) << "light " << i;
    EXPECT_EQ(lights[i].intensity, glm::vec3(o + 129, o + 130, o + 131)) << "light " << i;
    EXPECT_EQ(lights[i].sphere, u + 132) << "light " << i;
    EXPECT_EQ(lights[i].cos_inner, o + 133) << "light " << i;
    EXPECT_EQ(lights[i].cos_outer, o + 134) << "light " << i;
    EXPECT_EQ(lights[i].pmf, o + 135) << "light " << i;
    EXPECT_EQ(lights[i].alias_q, o + 136) << "light " << i;
    EXPECT_EQ(lights[i].alias, u + 137) << "light " << i;
    EXPECT_EQ(lights[i].instance, u + 138) << "light " << i;
    EXPECT_EQ(lights[i].triangle, u + 139) << "light " << i;
    EXPECT_EQ(lights[i].pad0, u + 140) << "light " << i;
    EXPECT_EQ(transmissions[i].absorption, glm::vec3(o + 141, o + 142, o + 143)) << "transmission " << i;
    EXPECT_EQ(transmissions[i].transmission_texture, u + 144) << "transmission " << i;
    EXPECT_EQ(tails[i].origin, glm::vec3(o + 151, o + 152, o + 153)) << "tail path " << i;
    EXPECT_EQ(tails[i].pixel, u + 154) << "tail path " << i;
    EXPECT_EQ(tails[i].dir, glm::vec3(o + 155, o + 156, o + 157)) << "tail path " << i;
    EXPECT_EQ(tails[i].sample_offset, u + 158) << "tail path " << i;
    EXPECT_EQ(tails[i].throughput, glm::vec3(o + 159, o + 160, o + 161)) << "tail path " << i;
    EXPECT_EQ(tails[i].bounce_flags, u + 162) << "tail path " << i;
    EXPECT_EQ(tails[i].radiance, glm::vec3(o + 163, o + 164, o + 165)) << "tail path " << i;
    EXPECT_EQ(tails[i].segments, u + 166) << "tail path " << i;
    EXPECT_EQ(tails[i].direct, glm::vec3(o + 167, o + 168, o + 169)) << "tail path " << i;
    EXPECT_EQ(tails[i].from_prim, u + 170) << "tail path " << i;
    EXPECT_EQ(tails[i].prev_p, glm::vec3(o + 171, o + 172, o + 173)) << "tail path " << i;
    EXPECT_EQ(tails[i].prev_pdf, o + 174) << "tail path " << i;
  }
}

}  // namespace
}  // namespace octrace
