// Octree, BVH and brute force find the same closest hit, so with the same
// random numbers they render the same image. All run the same intersect_sphere
// on the same spheres and keep the nearest; a tree only changes which
// spheres are tested and in which order. Exact ties (two spheres at the same
// t: coincident spheres, the wedge where a small sphere touches the ground)
// go to the lower sphere index in the scene in both (test_sphere in
// accel/closest_hit.glsl; with the spheres in a BVH's order on the device,
// the index that refs keeps for each position).
//
// Tolerance. Up to depth 8 the images must be bit-identical. At depth 50 a
// few pixel-channels may differ: brute force and octree are two pipelines
// (specialization constant ACCEL), compiled separately, and the driver is
// free to contract a*b+c into an FMA differently in each (GLSL allows it
// unless `precise`); a last-bit difference in a hit point is amplified along
// paths that bounce many times (inside glass, in the wedge under a sphere).
// Seen on lavapipe: 81 of 7680 values differ at depth 50 for 8000 spheres of
// r=0.05, none up to depth 8. Even brute force with its loop reversed differs
// from itself the same way, so it is not the octree. So at depth 50 at least
// 98% of values must be bit-identical and the image must agree statistically
// (mean over all pixels within 1%).
#include <cmath>
#include <cstring>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gpu_scene.h"
#include "test_util.h"

namespace octrace {
namespace {

struct AccelCase {
  const char* name;
  Scene (*make)();
};
void PrintTo(const AccelCase& c, std::ostream* os) { *os << c.name; }

Scene rtiow(uint64_t n, float r, uint64_t seed) { return make_rtiow_scene({n, r, seed}); }

// Spheres centred on the root's split planes and straddling them; the root's
// midpoints are at 0 on every axis since the spheres are symmetric about 0.
Scene split_planes() {
  Scene s = test::furnace_scene();
  s.sky.type = SkyType::Gradient;
  s.materials = {{MaterialType::Lambertian, {0.7f, 0.3f, 0.3f}}, {MaterialType::Metal, {0.9f, 0.9f, 0.9f}, 0.1f}};
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) s.spheres.push_back({{float(i), float(j), 0.0f}, 0.5f, uint32_t((i + j) & 1)});
  s.spheres.push_back({{-3.5f, -3.5f, -0.5f}, 0.1f, 0});
  s.spheres.push_back({{3.5f, 3.5f, 0.5f}, 0.1f, 0});
  return s;
}

Scene coincident() {
  Scene s = split_planes();
  s.materials.push_back({MaterialType::Lambertian, {0.1f, 0.9f, 0.1f}});
  size_t n = s.spheres.size();
  for (size_t i = 0; i < n; ++i) s.spheres.push_back({s.spheres[i].center, s.spheres[i].radius, 2});
  return s;
}

// Twelve copies of one sphere, each of its own colour: every ray that meets
// them ties among all twelve, and the first in the scene wins. More than
// kBvhMaxLeaf, so the BVH splits them at their median id (nth_element), which
// leaves its halves in another order than the scene's: a BVH that holds the
// spheres in its own order must still break ties by the scene's.
Scene coincident_many() {
  Scene s = test::furnace_scene();
  s.sky.type = SkyType::Gradient;
  for (int i = 0; i < 12; ++i) {
    s.materials.push_back({MaterialType::Lambertian, {0.08f * float(i), 0.9f - 0.07f * float(i), 0.5f}});
    s.spheres.push_back({{0.0f, 0.0f, 0.0f}, 1.5f, uint32_t(i)});
  }
  s.spheres.push_back({{0.0f, -101.5f, 0.0f}, 100.0f, 0});
  return s;
}

Scene one_huge_sphere() {
  Scene s = split_planes();
  s.spheres.push_back({{0, -1e5f, 0}, 1e5f - 4.0f, 1});
  return s;
}

// Spheres alone, some of them lights (sampled by next-event estimation):
// with the spheres in a BVH's order, a sphere light names its new position.
Scene emissive_spheres() {
  Scene s = rtiow(300, 0.2f, 6);
  s.sky.type = SkyType::Uniform;
  s.sky.radiance = glm::vec3(0.05f);
  s.materials.push_back(test::emitter(glm::vec3(4.0f, 3.0f, 2.0f)));
  for (size_t i = 0; i < s.spheres.size(); i += 7) s.spheres[i].material = uint32_t(s.materials.size() - 1);
  return s;
}

// The camera inside the root: among the spheres of the field.
Scene camera_inside() {
  Scene s = rtiow(300, 0.2f, 5);
  s.camera.lookfrom = {0.3f, 0.5f, 0.2f};
  s.camera.lookat = {5, 0.2f, 3};
  s.camera.focus_dist = 5;
  return s;
}

// Axis-aligned view: camera rays with direction components of exactly 0.
Scene axis_aligned() {
  Scene s = split_planes();
  s.camera.lookfrom = {0, 0, 10};
  s.camera.lookat = {0, 0, 0};
  return s;
}

// Triangles beside spheres: icospheres (flat and smooth), a grid with its
// shared edges on the octree's split planes, on the rtiow field.
Scene meshes_and_spheres() {
  Scene s = rtiow(200, 0.2f, 6);
  s.materials.push_back({MaterialType::Metal, {0.9f, 0.8f, 0.7f}, 0.05f});
  const uint32_t metal = uint32_t(s.materials.size() - 1);
  test::place(s, test::icosphere(2, 1), glm::translate(glm::mat4(1.0f), glm::vec3(2, 1, 2)));
  test::place(s, test::icosphere(3, metal, true), glm::translate(glm::mat4(1.0f), glm::vec3(-2, 0.8f, 2)));
  test::place(s, test::grid(8, 0), glm::translate(glm::mat4(1.0f), glm::vec3(-4, 0, -3)) *
                                       glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0)));
  return s;
}

