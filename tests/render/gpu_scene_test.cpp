// Packing the scene for the device: meshes stored once in object space,
// instances that carry the inverse of their placement and unique ids, and
// boxes for the top level (spheres, then instances).
#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "render/lights.h"
#include "scene/envmap.h"
#include "test_util.h"

namespace octrace {
namespace {

glm::vec3 apply(const gpu::GpuInstance& g, glm::vec3 p) {
  const glm::vec4 h(p, 1.0f);
  return {glm::dot(g.to_object0, h), glm::dot(g.to_object1, h), glm::dot(g.to_object2, h)};
}

// As the shader's normal_to_world: the transpose of the world-to-object 3x3.
glm::vec3 normal_to_world(const gpu::GpuInstance& g, glm::vec3 n) {
  return n.x * glm::vec3(g.to_object0) + n.y * glm::vec3(g.to_object1) + n.z * glm::vec3(g.to_object2);
}

Scene two_placements() {
  Scene s;
  s.materials = {test::lambertian(0.5f), test::lambertian(0.2f)};
  s.spheres = {{{1, 2, 3}, 0.5f, 0}};
  test::place(s, test::icosphere(1, 1, true), glm::translate(glm::mat4(1.0f), glm::vec3(-5, 0, 0)));
  // The same mesh placed again, mirrored and stretched: stored once.
  s.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 1.0f))});
  return s;
}

TEST(GpuScene, MeshesAreStoredOnceAndInstancesCarryTheirInverseAndIds) {
  const Scene s = two_placements();
  const size_t t = s.meshes[0].triangle_count();
  EXPECT_EQ(object_triangles(s).size(), t);
  EXPECT_EQ(object_triangle_normals(s).size(), t);
  const auto inst = gpu_instances(s);
  ASSERT_EQ(inst.size(), 2u);
  // Ids: spheres [0,1), instances [1,3), then each instance's triangles.
  EXPECT_EQ(inst[0].first_id, 3u);
  EXPECT_EQ(inst[1].first_id, 3u + t);
  const auto meshes = gpu_meshes(s);
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].triangle_count, t);
  // to_object undoes the placement.
  for (size_t i = 0; i < 2; ++i)
    for (glm::vec3 p : s.meshes[0].positions) {
      const glm::vec3 world(s.instances[i].transform * glm::vec4(p, 1.0f));
      const glm::vec3 back = apply(inst[i], world);
      EXPECT_NEAR(glm::distance(back, p), 0.0f, 1e-5f) << "instance " << i;
    }
}

// A closed mesh's normals leave every instance outward, the mirrored one too
// (the inverse transpose, not the winding of the world triangle, decides).
TEST(GpuScene, NormalsLeaveInstancesOutward) {
  const Scene s = two_placements();
  const auto tris = object_triangles(s);
  const auto inst = gpu_instances(s);
  for (size_t i = 0; i < 2; ++i) {
    const glm::vec3 center(s.instances[i].transform[3]);
    for (size_t k = 0; k < tris.size(); ++k) {
      const glm::vec3 n = normal_to_world(inst[i], glm::cross(tris[k].v1 - tris[k].v0, tris[k].v2 - tris[k].v0));
      const glm::vec3 c = (tris[k].v0 + tris[k].v1 + tris[k].v2) / 3.0f;
      const glm::vec3 world_c(s.instances[i].transform * glm::vec4(c, 1.0f));
      ASSERT_GT(glm::dot(n, world_c - center), 0.0f) << "instance " << i << ", triangle " << k;
    }
  }
}

TEST(GpuScene, TopLevelBoxesAreSpheresThenInstances) {
  const Scene s = two_placements();
  const auto boxes = primitive_boxes(s);
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[0].lo, glm::vec3(0.5f, 1.5f, 2.5f));
  EXPECT_EQ(boxes[0].hi, glm::vec3(1.5f, 2.5f, 3.5f));
  for (size_t i = 0; i < 2; ++i)
    for (glm::vec3 p : s.meshes[0].positions) {
      const glm::vec3 w(s.instances[i].transform * glm::vec4(p, 1.0f));
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(boxes[1 + i].lo[a], w[a] + 1e-5f);
        EXPECT_GE(boxes[1 + i].hi[a], w[a] - 1e-5f);
      }
    }
  // The mirrored, stretched instance: x spans 5 +- 2.
  EXPECT_NEAR(boxes[2].lo.x, 3.0f, 1e-5f);
  EXPECT_NEAR(boxes[2].hi.x, 7.0f, 1e-5f);
}

