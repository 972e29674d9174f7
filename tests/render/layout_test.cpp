// The C++ structs of shaders/shared.h agree with the GLSL compiler's std430
// layout: a probe shader writes a distinct value into every field, and the
// host reads each one back through the C++ struct.
#include <vector>

#include "render/gpu_layout.h"
#include "layout_probe.h"
#include "test_util.h"
#include "vk/resources.h"

namespace octrace {
namespace {

class LayoutTest : public test::VulkanTest {};

TEST_F(LayoutTest, HostAndShaderAgreeOnEveryField) {
  VulkanContext& ctx = test::shared_context();
  Buffer frame_buf, sphere_buf, material_buf, stats_buf;
  create_buffer(frame_buf, ctx, sizeof(gpu::FrameParams), false, "probe");
  create_buffer(sphere_buf, ctx, 2 * sizeof(gpu::GpuSphere), false, "probe");
  create_buffer(material_buf, ctx, 2 * sizeof(gpu::GpuMaterial), false, "probe");
  create_buffer(stats_buf, ctx, 2 * sizeof(gpu::RenderStats), false, "probe");
  ComputePipeline pipeline;
  create_compute_pipeline(pipeline, ctx, layout_probe_spv, sizeof(layout_probe_spv), 4, 0);
  bind_buffers(pipeline, {&frame_buf, &sphere_buf, &material_buf, &stats_buf});
  submit_and_wait(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, 1, &pipeline.set, 0, nullptr);
    vkCmdDispatch(cmd, 1, 1, 1);
    compute_barrier(cmd);
  });

  gpu::FrameParams f{};
  download_buffer(ctx, frame_buf, &f, sizeof f);
  EXPECT_EQ(f.cam_origin, glm::vec3(1, 2, 3));
  EXPECT_EQ(f.lens_radius, 4);
  EXPECT_EQ(f.lens_u, glm::vec3(5, 6, 7));
  EXPECT_EQ(f.width, 8u);
  EXPECT_EQ(f.lens_v, glm::vec3(9, 10, 11));
  EXPECT_EQ(f.height, 12u);
  EXPECT_EQ(f.pixel00, glm::vec3(13, 14, 15));
  EXPECT_EQ(f.max_depth, 16u);
  EXPECT_EQ(f.pixel_du, glm::vec3(17, 18, 19));
  EXPECT_EQ(f.sample_seed, 20u);
  EXPECT_EQ(f.pixel_dv, glm::vec3(21, 22, 23));
  EXPECT_EQ(f.sphere_count, 24u);
  EXPECT_EQ(f.sky_a, glm::vec3(25, 26, 27));
  EXPECT_EQ(f.sky_type, 28u);
  EXPECT_EQ(f.sky_b, glm::vec3(29, 30, 31));
  EXPECT_EQ(f.big_count, 32u);

  gpu::GpuSphere spheres[2];
  gpu::GpuMaterial materials[2];
  gpu::RenderStats stats[2];
  download_buffer(ctx, sphere_buf, spheres, sizeof spheres);
  download_buffer(ctx, material_buf, materials, sizeof materials);
  download_buffer(ctx, stats_buf, stats, sizeof stats);
  for (int i = 0; i < 2; ++i) {
    float o = 100.0f * float(i + 1);
    uint32_t u = uint32_t(o);
    EXPECT_EQ(spheres[i].center, glm::vec3(o + 1, o + 2, o + 3)) << "sphere " << i;
    EXPECT_EQ(spheres[i].radius, o + 4) << "sphere " << i;
    EXPECT_EQ(materials[i].color, glm::vec3(o + 5, o + 6, o + 7)) << "material " << i;
    EXPECT_EQ(materials[i].type, u + 8) << "material " << i;
    EXPECT_EQ(materials[i].fuzz, o + 9) << "material " << i;
    EXPECT_EQ(materials[i].ior, o + 10) << "material " << i;
    EXPECT_EQ(materials[i].pad0, u + 11) << "material " << i;
    EXPECT_EQ(materials[i].pad1, u + 12) << "material " << i;
    EXPECT_EQ(stats[i].nonfinite_samples, u + 13) << "stats " << i;
    EXPECT_EQ(stats[i].pad2, u + 16) << "stats " << i;
  }
}

}  // namespace
}  // namespace octrace