// Overlapping spheres: a field denser than its spheres are wide (a
// twentieth of them glass), where each sphere's box in the trees holds only
// the parts of it no opaque sphere covers (OctreeParams::hidden_parts,
// accel/hidden_parts.h), while brute force tests every sphere whole; and a
// sphere wholly inside an opaque one (nothing of it left) beside one wholly
// inside a glass one (seen through the glass).
Scene dense_overlapping() {
  Scene s = rtiow(1500, 0.35f, 8);
  s.materials.push_back({MaterialType::Lambertian, {0.8f, 0.6f, 0.2f}});
  const uint32_t opaque = uint32_t(s.materials.size() - 1);
  s.materials.push_back({MaterialType::Dielectric, glm::vec3(1.0f), 0.0f, 1.5f});
  const uint32_t glass = uint32_t(s.materials.size() - 1);
  s.materials.push_back({MaterialType::Lambertian, {0.9f, 0.1f, 0.1f}});
  const uint32_t red = uint32_t(s.materials.size() - 1);
  s.spheres.push_back({{2.0f, 1.2f, 1.5f}, 0.8f, opaque});
  s.spheres.push_back({{2.1f, 1.2f, 1.5f}, 0.3f, red});
  s.spheres.push_back({{-1.5f, 1.2f, 2.0f}, 0.8f, glass});
  s.spheres.push_back({{-1.4f, 1.2f, 2.0f}, 0.3f, red});
  return s;
}

// The camera inside an opaque sphere, into which the field's spheres and the
// ground reach, with a light: rays start inside it, so it hides nothing
// (sphere_occluders in render/gpu_scene.cpp); were it an occluder, the parts
// of the others inside it would be left out of the trees. Few spheres: on
// lavapipe brute force's loop over the spheres must stay under llvmpipe's
// 65535 iterations an invocation for paths this long (their last bounces'
// shadow rays found nothing with 6,000).
Scene camera_in_an_opaque_sphere() {
  Scene s = rtiow(500, 0.6f, 9);
  s.materials.push_back({MaterialType::Lambertian, {0.8f, 0.6f, 0.2f}});
  s.camera.lookfrom = {3.0f, 0.6f, 2.0f};
  s.camera.lookat = {2.0f, 0.2f, 1.0f};
  s.camera.focus_dist = 1.0f;
  s.camera.vfov = 60.0f;
  s.spheres.push_back({s.camera.lookfrom, 1.5f, uint32_t(s.materials.size() - 1)});
  s.materials.push_back(test::emitter(glm::vec3(6.0f, 5.0f, 4.0f)));  // a light inside with it
  s.spheres.push_back({{2.6f, 1.3f, 1.5f}, 0.15f, uint32_t(s.materials.size() - 1)});
  return s;
}