// A mesh placed once is baked into world space (mirrors flipped to keep
// their outside), one placed more often stays instanced.
TEST(GpuScene, MeshesPlacedOnceAreBakedIntoWorldSpace) {
  Scene s = two_placements();  // mesh 0 placed twice
  test::place(s, test::icosphere(1, 0), glm::translate(glm::mat4(1.0f), glm::vec3(0, 5, 0)) *
                                            glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, 1.0f)));
  const Scene b = bake_single_use_meshes(s);
  ASSERT_EQ(b.meshes.size(), 2u);     // the shared mesh, then the baked one
  ASSERT_EQ(b.instances.size(), 3u);  // two of the shared mesh, one identity
  EXPECT_EQ(b.instances[2].transform, glm::mat4(1.0f));
  EXPECT_EQ(b.meshes[1].triangle_count(), s.meshes[1].triangle_count());
  EXPECT_EQ(unique_triangle_count(b), unique_triangle_count(s));
  EXPECT_EQ(instanced_triangle_count(b), instanced_triangle_count(s));
  const Mesh& baked = b.meshes[1];
  for (size_t k = 0; k < baked.triangle_count(); ++k) {
    const glm::vec3 a = baked.positions[baked.indices[3 * k]], c1 = baked.positions[baked.indices[3 * k + 1]],
                    c2 = baked.positions[baked.indices[3 * k + 2]];
    ASSERT_GT(glm::dot(glm::cross(c1 - a, c2 - a), (a + c1 + c2) / 3.0f - glm::vec3(0, 5, 0)), 0.0f)
        << "baked mirrored triangle " << k << " faces inward";
  }
}

// Baking every instance: each placement of the shared mesh becomes a
// world-space copy in the one baked mesh, in instance order (mirrored ones
// turned outward), and nothing stays instanced.
TEST(GpuScene, EveryInstanceBakedIsACopyPerPlacement) {
  Scene s = two_placements();  // mesh 0 placed twice
  test::place(s, test::icosphere(1, 0), glm::translate(glm::mat4(1.0f), glm::vec3(0, 5, 0)));
  const Scene b = bake_single_use_meshes(s, true);
  ASSERT_EQ(b.meshes.size(), 1u);
  ASSERT_EQ(b.instances.size(), 1u);
  EXPECT_EQ(b.instances[0].transform, glm::mat4(1.0f));
  EXPECT_EQ(unique_triangle_count(b), instanced_triangle_count(s));
  EXPECT_EQ(instanced_triangle_count(b), instanced_triangle_count(s));
  const Mesh& baked = b.meshes[0];
  const size_t per_copy = s.meshes[0].triangle_count();
  for (size_t i = 0; i < 2; ++i) {
    const glm::vec3 center(s.instances[i].transform[3]);
    for (size_t k = 0; k < per_copy; ++k) {
      const uint32_t* v = &baked.indices[3 * (i * per_copy + k)];
      const glm::vec3 a = baked.positions[v[0]], c1 = baked.positions[v[1]], c2 = baked.positions[v[2]];
      ASSERT_GT(glm::dot(glm::cross(c1 - a, c2 - a), (a + c1 + c2) / 3.0f - center), 0.0f)
          << "copy " << i << ", triangle " << k << " faces inward";
    }
  }
}

// Instancing::Auto bakes every instance where the copies at most double the
// stored triangles and add at most kAutoBakeExtraTriangles; Keep and Bake
// do as they say; a scene without shared meshes has nothing to decide.
TEST(GpuScene, AutoInstancingBakesWhereTheCopiesAreFew) {
  EXPECT_TRUE(bakes_every_instance(Instancing::Auto, 75730, 121496));  // the engine: 1.6x
  EXPECT_TRUE(bakes_every_instance(Instancing::Auto, 100, 200));       // twice: at the limit
  EXPECT_FALSE(bakes_every_instance(Instancing::Auto, 100, 201));
  EXPECT_FALSE(bakes_every_instance(Instancing::Auto, 70000, 400 * 70000));  // issue 11's 400 instances
  EXPECT_TRUE(bakes_every_instance(Instancing::Auto, 10'000'000, 10'000'000 + kAutoBakeExtraTriangles));
  EXPECT_FALSE(bakes_every_instance(Instancing::Auto, 10'000'000, 10'000'001 + kAutoBakeExtraTriangles));
  EXPECT_TRUE(bakes_every_instance(Instancing::Auto, 0, 0));
  EXPECT_FALSE(bakes_every_instance(Instancing::Keep, 100, 101));
  EXPECT_TRUE(bakes_every_instance(Instancing::Bake, 70000, 400 * 70000));
  const Scene s = two_placements();
  EXPECT_EQ(device_meshes(s, Instancing::Keep).instances.size(), 2u);
  EXPECT_EQ(device_meshes(s, Instancing::Auto).instances.size(), 1u);
}

