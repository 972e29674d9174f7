// Packing the scene for the device: mesh instances become world-space
// triangles whose counter-clockwise side is still their front, with normals
// that follow, and the octree is built over spheres then triangles.
#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "test_util.h"

namespace octrace {
namespace {

glm::vec3 centroid(const gpu::GpuTriangle& t) { return (t.v0 + t.v1 + t.v2) / 3.0f; }
glm::vec3 face_normal(const gpu::GpuTriangle& t) { return glm::cross(t.v1 - t.v0, t.v2 - t.v0); }

// Every triangle of a closed convex mesh about `center` faces away from it.
void expect_outward(const std::vector<gpu::GpuTriangle>& tris, glm::vec3 center, const char* what) {
  for (size_t k = 0; k < tris.size(); ++k)
    ASSERT_GT(glm::dot(face_normal(tris[k]), centroid(tris[k]) - center), 0.0f) << what << ": triangle " << k;
}

TEST(GpuScene, InstancesBecomeWorldTrianglesFacingOutEvenWhenMirrored) {
  Scene s;
  s.materials = {test::lambertian(0.5f), test::lambertian(0.2f)};
  const Mesh mesh = test::icosphere(1, 1, true);
  expect_outward(world_triangles([&] {
                   Scene one = s;
                   test::place(one, mesh);
                   return one;
                 }()),
                 glm::vec3(0), "the mesh itself");
  const glm::mat4 mirror = glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0)) *
                           glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 1.0f));
  test::place(s, mesh, glm::translate(glm::mat4(1.0f), glm::vec3(-5, 0, 0)));
  s.instances.push_back({0, mirror});  // the same mesh placed again: stored once
  ASSERT_EQ(s.meshes.size(), 1u);
  const auto tris = world_triangles(s);
  ASSERT_EQ(tris.size(), 2 * mesh.triangle_count());
  EXPECT_EQ(instanced_triangle_count(s), 2 * mesh.triangle_count());
  const std::vector<gpu::GpuTriangle> first(tris.begin(), tris.begin() + long(mesh.triangle_count()));
  const std::vector<gpu::GpuTriangle> second(tris.begin() + long(mesh.triangle_count()), tris.end());
  expect_outward(first, glm::vec3(-5, 0, 0), "translated");
  expect_outward(second, glm::vec3(5, 0, 0), "mirrored (negative determinant)");
  for (const auto& t : tris) EXPECT_EQ(t.material, 1u);

  // Vertex normals go through the inverse transpose: still outward and unit
  // under the non-uniform mirror.
  const auto normals = world_triangle_normals(s);
  ASSERT_EQ(normals.size(), tris.size());
  for (size_t k = mesh.triangle_count(); k < tris.size(); ++k) {
    for (glm::vec3 n : {normals[k].n0, normals[k].n1, normals[k].n2}) {
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
      EXPECT_GT(glm::dot(n, centroid(tris[k]) - glm::vec3(5, 0, 0)), 0.0f) << "triangle " << k;
    }
  }
}

TEST(GpuScene, BoxesAreSpheresThenTriangles) {
  Scene s;
  s.materials = {test::lambertian(0.5f)};
  s.spheres = {{{1, 2, 3}, 0.5f, 0}};
  test::place(s, test::grid(1, 0), glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)));
  const auto boxes = primitive_boxes(s);
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[0].lo, glm::vec3(0.5f, 1.5f, 2.5f));
  EXPECT_EQ(boxes[0].hi, glm::vec3(1.5f, 2.5f, 3.5f));
  EXPECT_EQ(boxes[1].lo, glm::vec3(10, 0, 0));  // (10,0)-(11,0)-(11,1)
  EXPECT_EQ(boxes[1].hi, glm::vec3(11, 1, 0));
  EXPECT_EQ(boxes[2].lo, glm::vec3(10, 0, 0));  // (10,0)-(11,1)-(10,1)
  EXPECT_EQ(boxes[2].hi, glm::vec3(11, 1, 0));
}

}  // namespace
}  // namespace octrace