// Nothing but the sky; one sphere alone (a tree of one leaf).
Scene empty() {
  Scene s = test::furnace_scene();
  s.sky.type = SkyType::Gradient;
  return s;
}
Scene one_sphere() {
  Scene s = empty();
  s.materials = {{MaterialType::Metal, {0.9f, 0.8f, 0.7f}, 0.2f}};
  s.spheres.push_back({{0.2f, -0.1f, 0.0f}, 1.5f, 0});
  return s;
}

// Only triangles, the same mesh placed many times (a mirrored one too).
Scene only_triangles() {
  Scene s = test::furnace_scene();
  s.sky.type = SkyType::Gradient;
  s.materials = {{MaterialType::Lambertian, {0.7f, 0.3f, 0.3f}}, {MaterialType::Dielectric, glm::vec3(0.5f), 0, 1.5f}};
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      test::place(s, test::icosphere(1, uint32_t((i + j) & 1)),
                  glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(float(i), float(j), 0.0f)),
                             glm::vec3(i == 0 ? -0.45f : 0.45f, 0.45f, 0.45f)));
  return s;
}

// One mesh stored once and placed 25 times (one of them mirrored).
Scene instanced() {
  Scene s = only_triangles();
  s.meshes.resize(1);
  for (Instance& inst : s.instances) inst.mesh = 0;
  return s;
}

// The mesh walk's slab test is a multiply-add whose rounding is not relative
// to the distance (accel/octree.glsl, FusedSlabRay): far from the origin its
// margin matters (without it, 0.08% of this scene's BVH values differed from
// brute force at depth 8 on lavapipe).
Scene far_meshes() {
  Scene s = meshes_and_spheres();
  const glm::vec3 far(3e4f, 0.0f, -2e4f);
  for (Sphere& sp : s.spheres) sp.center += far;
  for (Instance& inst : s.instances) inst.transform = glm::translate(glm::mat4(1.0f), far) * inst.transform;
  s.camera.lookfrom += far;
  s.camera.lookat += far;
  return s;
}

// Big lists at both levels, and shadow rays that only a big primitive
// blocks: a mesh whose one large triangle is on its own octree's big list
// (it is more than half the size of the rest, a small grid), the rtiow
// ground sphere on the top level's, a point light above the field and a
// directional light shining up from below the ground (only the ground
// sphere lies between it and every point the camera sees). Every loop over
// a big list is reached: the walks' first leaf, and the callers' loops of
// the other form (RenderSettings::big_list) in closest_hit, test_instance
// and occluded.
Scene big_lists_and_lights() {
  Scene s = rtiow(120, 0.2f, 7);
  Mesh m = test::grid(4, 0);
  for (glm::vec3& p : m.positions) p = 0.25f * p;
  const uint32_t first = uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), {{-1.5f, -0.2f, -0.1f}, {1.5f, -0.2f, -0.1f}, {0.0f, 2.2f, -0.1f}});
  m.indices.insert(m.indices.end(), {first, first + 1, first + 2});
  m.materials.push_back(0);
  test::place(s, m, glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.3f, 0.0f)), 1.5708f, glm::vec3(0, 1, 0)));
  s.lights = {test::point_light({0.0f, 6.0f, 2.0f}, 40.0f), test::directional_light({0.0f, 1.0f, 0.0f}, 3.0f)};
  return s;
}