// Uvs follow their triangles into the baked mesh (mirrored ones too, whose
// winding flips), and a mesh without uvs gets zeros beside one with them.
TEST(GpuScene, UvsFollowTheirTrianglesIntoTheBakedMesh) {
  Scene s;
  s.materials = {test::lambertian(0.5f)};
  Mesh with = test::grid(1, 0);
  with.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  test::place(s, with, glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)));
  test::place(s, test::grid(1, 0), glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 3)));
  const Scene b = bake_single_use_meshes(s);
  ASSERT_EQ(b.meshes.size(), 1u);
  const Mesh& baked = b.meshes[0];
  ASSERT_EQ(baked.uvs.size(), baked.positions.size());
  for (size_t v = 0; v < baked.positions.size(); ++v) {
    const glm::vec3 p = baked.positions[v];
    // The first grid, mirrored in x: a vertex at (x, y) had uv (-x, y); the second has none.
    const glm::vec2 want = p.z == 0.0f ? glm::vec2(-p.x, p.y) : glm::vec2(0.0f);
    EXPECT_EQ(baked.uvs[v], want) << "vertex " << v;
  }
  const auto uvs = object_triangle_uvs(b);
  ASSERT_EQ(uvs.size(), 4u);
  EXPECT_EQ(uvs[0].uv1, baked.uvs[baked.indices[1]]);
}

// The texture table: each texture's first texel in the one texel buffer, its
// size and both wrap modes.
TEST(GpuScene, TexturesArePackedIntoOneTexelBuffer) {
  Scene s;
  s.textures = {{2, 1, {1, 2}, Wrap::ClampToEdge, Wrap::MirroredRepeat}, {1, 3, {3, 4, 5}, Wrap::Repeat, Wrap::ClampToEdge}};
  const GpuTextures t = gpu_textures(s);
  EXPECT_EQ(t.texels, (std::vector<uint32_t>{1, 2, 3, 4, 5}));
  ASSERT_EQ(t.table.size(), 2u);
  EXPECT_EQ(t.table[0].first_texel, 0u);
  EXPECT_EQ(t.table[1].first_texel, 2u);
  EXPECT_EQ(t.table[1].width, 1u);
  EXPECT_EQ(t.table[1].height, 3u);
  EXPECT_EQ(t.table[0].wrap, gpu::WRAP_CLAMP_TO_EDGE | gpu::WRAP_MIRRORED_REPEAT << 16);
  EXPECT_EQ(t.table[1].wrap, gpu::WRAP_REPEAT | gpu::WRAP_CLAMP_TO_EDGE << 16);
}

// The sky as a light (render/lights.h): an envmap joins the light list as
// its last entry, with power pi R^2 x the integral of its luminance over the
// sphere (2 pi^2 / the tables' density scale); the pick is the 50/50 mix of
// power and uniform. A gradient sky and a black envmap are no lights.
TEST(Lights, EnvmapIsTheLastLightWeightedByItsPower) {
  Scene s;
  s.materials = {test::emitter(glm::vec3(4.0f))};
  s.spheres = {{{0, 0, 0}, 0.5f, 0}};
  EXPECT_EQ(build_light_list(s).lights.size(), 1u);  // gradient sky: no light
  s.sky = test::envmap_sky(test::test_envmap(32, 16, 2000.0f), 2.0f);
  const LightList list = build_light_list(s);
  ASSERT_EQ(list.lights.size(), 2u);
  EXPECT_EQ(list.lights[0].type, gpu::LIGHT_SPHERE);
  EXPECT_EQ(list.lights[1].type, gpu::LIGHT_ENVMAP);
  const double pi = 3.14159265358979;
  const double sphere = 4 * pi * pi * 0.25 * 4.0;
  const float scale = build_envmap_tables(s.sky.image).marginal[16 + 1];
  const double sky = pi * 1.0 * 2.0 * 2 * pi * pi / double(scale);  // R = 0.5: R^2 clamped to 1
  const double expected = 0.5 * sky / (sky + sphere) + 0.25;
  EXPECT_NEAR(list.lights[1].pmf, expected, 1e-6);
  EXPECT_NEAR(list.lights[0].pmf + list.lights[1].pmf, 1.0, 1e-6);
  s.sky.strength = 0.0f;
  EXPECT_EQ(build_light_list(s).lights.size(), 1u);
}

}  // namespace
}  // namespace octrace
