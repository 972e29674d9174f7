// Scenes larger than one storage buffer (render/gpu_scene.cpp,
// shaders/shared/scene_buffers.glsl). A scene that needs more than one
// buffer per array is cut into parts read through buffer device addresses;
// the test hook OCTRACE_TEST_MAX_BUFFER_BYTES lowers the per-buffer limit so
// that small scenes split into many parts and render in milliseconds. Only
// how the arrays are stored differs: the image must be the same bit for bit.
// And a scene larger than the device's memory is refused up front, in one
// line (OCTRACE_TEST_DEVICE_MEMORY_BYTES fakes a small device).
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>

#include <unistd.h>

#include "scene/gltf.h"
#include "test_util.h"

namespace octrace {
namespace {

class BigSceneTest : public test::VulkanTest {};

// Sets a test hook's environment variable for a scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { unsetenv(name_); }

 private:
  const char* name_;
};

RenderSettings small_settings(Accel accel, Precision precision, Instancing instancing = Instancing::Auto) {
  RenderSettings s;
  s.octree.instancing = instancing;
  s.width = 32;
  s.height = 24;
  s.spp = 2;
  s.bounce_limit = 8;
  s.accel = accel;
  s.precision = precision;
  return s;
}

RenderResult render_small(const Scene& scene, Accel accel, Precision precision,
                          Instancing instancing = Instancing::Auto) {
  return render(test::shared_context(), scene, small_settings(accel, precision, instancing));
}

// Renders `scene` whole and split into parts of at most `max_bytes`, and
// expects the same image, bit for bit, and `parts` parts.
void expect_split_renders_the_same(const Scene& scene, Accel accel, Precision precision, uint64_t max_bytes,
                                   uint32_t parts, Instancing instancing = Instancing::Auto) {
  SCOPED_TRACE(std::string(accel_name(accel)) + " " + precision_name(precision));
  const RenderResult whole = render_small(scene, accel, precision, instancing);
  RenderResult split;
  {
    ScopedEnv limit("OCTRACE_TEST_MAX_BUFFER_BYTES", std::to_string(max_bytes));
    split = render_small(scene, accel, precision, instancing);
  }
  EXPECT_EQ(whole.buffer_parts, 0u);
  EXPECT_EQ(split.buffer_parts, parts);
  EXPECT_EQ(split.buffer_part_bytes, std::bit_floor(max_bytes));
  EXPECT_EQ(split.nonfinite_samples, 0u);
  ASSERT_EQ(whole.mean.rgb.size(), split.mean.rgb.size());
  EXPECT_EQ(std::memcmp(whole.mean.rgb.data(), split.mean.rgb.data(), whole.mean.rgb.size() * sizeof(float)), 0)
      << "the split render differs from the render in one buffer per array";
  EXPECT_EQ(whole.rays, split.rays);
}

// The default scene (492 spheres, 467 materials, 196 octree nodes, 733
// references): parts of 1 KiB hold 64 spheres, 256 material indices, 8
// materials (16 in fp16), 32 nodes or 256 references, so every array spans
// several parts (8, 2, 59 in fp32 or 30 in fp16: the materials go up in
// the render's precision only, log 130; 7 and 3) and a walk crosses part
// boundaries all the time.
TEST_F(BigSceneTest, SplitSpheresRenderAsInOneBuffer) {
  const Scene scene = make_rtiow_scene({});
  expect_split_renders_the_same(scene, Accel::Octree, Precision::FP32, 1024, 8 + 2 + 59 + 7 + 3);
  expect_split_renders_the_same(scene, Accel::Brute, Precision::FP32, 1024, 8 + 2 + 59);
  if (!test::shared_context().fp16_enabled) return;
  expect_split_renders_the_same(scene, Accel::Octree, Precision::FP16, 1024, 8 + 2 + 30 + 7 + 3);
  // Split in fp32, then switched to fp16: the fp16 materials go up into
  // parts of their own (the part table again), and the image is fp16's.
  const RenderSettings half = small_settings(Accel::Octree, Precision::FP16);
  const RenderResult want = render(test::shared_context(), scene, half);
  ScopedEnv limit("OCTRACE_TEST_MAX_BUFFER_BYTES", "1024");
  PathTracer tracer(test::shared_context(), scene, small_settings(Accel::Octree, Precision::FP32));
  EXPECT_EQ(tracer.buffer_parts(), 8u + 2 + 59 + 7 + 3);
  tracer.reconfigure(scene, Accel::Octree, Precision::FP16, false);
  EXPECT_EQ(tracer.buffer_parts(), 8u + 2 + 59 + 30 + 7 + 3);
  tracer.run_passes(pass_settings(scene, half), 0, half.spp);
  const RenderResult got = tracer.read_result();
  ASSERT_EQ(got.mean.rgb.size(), want.mean.rgb.size());
  EXPECT_EQ(std::memcmp(got.mean.rgb.data(), want.mean.rgb.data(), want.mean.rgb.size() * sizeof(float)), 0)
      << "switched to fp16 in parts, the image is not fp16's";
}

// Meshes: the 2CylinderEngine (Debian's assimp-testmodels) has instanced
// meshes (kept so: --instancing keep) with their own octrees and vertex
// normals: in parts of 1 MiB, its
// 75,730 triangles and their normals take 5 parts each (16,384 of 48 bytes
// a part), its 63,158 nodes and 392,906 references 2 each, its 34
// materials one (fp32 only: log 130). BoxTextured has texture coordinates:
// in parts of 256 bytes, its 12 triangles take 3 parts (4 a part), their
// normals 3 and uvs 2 (8 a part), its material one, and its octree of 2
// nodes and 13 references one each.
TEST_F(BigSceneTest, SplitMeshesRenderAsInOneBuffer) {
  const Scene engine =
      load_gltf_scene("/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  expect_split_renders_the_same(engine, Accel::Octree, Precision::FP32, 1 << 20, 5 + 5 + 2 + 2 + 1,
                                Instancing::Keep);
  const Scene box = load_gltf_scene("/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf");
  expect_split_renders_the_same(box, Accel::Octree, Precision::FP32, 256, 3 + 3 + 2 + 1 + 1 + 1);
  expect_split_renders_the_same(box, Accel::Brute, Precision::FP32, 256, 3 + 3 + 2 + 1);
}

// A part table has MAX_PARTS entries per array: more parts than that is
// refused, naming the array and the sizes. Parts of 128 bytes hold 8
// spheres (62 parts for 492) but one 80-byte material (467 parts).
TEST_F(BigSceneTest, MorePartsThanTheTableHoldsIsRefused) {
  ScopedEnv limit("OCTRACE_TEST_MAX_BUFFER_BYTES", "128");
  try {
    render_small(make_rtiow_scene({}), Accel::Brute, Precision::FP32);
    FAIL() << "no error";
  } catch (const SceneSizeError& e) {
    EXPECT_STREQ(e.what(),
                 "467 materials need 37360 bytes, more than 64 buffers of 128 bytes (the device allows 128 bytes per "
                 "buffer)");
  }
}

// A switch of structure (reconfigure) to a tree whose arrays do not fit the
// buffers the scene was uploaded in is refused, and leaves the device as it
// was: here the BVH with the spheres in its order (render/gpu_scene.cpp
// device_sphere_order), not to be put back in the scene's order for an
// octree that never comes. 60 small spheres in a clump: the octree of
// leaves of one sphere needs 185 nodes (5,920 bytes), more than the 4 KiB
// allowed; the BVH's scene fits (its largest array, 119 nodes, 3,808 bytes).
TEST_F(BigSceneTest, RefusedTreeLeavesTheSpheresInTheOrderTheyHave) {
  VulkanContext& ctx = test::shared_context();
  Scene scene = test::furnace_scene();
  scene.materials = {{MaterialType::Lambertian, {0.6f, 0.4f, 0.3f}}};
  for (int i = 0; i < 60; ++i) {
    const auto coordinate = [i](double step) { return float(2.0 * std::fmod(i * step, 1.0) - 1.0); };
    scene.spheres.push_back({{coordinate(0.6180339887), coordinate(0.4142135624), coordinate(0.7320508076)}, 0.15f, 0});
  }
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.spp = 2;
  s.bounce_limit = 8;
  s.accel = Accel::Bvh;
  s.octree.bvh_sphere_order = SphereOrder::Tree;
  s.octree.leaf_size = 1;
  PathTracer tracer(ctx, scene, s);
  ASSERT_TRUE(tracer.octree_stats().bvh_sphere_order);
  {
    ScopedEnv limit("OCTRACE_TEST_MAX_BUFFER_BYTES", "4096");
    EXPECT_THROW(tracer.reconfigure(scene, Accel::Octree, Precision::FP32, false), SceneSizeError);
  }
  EXPECT_EQ(tracer.settings().accel, Accel::Bvh);
  EXPECT_TRUE(tracer.octree_stats().bvh_sphere_order);
  tracer.run_passes(pass_settings(scene, s), 0, s.spp);
  const RenderResult got = tracer.read_result(), want = render(ctx, scene, s);
  ASSERT_EQ(got.mean.rgb.size(), want.mean.rgb.size());
  EXPECT_EQ(std::memcmp(got.mean.rgb.data(), want.mean.rgb.data(), got.mean.rgb.size() * sizeof(float)), 0)
      << "after the refused switch the tracer renders another image than the BVH's";
}

// Too large for the device's memory: exit 2, one line naming the scene
// file, what it needs and what the device has, and no output file. The
// device pretends to have 1,000,000 bytes; 70,000 spheres of one material
// need 1.4 MB (16 bytes of centre and radius and 4 of material index each).
// The built-in generator's scene gets the same line without a file name.
TEST_F(BigSceneTest, SceneLargerThanTheDeviceMemoryIsRefusedInOneLine) {
  const std::string json = test::tmp_path("big_scene_too_large.json");
  const std::string out = test::tmp_path("big_scene_too_large.png");
  std::string text = R"({"materials": [{"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}], "spheres": [)";
  for (int i = 0; i < 70000; ++i)
    text += std::string(i ? "," : "") + "{\"center\": [" + std::to_string(i % 300) + ", 0, " + std::to_string(i / 300) +
            "], \"radius\": 0.4, \"material\": 0}";
  std::ofstream(json) << text << "]}";
  std::filesystem::remove(out);
  const std::string env = "OCTRACE_TEST_DEVICE_MEMORY_BYTES=1000000";
  const auto errors = [](const std::string& output) {
    size_t n = 0;
    for (size_t at = output.find("octrace: error:"); at != std::string::npos; at = output.find("octrace: error:", at + 1))
      ++n;
    return n;
  };
  test::RunResult r =
      test::run_octrace("render --scene " + json + " --accel brute --size 32x24 --spp 1 -q -o " + out, env);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(errors(r.output), 1u) << r.output;
  EXPECT_NE(("\n" + r.output)
                .find("\noctrace: error: " + json +
                      ": 70000 spheres need 2 MiB of device memory, the device has 1000000 bytes "
                      "(OCTRACE_TEST_DEVICE_MEMORY_BYTES)\n"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  r = test::run_octrace("render --spheres 100000 --radius 0.01 --size 32x24 --spp 1 -q -o " + out, env);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(errors(r.output), 1u) << r.output;
  EXPECT_TRUE(std::regex_search("\n" + r.output,
                                std::regex("\noctrace: error: 100004 spheres with their octree need [0-9]+ MiB of device "
                                           "memory, the device has 1000000 bytes "
                                           "\\(OCTRACE_TEST_DEVICE_MEMORY_BYTES\\)\n$")))
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Without the hooks, a real device's memory and buffer limit are what the
// checks use: the heap (or its budget), and on a CPU device at least the
// host's memory; at least one buffer's worth.
TEST_F(BigSceneTest, DeviceMemoryAndBufferLimitComeFromTheDevice) {
  const VulkanContext& ctx = test::shared_context();
  const DeviceMemory memory = device_memory(ctx);
  EXPECT_GE(memory.bytes, max_buffer_bytes(ctx));
  EXPECT_LE(max_buffer_bytes(ctx), ctx.limits.maxStorageBufferRange);
  if (ctx.info.software) {
    EXPECT_GE(memory.bytes, uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE)));
  }
}

}  // namespace
}  // namespace octrace