const AccelCase CASES[] = {
    {"big_lists_and_lights", big_lists_and_lights},
    {"meshes_and_spheres", meshes_and_spheres},
    {"instanced", instanced},
    {"only_triangles", only_triangles},
    {"rtiow_488_r02", [] { return rtiow(488, 0.2f, 1); }},
    {"rtiow_2000_r01", [] { return rtiow(2000, 0.1f, 2); }},
    {"rtiow_8000_r005", [] { return rtiow(8000, 0.05f, 3); }},
    {"rtiow_50_r04", [] { return rtiow(50, 0.4f, 4); }},
    {"split_planes", split_planes},
    {"coincident", coincident},
    {"coincident_many", coincident_many},
    {"emissive_spheres", emissive_spheres},
    {"one_huge_sphere", one_huge_sphere},
    {"dense_overlapping", dense_overlapping},
    {"camera_in_an_opaque_sphere", camera_in_an_opaque_sphere},
    {"camera_inside_root", camera_inside},
    {"camera_outside_root", [] { return rtiow(488, 0.2f, 1); }},
    {"axis_aligned_rays", axis_aligned},
    {"meshes_far_from_the_origin", far_meshes},
    {"empty", empty},
    {"one_sphere", one_sphere},
};

class AccelTest : public test::VulkanTest, public ::testing::WithParamInterface<AccelCase> {};

// Fraction of values that are bit-identical, and the relative difference of
// the image means.
std::pair<double, double> agreement(const RenderResult& a, const RenderResult& b) {
  size_t same = 0;
  double sum_a = 0, sum_b = 0;
  for (size_t i = 0; i < a.mean.rgb.size(); ++i) {
    same += std::memcmp(&a.mean.rgb[i], &b.mean.rgb[i], sizeof(float)) == 0;
    sum_a += a.mean.rgb[i];
    sum_b += b.mean.rgb[i];
  }
  return {double(same) / double(a.mean.rgb.size()), std::abs(sum_a - sum_b) / std::max(sum_b, 1e-30)};
}

// Each tree against one brute-force render per depth; the octree with and
// without octant culling, and with the big list tested by the walks' callers
// for scenes with triangles (the form GPUs take for them; lavapipe's is the
// first leaf: RenderSettings::big_list), and with a split budget of 32
// references per primitive (OctreeParams::max_refs: deeper clipped trees),
// and with the other form of its loop than the device's own
// (RenderSettings::nearest_child: held on a CPU device, pushed on a GPU);
// the BVH binary, four-wide, and in the device's default widths
// (OctreeParams::bvh_width), and binary with the spheres in the other order
// than the device's own (OctreeParams::bvh_sphere_order: the tree's on a
// GPU, the scene's on a CPU device), and binary with the top level's walk
// in while-while form (RenderSettings::bvh_walk; auto takes it for dense
// top levels on a GPU only, which these small scenes are not).
TEST_P(AccelTest, TreeImagesMatchBruteForce) {
  Scene scene = GetParam().make();
  for (uint32_t depth : {8u, 50u}) {
    RenderSettings s;
    s.width = 64;
    s.height = 40;
    s.spp = 2;
    s.bounce_limit = depth;
    s.accel = Accel::Brute;
    RenderResult brute = render(test::shared_context(), scene, s);
    ASSERT_EQ(brute.nonfinite_samples, 0u);
    struct Variant {
      Accel accel;
      bool culling;
      BigList big_list;
      uint32_t bvh_width = 0;
      uint32_t max_refs = 8;
      NearestChild nearest = NearestChild::Auto;
      SphereOrder order = SphereOrder::Auto;
      BvhWalk walk = BvhWalk::Auto;
      SurfaceCells surfaces = SurfaceCells::Auto;
    };
    const NearestChild other_form =
        test::shared_context().info.software ? NearestChild::Pushed : NearestChild::Held;
    const SphereOrder other_order = test::shared_context().info.software ? SphereOrder::Tree : SphereOrder::Scene;
    // The octree's cells over the spheres' surfaces: auto leaves them off for
    // renders this short on every device (log 127), so on is the other way.
    const SurfaceCells other_surfaces = SurfaceCells::On;
    HiddenPartsStats hidden;
    primitive_boxes(scene, HiddenParts::Cull, &hidden);
    for (Variant v : {Variant{Accel::Octree, true, BigList::FirstLeaf}, Variant{Accel::Octree, false, BigList::FirstLeaf},
                      Variant{Accel::Octree, true, BigList::OwnLoop}, Variant{Accel::Octree, true, BigList::FirstLeaf, 0, 32},
                      Variant{Accel::Octree, true, BigList::FirstLeaf, 0, 8, other_form},
                      Variant{Accel::Octree, true, BigList::FirstLeaf, 0, 8, NearestChild::Auto, SphereOrder::Auto,
                              BvhWalk::Auto, other_surfaces},
                      Variant{Accel::Bvh, false, BigList::Auto, 0},
                      Variant{Accel::Bvh, false, BigList::Auto, 2}, Variant{Accel::Bvh, false, BigList::Auto, 4},
                      Variant{Accel::Bvh, false, BigList::Auto, 2, 8, NearestChild::Auto, other_order},
                      Variant{Accel::Bvh, false, BigList::Auto, 2, 8, NearestChild::Auto, SphereOrder::Auto,
                              BvhWalk::WhileWhile}}) {
      if (v.big_list == BigList::OwnLoop && scene.instances.empty()) continue;
      // The octree's cells over the spheres' surfaces: only where the hidden parts clipped boxes.
      if (v.surfaces != SurfaceCells::Auto && hidden.clipped == 0) continue;
      // The BVH's auto widths on a CPU device are all binary (accel/bvh.h): width 2 again.
      if (v.accel == Accel::Bvh && v.bvh_width == 0 && test::shared_context().info.software) continue;
      s.accel = v.accel;
      s.octant_culling = v.culling ? OctantCulling::On : OctantCulling::Off;
      s.big_list = v.big_list;
      s.nearest_child = v.nearest;
      s.octree.leaf_size = 2;  // octree: a deep tree, many cells, many straddling spheres
      s.octree.bvh_width = v.bvh_width;
      s.octree.max_refs = v.max_refs;
      s.octree.bvh_sphere_order = v.order;
      s.bvh_walk = v.walk;
      s.octree.surface_cells = v.surfaces;
      RenderResult tree = render(test::shared_context(), scene, s);
      ASSERT_EQ(tree.nonfinite_samples, 0u);
      auto [identical, mean_diff] = agreement(tree, brute);
      const std::string what = std::string(accel_name(v.accel)) + (v.culling ? " (octant culling)" : "") +
                               (v.big_list == BigList::OwnLoop ? " (big list in its own loop)" : "") +
                               (v.accel == Accel::Bvh ? " (width " + std::to_string(v.bvh_width) + ")" : "") +
                               (v.max_refs != 8 ? " (" + std::to_string(v.max_refs) + " refs per primitive)" : "") +
                               (v.nearest == NearestChild::Held     ? " (nearest child held)"
                                : v.nearest == NearestChild::Pushed ? " (nearest child pushed)"
                                                                    : "") +
                               (v.order != SphereOrder::Auto
                                    ? std::string(" (spheres in the ") + sphere_order_name(v.order) + "'s order)"
                                    : "") +
                               (v.walk == BvhWalk::WhileWhile ? " (top walk while-while)" : "") +
                               (v.surfaces != SurfaceCells::Auto
                                    ? std::string(" (cells over surfaces ") + surface_cells_name(v.surfaces) + ")"
                                    : "") +
                               ", depth " + std::to_string(depth);
      if (depth <= 8) {
        EXPECT_EQ(identical, 1.0) << what << ": only " << identical * 100 << "% bit-identical";
      } else {
        EXPECT_GE(identical, 0.98) << what << ": only " << identical * 100 << "% bit-identical";
        EXPECT_LE(mean_diff, 0.01) << what << ": image means differ by " << mean_diff * 100 << "%";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AccelTest, ::testing::ValuesIn(CASES),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace octrace
