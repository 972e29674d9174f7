// glTF files as a user meets them: the triangles, windings, transforms,
// instances, materials and cameras the file describes, one warning for what is
// skipped, and one line naming the file and the glTF path for what is wrong.
// Small files are written by the tests (gltf_builder.h); the real models are
// Debian's assimp-testmodels (tools/setup.sh installs them).
#include "scene/gltf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "core/errors.h"
#include "scene/gltf_builder.h"
#include "test_util.h"

namespace octrace {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// A folder per test: ctest runs the tests as parallel processes.
std::string tmp(const std::string& name) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(OCTRACE_TEST_TMP) + "/gltf/" + test->test_suite_name() + "." + test->name() + "/" + name;
}

// Loads `b` written as `name` (.gltf or .glb); warnings are collected in `warnings`.
Scene load(const GltfBuilder& b, const std::string& name, GltfOptions opts = {},
           std::vector<std::string>* warnings = nullptr) {
  opts.warn = [&](const std::string& w) {
    if (warnings) warnings->push_back(w);
    else ADD_FAILURE() << "unexpected warning: " << w;
  };
  return load_gltf_scene(b.write(tmp(name)), opts);
}

using test::input_error;

// What loading `b` as `name` says; the file's path is written as PATH.
std::string load_error(const GltfBuilder& b, const std::string& name, GltfOptions opts = {}) {
  std::string message = input_error([&] { load(b, name, opts); });
  const std::string path = tmp(name);
  for (size_t at; (at = message.find(path)) != std::string::npos;) message.replace(at, path.size(), "PATH");
  return message;
}

std::string load_error(const std::string& bytes, const std::string& name) {
  test::write_bytes(tmp(name), bytes);
  std::string message = input_error([&] { load_gltf_scene(tmp(name)); });
  const std::string path = tmp(name);
  for (size_t at; (at = message.find(path)) != std::string::npos;) message.replace(at, path.size(), "PATH");
  return message;
}

using Triangle = std::array<uint32_t, 3>;

// The triangles by vertex index, each rotated to start at its least index
// (the same triangle with the same winding), sorted.
std::vector<Triangle> triangles(const Mesh& m) {
  std::vector<Triangle> out;
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    Triangle t{m.indices[i], m.indices[i + 1], m.indices[i + 2]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance) << "x";
  EXPECT_NEAR(a.y, b.y, tolerance) << "y";
  EXPECT_NEAR(a.z, b.z, tolerance) << "z";
}

// A closed unit cube, every face counter-clockwise seen from outside.
GltfBuilder cube_gltf() {
  GltfBuilder b;
  const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  const int indices = b.add_indices(std::vector<uint8_t>{
      0, 2, 1, 0, 3, 2,  // z = 0, facing -z
      4, 5, 6, 4, 6, 7,  // z = 1, facing +z
      0, 1, 5, 0, 5, 4,  // y = 0
      3, 7, 6, 3, 6, 2,  // y = 1
      0, 4, 7, 0, 7, 3,  // x = 0
      1, 2, 6, 1, 6, 5,  // x = 1
  });
  b.add_mesh(positions, indices);
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  return b;
}

// ---------------------------------------------------------------------------
// geometry
// ---------------------------------------------------------------------------

TEST(Gltf, QuadLoadsAsOneMeshPlacedOnce) {
  const Scene s = load(test::quad_gltf(), "quad.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_EQ(s.instances[0].mesh, 0u);
  EXPECT_EQ(s.instances[0].transform, glm::mat4(1.0f));
  // No material in the file: glTF's default, base colour 1, metallic 1, roughness 1.
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0], test::gltf_default_material());
  EXPECT_EQ(s.materials[0].metallic, 1.0f);
  EXPECT_EQ(s.materials[0].roughness, 1.0f);
  EXPECT_EQ(m.materials, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(s.sky, Sky{});
  EXPECT_TRUE(s.spheres.empty());
}

// KHR_lights_punctual: three lights placed by nodes (the spot's node
// rotated and moved, the sun's node rotated), in photometric units.
GltfBuilder lights_gltf() {
  GltfBuilder b = test::quad_gltf();
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 683.0}},
      {{"type", "spot"}, {"intensity", 1366.0}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 6830.0}}};
  // Rotated -90 degrees about x: the node's -Z (where a light shines) turns to -Y.
  const double h = std::sqrt(0.5);
  b.add("nodes", {{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.add("nodes", {{"translation", {0, 4, 0}}, {"rotation", {-h, 0, 0, h}},
                  {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  b.add("nodes", {{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  b.set_scene({0, 1, 2, 3});
  return b;
}

TEST(Gltf, PunctualLightsArePlacedByTheirNodesIn683thsOfTheirUnits) {
  const Scene s = load(lights_gltf(), "lights.gltf");
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.mesh_file_lights, 3u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_EQ(point.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(point.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(point.intensity, 1.0f);  // 683 cd: 1 W/sr
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_NEAR(glm::distance(spot.position, glm::vec3(0, 4, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(spot.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_EQ(spot.intensity, 2.0f);
  EXPECT_NEAR(spot.inner_cone, 0.25 * 180 / glm::pi<double>(), 1e-4);
  EXPECT_NEAR(spot.outer_cone, 0.5 * 180 / glm::pi<double>(), 1e-4);
  EXPECT_EQ(s.lights[2].type, LightType::Directional);
  EXPECT_NEAR(glm::distance(s.lights[2].direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_EQ(s.lights[2].intensity, 10.0f);  // 6830 lux: 10 W/m^2
}

TEST(Gltf, PunctualLightsFollowAJsonMeshReferenceAndAreNotWrittenBack) {
  const std::string gltf = test::tmp_path("lights_ref.gltf");
  test::write_bytes(gltf, lights_gltf().gltf());
  const Scene s = parse_scene_json(R"({"materials": [], "lights": [{"type": "point", "position": [0, 9, 0]}],
      "meshes": [{"file": ")" + gltf + R"(", "transform": {"translate": [10, 0, 0]}}]})", "scene.json");
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0, 9, 0));
  EXPECT_EQ(s.lights[1].position, glm::vec3(11, 2, 3));
  const std::string json = scene_to_json(s);
  const Scene again = parse_scene_json(json, "scene.json");
  EXPECT_EQ(again.lights, s.lights);
}

TEST(GltfErrors, BadPunctualLights) {
  GltfBuilder b = lights_gltf();
  b.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.5;
  EXPECT_EQ(load_error(b, "l.gltf"),
            "PATH: extensions.KHR_lights_punctual.lights[1].spot.innerConeAngle: must be in [0, outerConeAngle) "
            "radians, got 0.5");
  b = lights_gltf();
  b.doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  EXPECT_EQ(load_error(b, "l.gltf"), "PATH: nodes[1].extensions.KHR_lights_punctual.light: index 7 out of range (3 lights)");
  b = lights_gltf();
  b.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1.0;
  EXPECT_EQ(load_error(b, "l.gltf"),
            "PATH: extensions.KHR_lights_punctual.lights[0].intensity: must be a finite number >= 0, got -1");
}

TEST(Gltf, GlbEqualsGltf) {
  EXPECT_EQ(load(cube_gltf(), "cube.glb").meshes, load(cube_gltf(), "cube.gltf").meshes);
}

// Every edge of the closed cube is used once in each direction (consistent
// windings), and the signed volume is +1 (the windings face outward).
TEST(Gltf, ClosedCubeKeepsItsOutwardWindings) {
  const Mesh m = load(cube_gltf(), "cube.gltf").meshes.at(0);
  ASSERT_EQ(m.triangle_count(), 12u);
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  double volume = 0;
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    for (int k = 0; k < 3; ++k) ++edges[{m.indices[i + k], m.indices[i + (k + 1) % 3]}];
    const glm::dvec3 a(m.positions[m.indices[i]]), b(m.positions[m.indices[i + 1]]), c(m.positions[m.indices[i + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1) << edge.first << "->" << edge.second;
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << "->" << edge.second << " has no twin";
  }
  EXPECT_DOUBLE_EQ(volume, 1.0);
}

// A convex hexagon as a list, a strip and a fan over the same vertices: the
// same triangles, each with the winding of the list (glTF 2.0 spec 3.7.2.1).
TEST(Gltf, StripsAndFansGiveTheTrianglesOfTheList) {
  GltfBuilder b;
  // Around the hexagon counter-clockwise seen from +z.
  const int positions = b.add_vec3({{2, 0, 0}, {1, 1.7f, 0}, {-1, 1.7f, 0}, {-2, 0, 0}, {-1, -1.7f, 0}, {1, -1.7f, 0}});
  const int list = b.add_indices(std::vector<uint8_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5});
  const int fan = b.add_indices(std::vector<uint8_t>{0, 1, 2, 3, 4, 5});
  // A strip zig-zags across the hexagon; the list beside it names the same
  // triangles with the same (counter-clockwise) winding.
  const int strip = b.add_indices(std::vector<uint8_t>{1, 2, 0, 3, 5, 4});
  const int strip_list = b.add_indices(std::vector<uint8_t>{1, 2, 0, 2, 3, 0, 0, 3, 5, 3, 4, 5});
  b.add_mesh(positions, list);
  b.add_mesh(positions, fan, test::kFan);
  b.add_mesh(positions, strip, test::kStrip);
  b.add_mesh(positions, strip_list);
  for (int i = 0; i < 4; ++i) b.add("nodes", {{"mesh", i}});
  b.set_scene({0, 1, 2, 3});
  const Scene s = load(b, "modes.gltf");
  ASSERT_EQ(s.meshes.size(), 4u);
  EXPECT_EQ(triangles(s.meshes[1]), triangles(s.meshes[0]));
  EXPECT_EQ(triangles(s.meshes[2]), triangles(s.meshes[3]));
  // Every triangle faces +z, as the hexagon's vertices run.
  for (const Mesh& m : s.meshes) {
    ASSERT_EQ(m.triangle_count(), 4u) << m.name;
    for (size_t i = 0; i < m.indices.size(); i += 3) {
      const glm::vec3 a = m.positions[m.indices[i]], c = m.positions[m.indices[i + 1]], d = m.positions[m.indices[i + 2]];
      EXPECT_GT(glm::cross(c - a, d - a).z, 0.0f) << m.name << " triangle " << i / 3;
    }
  }
}

TEST(Gltf, NonIndexedStripAndFanUseTheVerticesInOrder) {
  GltfBuilder b;
  const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  b.add_mesh(positions, -1, test::kStrip);
  b.add_mesh(positions, -1, test::kFan);
  b.add_mesh(positions, -1, test::kTriangles);
  json first_three = b.doc["accessors"][0];
  first_three["count"] = 3;
  b.doc["accessors"].push_back(first_three);
  b.doc["meshes"][2]["primitives"][0]["attributes"]["POSITION"] = 1;
  for (int i = 0; i < 3; ++i) b.add("nodes", {{"mesh", i}});
  b.set_scene({0, 1, 2});
  const Scene s = load(b, "nonindexed.gltf");
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(s.meshes[1].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0}));
  EXPECT_EQ(s.meshes[2].indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(Gltf, EightSixteenAndThirtyTwoBitIndicesGiveTheSameMesh) {
  std::vector<Mesh> meshes;
  for (int bits : {8, 16, 32}) {
    GltfBuilder b;
    const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const std::vector<uint32_t> v{0, 1, 2, 0, 2, 3};
    const int indices = bits == 8    ? b.add_indices(std::vector<uint8_t>(v.begin(), v.end()))
                        : bits == 16 ? b.add_indices(std::vector<uint16_t>(v.begin(), v.end()))
                                     : b.add_indices(v);
    b.add_mesh(positions, indices);
    b.add("nodes", {{"mesh", 0}});
    b.set_scene({0});
    meshes.push_back(load(b, "indices" + std::to_string(bits) + ".glb").meshes.at(0));
  }
  EXPECT_EQ(meshes[0], meshes[1]);
  EXPECT_EQ(meshes[0], meshes[2]);
  EXPECT_EQ(meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

// Positions and normals interleaved in one view (byteStride 24) read as the
// same mesh as tightly packed views.
TEST(Gltf, ByteStrideIsHonoured) {
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> n{{0, 0, 1}, {0, 0.6f, 0.8f}, {0.6f, 0, 0.8f}, {0, 0, 1}};
  std::vector<glm::vec3> interleaved;
  for (size_t i = 0; i < p.size(); ++i) interleaved.insert(interleaved.end(), {p[i], n[i]});
  GltfBuilder a;
  const int view = a.add_view(interleaved, 24);
  const int pa = a.add_accessor(view, test::kFloat, 4, "VEC3");
  const int na = a.add_accessor(view, test::kFloat, 4, "VEC3", 12);
  const int ia = a.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  a.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", pa}, {"NORMAL", na}}}, {"indices", ia}}}}});
  a.add("nodes", {{"mesh", 0}});
  a.set_scene({0});

  GltfBuilder b;
  const int pb = b.add_vec3(p), nb = b.add_vec3(n);
  const int ib = b.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  b.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", pb}, {"NORMAL", nb}}}, {"indices", ib}}}}});
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});

  const Mesh strided = load(a, "strided.gltf").meshes.at(0);
  EXPECT_EQ(strided, load(b, "tight.gltf").meshes.at(0));
  EXPECT_EQ(strided.normals, n);
}

// Sparse accessors (3.6.2.3): elements replaced over a bufferView, and over zeros.
TEST(Gltf, SparseAccessorsReplaceTheirElements) {
  for (bool dense : {true, false}) {
    GltfBuilder b;
    const int base = b.add_view(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {9, 9, 9}, {0, 1, 0}});
    const int indices = b.add_view(std::vector<uint16_t>{1, 2});
    const int values = b.add_view(std::vector<glm::vec3>{{5, 0, 0}, {1, 1, 0}});
    const int positions = b.add_accessor(dense ? base : -1, test::kFloat, 4, "VEC3");
    b.doc["accessors"][positions]["sparse"] = {
        {"count", 2},
        {"indices", {{"bufferView", indices}, {"componentType", test::kUnsignedShort}}},
        {"values", {{"bufferView", values}}}};
    b.add_mesh(positions, b.add_indices(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}));
    b.add("nodes", {{"mesh", 0}});
    b.set_scene({0});
    const Mesh m = load(b, "sparse.gltf").meshes.at(0);
    EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {5, 0, 0}, {1, 1, 0}, dense ? glm::vec3(0, 1, 0) : glm::vec3(0)}))
        << (dense ? "over a bufferView" : "over zeros");
  }
}

// TEXCOORD_0 as normalized 16-bit integers (core glTF), POSITION and NORMAL
// as 16-bit and 8-bit integers (KHR_mesh_quantization, which may be required).
TEST(Gltf, NormalizedAndQuantizedAttributes) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  const int positions = b.add_accessor(b.add_view(std::vector<int16_t>{0, 0, 0, 0, 2, 0, 0, 0, -3, 0, 0, 0, 0, 4, 5, 0}, 8),
                                       test::kShort, 3, "VEC3");
  const int normals = b.add_accessor(b.add_view(std::vector<int8_t>{0, 0, 127, 0, 0, 0, -127, 0, 0, 0, -128, 0}, 4),
                                     test::kByte, 3, "VEC3", 0, true);
  const int uvs = b.add_accessor(b.add_view(std::vector<uint16_t>{0, 65535, 32768, 0, 65535, 65535}), test::kUnsignedShort,
                                 3, "VEC2", 0, true);
  b.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", positions}, {"NORMAL", normals}, {"TEXCOORD_0", uvs}}}}}}});
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  const Mesh m = load(b, "quantized.gltf").meshes.at(0);
  EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {2, 0, 0}, {-3, 0, 0}}));
  // -128 maps to -1 as -127 does (max(c / 127, -1), spec 3.11).
  EXPECT_EQ(m.normals, (std::vector<glm::vec3>{{0, 0, 1}, {0, 0, -1}, {0, 0, -1}}));
  EXPECT_EQ(m.uvs, (std::vector<glm::vec2>{{0, 1}, {32768 / 65535.0f, 0}, {1, 1}}));
}

// Normals are kept when every primitive has them; uvs when any has them, the
// others' vertices at uv (0, 0).
TEST(Gltf, NormalsAreKeptWhenEveryPrimitiveHasThemUvsWhenAnyHas) {
  GltfBuilder b;
  const int p = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int n = b.add_vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  const int t = b.add_accessor(b.add_view(std::vector<float>{0, 0, 1, 0, 0, 1}), test::kFloat, 3, "VEC2");
  b.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}, {"NORMAL", n}}}},
                                   {{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}}}}}}});
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  Mesh m = load(b, "partial.gltf").meshes.at(0);
  EXPECT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.uvs, (std::vector<glm::vec2>{{0, 0}, {0, 0}, {0, 0}, {0, 0}, {1, 0}, {0, 1}}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  // Without uvs anywhere, primitives that share their vertex accessors share the vertices.
  b.doc["meshes"][0]["primitives"][1]["attributes"].erase("TEXCOORD_0");
  m = load(b, "shared.gltf").meshes.at(0);
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 1, 2}));
}

TEST(Gltf, PrimitivesConcatenateWithAMaterialPerTriangle) {
  GltfBuilder b;
  b.add("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.2, 0.1, 1.0}}}}});
  b.add("materials", json::object());  // no pbrMetallicRoughness: base colour 1
  const int p0 = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const int p1 = b.add_vec3({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}});
  const int i1 = b.add_indices(std::vector<uint8_t>{0, 1, 2, 1, 3, 2});
  b.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", p0}}}, {"material", 1}},
                                   {{"attributes", {{"POSITION", p1}}}, {"indices", i1}},
                                   {{"attributes", {{"POSITION", p0}}}, {"material", 0}}}}});
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  std::vector<std::string> warnings;
  const Scene s = load(b, "materials.gltf", {}, &warnings);
  // Nothing the materials have goes unrendered: no warning.
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(s.materials.size(), 3u);  // the file's two, then glTF's default for the primitive without
  EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.8f, 0.2f, 0.1f));
  EXPECT_EQ(s.materials[1].albedo, glm::vec3(1.0f));
  EXPECT_EQ(s.materials[2], test::gltf_default_material());
  const Mesh& m = s.meshes.at(0);
  EXPECT_EQ(m.positions.size(), 7u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 4, 6, 5, 0, 1, 2}));
  EXPECT_EQ(m.materials, (std::vector<uint32_t>{1, 2, 2, 0}));
  EXPECT_EQ(s.mesh_file_materials, 3u);
}

TEST(Gltf, PointsAndLinesAreSkippedWithOneWarningPerMesh) {
  GltfBuilder b;
  const int p = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  b.add("meshes", {{"name", "Wires"},
                   {"primitives", {{{"attributes", {{"POSITION", p}}}, {"mode", test::kPoints}},
                                   {{"attributes", {{"POSITION", p}}}, {"mode", test::kLines}},
                                   {{"attributes", {{"POSITION", p}}}, {"mode", test::kPoints}},
                                   {{"attributes", {{"POSITION", p}}}, {"mode", test::kStrip}}}}});
  b.add_mesh(p, -1, test::kPoints);
  b.add("nodes", {{"mesh", 0}});
  b.add("nodes", {{"mesh", 1}});
  b.set_scene({0, 1});
  std::vector<std::string> warnings;
  const Scene s = load(b, "points.gltf", {}, &warnings);
  const std::string path = tmp("points.gltf");
  EXPECT_EQ(warnings, (std::vector<std::string>{
                          path + ": meshes[0] \"Wires\": skipped 3 primitives (POINTS, LINES): only triangles are rendered",
                          path + ": meshes[1]: skipped 1 primitive (POINTS): only triangles are rendered"}));
  // The strip stays; the mesh of points alone is neither stored nor placed.
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangle_count(), 2u);
  EXPECT_EQ(s.instances.size(), 1u);
}

// ---------------------------------------------------------------------------
// nodes and instances
// ---------------------------------------------------------------------------

// Parent TRS (translate (1, 2, 3), rotate 90 degrees about z, scale 2) over a
// child matrix (translate (1, 0, 0)): points land where the spec's order puts them.
TEST(Gltf, NodeHierarchyComposesParentTimesChild) {
  GltfBuilder b = test::quad_gltf();
  const double h = std::sqrt(0.5);
  b.doc["nodes"] = json::array();
  b.add("nodes", {{"children", {1}}, {"translation", {1, 2, 3}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}});
  b.add("nodes", {{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1}}});
  const Scene s = load(b, "hierarchy.gltf");
  ASSERT_EQ(s.instances.size(), 1u);
  const glm::mat4& t = s.instances[0].transform;
  // (0,0,0) -> child (1,0,0) -> scale (2,0,0) -> rotate (0,2,0) -> translate (1,4,3).
  expect_near(apply(t, {0, 0, 0}), {1, 4, 3});
  // (0,1,0) -> (1,1,0) -> (2,2,0) -> (-2,2,0) -> (-1,4,3).
  expect_near(apply(t, {0, 1, 0}), {-1, 4, 3});
}

// The same placement given by the file's node and by the JSON scene's
// "transform" (scale, then rotate, then translate; or a matrix).
TEST(Gltf, NodeTransformEqualsTheSameTransformGivenInJson) {
  const double half = glm::radians(35.0) / 2;
  GltfBuilder placed = test::quad_gltf();
  placed.doc["nodes"][0]["scale"] = {1.5, 1.5, 1.5};
  placed.doc["nodes"][0]["rotation"] = {0, std::sin(half), 0, std::cos(half)};
  placed.doc["nodes"][0]["translation"] = {0.3, 0, -0.2};
  const glm::mat4 from_node = load(placed, "placed.gltf").instances.at(0).transform;

  test::quad_gltf().write(tmp("json/quad.glb"));
  const auto from_json = [](const std::string& transform) {
    const std::string scene = R"({"materials": [], "meshes": [{"file": "quad.glb", "transform": )" + transform + "}]}";
    return parse_scene_json(scene, tmp("json/scene.json")).instances.at(0).transform;
  };
  const glm::mat4 trs = from_json(R"({"scale": 1.5, "rotate": [0, 1, 0, 35], "translate": [0.3, 0, -0.2]})");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(trs[c][r], from_node[c][r], 1e-6) << c << "," << r;

  GltfBuilder by_matrix = test::quad_gltf();
  by_matrix.doc["nodes"][0]["matrix"] = json::array();
  for (int i = 0; i < 16; ++i) by_matrix.doc["nodes"][0]["matrix"].push_back(from_node[i / 4][i % 4]);
  EXPECT_EQ(from_json(R"({"matrix": )" + by_matrix.doc["nodes"][0]["matrix"].dump() + "}"),
            load(by_matrix, "matrix.gltf").instances.at(0).transform);
}

TEST(Gltf, AMeshPlacedByTwoNodesIsStoredOnce) {
  GltfBuilder b = test::quad_gltf();
  b.add("nodes", {{"mesh", 0}, {"translation", {5, 0, 0}}});
  b.set_scene({0, 1});
  const Scene s = load(b, "twice.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].mesh, 0u);
  EXPECT_EQ(s.instances[1].mesh, 0u);
  expect_near(apply(s.instances[1].transform, {0, 0, 0}), {5, 0, 0});
  EXPECT_EQ(unique_triangle_count(s), 2u);
  EXPECT_EQ(instanced_triangle_count(s), 4u);
}

// A mirror keeps the file's windings: the renderer flips the front face of an
// instance whose transform has a negative determinant.
TEST(Gltf, ANegativeScaleIsKeptAsAMirroredInstance) {
  GltfBuilder b = test::quad_gltf();
  b.doc["nodes"][0]["scale"] = {-1, 1, 1};
  const Scene s = load(b, "mirror.gltf");
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_LT(glm::determinant(s.instances[0].transform), 0.0f);
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(Gltf, TheSceneOptionChoosesWhichScene) {
  GltfBuilder b = test::quad_gltf();
  b.add("nodes", {{"mesh", 0}, {"translation", {0, 7, 0}}});
  b.doc["scenes"].push_back({{"nodes", {0, 1}}});
  EXPECT_EQ(load(b, "scenes.gltf").instances.size(), 1u);
  GltfOptions second;
  second.scene = 1;
  const Scene s = load(b, "scenes.gltf", second);
  EXPECT_EQ(s.instances.size(), 2u);
  ASSERT_EQ(s.mesh_refs.size(), 1u);
  EXPECT_EQ(s.mesh_refs[0].scene, 1u);
  EXPECT_EQ(s.mesh_refs[0].file, tmp("scenes.gltf"));
  second.scene = 2;
  EXPECT_EQ(load_error(b, "scenes.gltf", second), "gltf.scene: index 2 out of range (PATH has 2 scenes)");
}

// ---------------------------------------------------------------------------
// cameras
// ---------------------------------------------------------------------------

// cameras[0] orthographic, [1] perspective at (0, 0, 5) looking down -z,
// [2] perspective turned 90 degrees about y (looking down -x), [3] unplaced.
GltfBuilder cameras_gltf() {
  GltfBuilder b = test::quad_gltf();
  b.add("cameras", {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}});
  b.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}});
  b.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}});
  b.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}});
  const double h = std::sqrt(0.5);
  b.add("nodes", {{"camera", 0}});
  b.add("nodes", {{"camera", 2}, {"rotation", {0, h, 0, h}}, {"translation", {3, 0, 0}}});
  b.add("nodes", {{"camera", 1}, {"translation", {0, 0, 5}}});
  b.set_scene({0, 1, 2, 3});
  return b;
}

TEST(Gltf, TheFirstPerspectiveCameraIsUsed) {
  const Camera c = load(cameras_gltf(), "cameras.gltf").camera;
  expect_near(c.lookfrom, {0, 0, 5});
  expect_near(glm::normalize(c.lookat - c.lookfrom), {0, 0, -1});
  expect_near(c.vup, {0, 1, 0});
  EXPECT_FLOAT_EQ(c.vfov, float(glm::degrees(0.5)));
  EXPECT_EQ(c.aperture, 0.0f);
}

TEST(Gltf, TheCameraOptionChoosesACamera) {
  GltfOptions opts;
  opts.camera = 2;
  const Camera c = load(cameras_gltf(), "cameras.gltf", opts).camera;
  expect_near(c.lookfrom, {3, 0, 0});
  expect_near(glm::normalize(c.lookat - c.lookfrom), {-1, 0, 0});
  EXPECT_FLOAT_EQ(c.vfov, float(glm::degrees(1.0)));

  opts.camera = 0;
  EXPECT_EQ(load_error(cameras_gltf(), "cameras.gltf", opts),
            "gltf.camera: cameras[0] of PATH is orthographic: only perspective cameras are supported");
  opts.camera = 3;
  EXPECT_EQ(load_error(cameras_gltf(), "cameras.gltf", opts),
            "gltf.camera: cameras[3] of PATH is not placed by a node of scenes[0]");
  opts.camera = 4;
  EXPECT_EQ(load_error(cameras_gltf(), "cameras.gltf", opts), "gltf.camera: index 4 out of range (PATH has 4 cameras)");
  opts.camera = 0;
  EXPECT_EQ(load_error(test::quad_gltf(), "quad.gltf", opts), "gltf.camera: index 0 out of range (PATH has 0 cameras)");
}

// Without a camera: look at the centre of the bounds from rtiow's direction,
// the bounding sphere filling the 30 degree vertical field of view.
TEST(Gltf, AFramingCameraWhenTheFileHasNone) {
  GltfBuilder b = test::quad_gltf();
  b.doc["nodes"][0]["scale"] = {4, 2, 1};
  b.doc["nodes"][0]["translation"] = {10, 0, -3};
  const Camera c = load(b, "framed.gltf").camera;
  const glm::vec3 centre(12, 1, -3);
  const double radius = 0.5 * std::sqrt(4.0 * 4.0 + 2.0 * 2.0);
  expect_near(c.lookat, centre);
  expect_near(glm::normalize(c.lookfrom - c.lookat), glm::normalize(glm::vec3(13, 2, 3)));
  EXPECT_NEAR(glm::length(c.lookfrom - c.lookat), radius / std::sin(glm::radians(15.0)), 1e-4);
  EXPECT_EQ(c.vfov, 30.0f);
  EXPECT_EQ(c.aperture, 0.0f);
  EXPECT_EQ(c.vup, glm::vec3(0, 1, 0));
}

// ---------------------------------------------------------------------------
// textures and emission
// ---------------------------------------------------------------------------

// Two texels, rows from the top: opaque red, then a blue-green of alpha 7.
const std::vector<uint8_t> kTwoTexels = {255, 0, 0, 255, 0, 128, 255, 7};

// A texture is its image decoded to RGBA8 with its sampler's wrap modes, stored
// once however many materials use it; textures no material uses are not stored.
TEST(Gltf, TexturesAreDecodedWithTheirWrapModesAndStoredOnce) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels), test::kClampToEdge, test::kMirroredRepeat);
  b.add("textures", {{"source", 0}});  // no sampler: REPEAT both ways
  b.add("textures", {{"source", 0}});  // used by no material
  const auto pbr = [](int texture) {
    return json{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}}}};
  };
  b.add("materials", pbr(0));  // shares texture 0 with material 0
  json emissive = pbr(1);
  emissive["emissiveFactor"] = {1, 1, 1};
  emissive["emissiveTexture"] = {{"index", 0}};
  b.add("materials", emissive);
  const Scene s = load(b, "textures.gltf");
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_EQ(s.textures[0], (Texture{2, 1, {0xff0000ffu, 0x07ff8000u}, Wrap::ClampToEdge, Wrap::MirroredRepeat}));
  EXPECT_EQ(s.textures[1], (Texture{2, 1, {0xff0000ffu, 0x07ff8000u}, Wrap::Repeat, Wrap::Repeat}));
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.materials[0].base_color_texture, 0u);
  EXPECT_EQ(s.materials[1].base_color_texture, 0u);
  EXPECT_EQ(s.materials[2].base_color_texture, 1u);
  EXPECT_EQ(s.materials[2].emission_texture, 0u);
  EXPECT_EQ(s.materials[0].emission_texture, std::nullopt);
  EXPECT_EQ(s.meshes.at(0).uvs, (std::vector<glm::vec2>{{0, 1}, {1, 1}, {1, 0}, {0, 0}}));
  // The .glb (the image in a data URI all the same) gives the same scene.
  EXPECT_EQ(load(b, "textures.glb").textures, s.textures);
}

// Emission = emissiveFactor x KHR_materials_emissive_strength, an extension a
// file may require; an emissive texture times a zero emission is not stored.
TEST(Gltf, EmissionIsTheFactorTimesTheStrength) {
  GltfBuilder b = test::quad_gltf();
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  const int texture = b.add_texture(test::png(2, 1, kTwoTexels));
  b.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}},
                      {"emissiveFactor", {1, 0.5, 0.25}},
                      {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}}}});
  b.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}, {"emissiveTexture", {{"index", texture}}}});
  const Scene s = load(b, "emission.gltf");
  ASSERT_EQ(s.materials.size(), 3u);  // and glTF's default, which the quad takes
  EXPECT_EQ(s.materials[0].emission, glm::vec3(4, 2, 1));
  EXPECT_EQ(s.materials[0].type, MaterialType::Pbr);
  EXPECT_EQ(s.materials[1].emission, glm::vec3(0));
  EXPECT_EQ(s.materials[1].emission_texture, std::nullopt);
  EXPECT_TRUE(s.textures.empty());
}

// A scene's material that replaces the file's takes their textures with them,
// and their warning.
TEST(Gltf, AMaterialOverrideLeavesTheFilesTexturesOut) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  b.doc["materials"][0]["pbrMetallicRoughness"].erase("metallicFactor");
  Scene s;
  s.materials = {test::lambertian(0.5f)};
  GltfOptions opts;
  opts.warn = [](const std::string& w) { ADD_FAILURE() << "unexpected warning: " << w; };
  append_gltf(s, b.write(tmp("quad.glb")), 0u, glm::mat4(1.0f), opts);
  EXPECT_TRUE(s.textures.empty());
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.meshes.at(0).materials, (std::vector<uint32_t>{0, 0}));
}

// metallicFactor, roughnessFactor, the metallic-roughness texture (stored
// once, shared with the base colour slot when the file shares it) and
// KHR_materials_ior's ior.
TEST(Gltf, MetallicRoughnessFactorsTextureAndIor) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  b.doc["extensionsUsed"] = {"KHR_materials_ior"};
  const int mr = b.add_texture(test::png(1, 1, {0, 255, 128, 255}));
  nlohmann::json& m = b.doc["materials"][0];
  m["pbrMetallicRoughness"]["metallicFactor"] = 0.5;
  m["pbrMetallicRoughness"]["roughnessFactor"] = 0.25;
  m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", mr}};
  m["extensions"] = {{"KHR_materials_ior", {{"ior", 1.33}}}};
  const Scene s = load(b, "metal_rough.gltf");
  const Material& got = s.materials.at(0);
  EXPECT_EQ(got.type, MaterialType::Pbr);
  EXPECT_EQ(got.metallic, 0.5f);
  EXPECT_EQ(got.roughness, 0.25f);
  EXPECT_EQ(got.ior, 1.33f);
  EXPECT_EQ(got.base_color_texture, 0u);
  ASSERT_EQ(got.metallic_roughness_texture, 1u);
  // Linear data, stored as the file has it: r | g << 8 | b << 16 | a << 24.
  EXPECT_EQ(s.textures.at(1).texels, std::vector<uint32_t>{0xff80ff00u});
}

TEST(GltfErrors, MetallicRoughnessAndIorOutOfRange) {
  GltfBuilder b = test::quad_gltf();
  b.add("materials", {{"pbrMetallicRoughness", {{"roughnessFactor", 1.5}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_EQ(load_error(b, "rough.gltf"),
            "PATH: materials[0].pbrMetallicRoughness.roughnessFactor: must be a number in [0, 1], got 1.5");
  b.doc["materials"][0] = {{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}};
  EXPECT_EQ(load_error(b, "ior.gltf"),
            "PATH: materials[0].extensions.KHR_materials_ior.ior: must be a finite number >= 1, got 0.5");
}

// KHR_materials_transmission's factor; without KHR_materials_volume the
// surface is thin-walled, with thickness > 0 a closed solid whose back faces
// are hit whatever doubleSided says (a ray leaves the solid through them).
TEST(Gltf, TransmissionThinWalledOrSolid) {
  GltfBuilder b = test::quad_gltf();
  b.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
  b.add("materials", {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.75}}}}}});
  b.add("materials", {{"extensions",
                       {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                        {"KHR_materials_volume", {{"thicknessFactor", 0.1}}}}}});
  b.add("materials", {{"extensions", {{"KHR_materials_volume", {{"thicknessFactor", 0}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  std::vector<std::string> warnings;
  const Scene s = load(b, "glass.gltf", {}, &warnings);
  EXPECT_EQ(warnings, std::vector<std::string>{});
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.materials[0].transmission, 0.75f);
  EXPECT_TRUE(s.materials[0].thin_walled);
  EXPECT_FALSE(s.materials[0].double_sided);
  EXPECT_EQ(s.materials[1].transmission, 1.0f);
  EXPECT_FALSE(s.materials[1].thin_walled);
  EXPECT_TRUE(s.materials[1].double_sided);
  EXPECT_EQ(s.materials[2].transmission, 0.0f);
  EXPECT_TRUE(s.materials[2].thin_walled);
  EXPECT_FALSE(s.materials[2].double_sided);
}

// The volume's attenuation and the transmission texture (with its uv
// transform) are read, without a warning; the thickness only says "solid".
// A transmission texture under a factor of 0 is not stored.
TEST(Gltf, VolumeAttenuationAndTransmissionTextureAreRead) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  json texture = {{"index", 0}};
  texture["extensions"]["KHR_texture_transform"]["offset"] = {0.5, 0.25};
  json& extensions = b.doc["materials"][0]["extensions"];
  extensions["KHR_materials_transmission"] = {{"transmissionFactor", 0.75}, {"transmissionTexture", texture}};
  extensions["KHR_materials_volume"] = {
      {"thicknessFactor", 0.01}, {"attenuationColor", {1, 0.5, 0.25}}, {"attenuationDistance", 2}};
  const Scene s = load(b, "tinted.gltf");
  const Material& m = s.materials.at(0);
  EXPECT_EQ(m.transmission, 0.75f);
  EXPECT_FALSE(m.thin_walled);
  EXPECT_EQ(m.transmission_texture, 0u);
  EXPECT_EQ(m.transmission_uv, glm::mat3x2(glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0.5f, 0.25f)));
  EXPECT_EQ(m.attenuation_color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(m.attenuation_distance, 2.0f);
  // sigma = -ln(colour) / distance.
  const glm::vec3 sigma = absorption_coefficient(m);
  EXPECT_EQ(sigma.x, 0.0f);
  EXPECT_FLOAT_EQ(sigma.y, float(std::log(2.0) / 2.0));
  EXPECT_FLOAT_EQ(sigma.z, float(std::log(4.0) / 2.0));
  b.doc["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 0;
  EXPECT_FALSE(load(b, "clear.gltf").materials.at(0).transmission_texture.has_value());
  // Without a distance nothing is absorbed (glTF's default is +infinity).
  b.doc["materials"][0]["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 1;
  b.doc["materials"][0]["extensions"]["KHR_materials_volume"].erase("attenuationDistance");
  EXPECT_EQ(absorption_coefficient(load(b, "forever.gltf").materials.at(0)), glm::vec3(0.0f));
}

TEST(GltfErrors, TransmissionAndThicknessOutOfRange) {
  GltfBuilder b = test::quad_gltf();
  b.add("materials", {{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_EQ(load_error(b, "transmission.gltf"),
            "PATH: materials[0].extensions.KHR_materials_transmission.transmissionFactor: must be a number in [0, 1], "
            "got 1.5");
  b.doc["materials"][0] = {{"extensions", {{"KHR_materials_volume", {{"thicknessFactor", -1}}}}}};
  EXPECT_EQ(load_error(b, "thickness.gltf"),
            "PATH: materials[0].extensions.KHR_materials_volume.thicknessFactor: must be a finite number >= 0, got -1");
  b.doc["materials"][0] = {{"extensions", {{"KHR_materials_volume", {{"attenuationColor", {0.5, 1.5, 0}}}}}}};
  EXPECT_EQ(load_error(b, "colour.gltf"),
            "PATH: materials[0].extensions.KHR_materials_volume.attenuationColor: must be 3 numbers in [0, 1], got "
            "[0.5, 1.5, 0]");
  b.doc["materials"][0] = {{"extensions", {{"KHR_materials_volume", {{"attenuationColor", {0.5, -0.1, 0}}}}}}};
  EXPECT_EQ(load_error(b, "negative.gltf"),
            "PATH: materials[0].extensions.KHR_materials_volume.attenuationColor: must be 3 numbers in [0, 1], got "
            "[0.5, -0.1, 0]");
  for (const char* d : {"0", "-2", "1e300"}) {
    b.doc["materials"][0] = {{"extensions", {{"KHR_materials_volume", {{"attenuationDistance", json::parse(d)}}}}}};
    EXPECT_EQ(load_error(b, "distance.gltf"),
              std::string("PATH: materials[0].extensions.KHR_materials_volume.attenuationDistance: must be a finite "
                          "number > 0 (leave it out for no absorption), got ") +
                  (d[0] == '1' ? "inf" : d));
  }
  b.doc["materials"][0] = json::object();
  b.doc["materials"][0]["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1},
                                                                       {"transmissionTexture", {{"index", 3}}}};
  EXPECT_EQ(load_error(b, "texture.gltf"),
            "PATH: materials[0].extensions.KHR_materials_transmission.transmissionTexture.index: index 3 out of range "
            "(0 textures)");
}

// alphaMode, alphaCutoff (default 0.5), baseColorFactor's alpha and doubleSided.
TEST(Gltf, AlphaModeCutoffAndDoubleSided) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  b.add("materials", {{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"doubleSided", true}});
  b.add("materials", {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.3}}}}});
  b.add("materials", {{"alphaMode", "MASK"}});
  const Scene s = load(b, "alpha.gltf");
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_EQ(s.materials[0].alpha_mode, AlphaMode::Opaque);
  EXPECT_EQ(s.materials[0].alpha, 1.0f);
  EXPECT_FALSE(s.materials[0].double_sided);
  EXPECT_EQ(s.materials[1].alpha_mode, AlphaMode::Mask);
  EXPECT_EQ(s.materials[1].alpha_cutoff, 0.25f);
  EXPECT_TRUE(s.materials[1].double_sided);
  EXPECT_EQ(s.materials[2].alpha_mode, AlphaMode::Blend);
  EXPECT_EQ(s.materials[2].alpha, 0.3f);
  EXPECT_EQ(s.materials[3].alpha_mode, AlphaMode::Mask);
  EXPECT_EQ(s.materials[3].alpha_cutoff, 0.5f);
  // glTF's default material (a primitive without one) is single-sided.
  EXPECT_FALSE(load(test::quad_gltf(), "no_material.gltf").materials.at(0).double_sided);
}

TEST(GltfErrors, BadAlphaCutoffAndMode) {
  GltfBuilder b = test::quad_gltf();
  b.add("materials", {{"alphaMode", "MASK"}, {"alphaCutoff", -0.5}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_EQ(load_error(b, "cutoff.gltf"), "PATH: materials[0].alphaCutoff: must be a finite number >= 0, got -0.5");
  b.doc["materials"][0] = {{"alphaMode", "CUTOUT"}};
  EXPECT_EQ(load_error(b, "mode.gltf"),
            "PATH: materials[0].alphaMode: must be \"OPAQUE\", \"MASK\" or \"BLEND\", got \"CUTOUT\"");
}

// The textured quad with vertex normals and a TANGENT of `tangents`
// (accessor 4, VEC4 unless `type` says otherwise), its material normal-mapped or not.
GltfBuilder tangent_quad(const std::vector<glm::vec4>& tangents, bool normal_mapped, const char* type = "VEC4") {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  json& attributes = b.doc["meshes"][0]["primitives"][0]["attributes"];
  attributes["NORMAL"] = b.add_vec3(std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
  attributes["TANGENT"] = b.add_accessor(b.add_view(tangents), test::kFloat,
                                         std::string(type) == "VEC3" ? tangents.size() * 4 / 3 : tangents.size(), type);
  if (normal_mapped) b.doc["materials"][0]["normalTexture"] = {{"index", 0}};
  return b;
}

// TANGENT (3.7.2.1) is kept where a normal map uses it, exactly as the file
// has it; elsewhere it costs no memory. Either way a bad one is refused.
TEST(Gltf, TangentsAreKeptUnderNormalMapsAndChecked) {
  const std::vector<glm::vec4> good = {{1, 0, 0, 1}, {0, 1, 0, -1}, {0, 0, 1, 1}, {0.6f, 0.8f, 0, -1}};
  EXPECT_EQ(load(tangent_quad(good, true), "mapped.gltf").meshes.at(0).tangents, good);
  EXPECT_TRUE(load(tangent_quad(good, false), "unmapped.gltf").meshes.at(0).tangents.empty());
  for (bool mapped : {true, false}) {
    std::vector<glm::vec4> half_w = good;
    half_w[2].w = 0.5f;
    EXPECT_EQ(load_error(tangent_quad(half_w, mapped), "w.gltf"),
              "PATH: meshes[0].primitives[0].attributes.TANGENT: accessors[4][2]: w (the handedness) must be 1 or -1, "
              "got 0.5");
    std::vector<glm::vec4> not_finite = good;
    not_finite[1].x = INFINITY;
    EXPECT_EQ(load_error(tangent_quad(not_finite, mapped), "inf.gltf"),
              "PATH: accessors[4][1]: must be 4 finite numbers, got [inf, 1, 0, -1]");
    EXPECT_EQ(load_error(tangent_quad({good[0], good[1], good[2]}, mapped), "count.gltf"),
              "PATH: meshes[0].primitives[0].attributes.TANGENT: accessors[4] has 3 elements, POSITION 4");
    EXPECT_EQ(load_error(tangent_quad(good, mapped, "VEC3"), "vec3.gltf"),
              "PATH: accessors[4]: TANGENT must be VEC4, got VEC3");
  }
}

// What is not rendered yet is named in one warning per file.
TEST(Gltf, WhatMaterialsLackIsNamedInOneWarning) {
  GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_texture_transform", "KHR_materials_emissive_strength"};
  // KHR_texture_transform is rendered, but not its texCoord override to another set.
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"texCoord", 1}}}};
  b.add("materials", json::object());  // metallicFactor 1 by default
  b.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}, {"normalTexture", {{"index", 0}}},
                      {"alphaMode", "BLEND"}});
  b.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}, {"alphaMode", "MASK"}});
  std::vector<std::string> warnings;
  load(b, "lacks.gltf", {}, &warnings);
  EXPECT_EQ(warnings, std::vector<std::string>{tmp("lacks.gltf") +
                                               ": materials render without what octrace does not support yet: "
                                               "texture coordinate sets other than 0, "
                                               "KHR_materials_clearcoat"});
}

// ---------------------------------------------------------------------------
// bad input: one line naming the file and the glTF path
// ---------------------------------------------------------------------------

TEST(GltfErrors, MissingFile) {
  EXPECT_EQ(input_error([] { load_gltf_scene(tmp("none.glb")); }),
            tmp("none.glb") + ": cannot open file: No such file or directory");
}

TEST(GltfErrors, TruncatedOrCorruptGlb) {
  const std::string glb = cube_gltf().glb();
  EXPECT_EQ(load_error(glb.substr(0, glb.size() - 10), "truncated.glb"),
            "PATH: the GLB header gives a length of " + std::to_string(glb.size()) + " bytes, the file has " +
                std::to_string(glb.size() - 10) + " (truncated or corrupt)");
  EXPECT_EQ(load_error("hello", "short.glb"), "PATH: not a glTF binary: 5 bytes, less than a GLB header (20)");
  EXPECT_EQ(load_error(std::string(40, 'x'), "magic.glb"), "PATH: not a glTF binary (no \"glTF\" magic at the start)");
  std::string bad_json = glb;
  bad_json[20] = '#';
  EXPECT_EQ(load_error(bad_json, "badjson.glb").rfind("PATH: GLB JSON chunk: invalid JSON at line 1, column 1: ", 0), 0u)
      << load_error(bad_json, "badjson.glb");
}

// Every prefix of a .glb and of a .gltf, and bytes flipped at random: an
// InputError or a scene, never a crash or another exception.
TEST(GltfErrors, DamagedFilesNeverCrash) {
  GltfBuilder b = cube_gltf();
  b.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}});
  b.add("nodes", {{"camera", 0}, {"translation", {0, 0, 5}}});
  b.set_scene({0, 1});
  std::mt19937 rng(7);
  for (const std::string& path : {tmp("damaged.glb"), tmp("damaged.gltf")}) {
    const std::string file = path.back() == 'b' ? b.glb() : b.gltf();
    for (size_t n = 0; n < file.size(); ++n) {
      test::write_bytes(path, file.substr(0, n));
      EXPECT_THROW(load_gltf_scene(path), InputError) << n << " bytes";
    }
    for (int trial = 0; trial < 300; ++trial) {
      std::string damaged = file;
      for (int k = 0; k < 3; ++k) damaged[rng() % damaged.size()] = char(rng());
      test::write_bytes(path, damaged);
      try {
        GltfOptions quiet;
        quiet.warn = nullptr;
        load_gltf_scene(path, quiet);
      } catch (const InputError&) {
      }
    }
  }
}

TEST(GltfErrors, NotJson) {
  const std::string message = load_error("not json", "text.gltf");
  EXPECT_EQ(message.rfind("PATH: invalid JSON at line 1, column 2: ", 0), 0u) << message;
}

// tinygltf reads a document's values recursively: extras nested twenty
// thousand levels deep overflowed its stack. Refused while octrace parses
// the file first, past 512 levels, in a .gltf and in a .glb's JSON chunk
// (600 here: the builder's own dump() recurses too).
TEST(GltfErrors, DeepNestingIsRefusedNotACrash) {
  GltfBuilder b = test::quad_gltf();
  nlohmann::json deep = nlohmann::json::array();
  for (int i = 0; i < 600; ++i) deep = nlohmann::json::array({std::move(deep)});
  b.doc["extras"] = std::move(deep);
  EXPECT_EQ(load_error(b, "deep.gltf"), "PATH: nested deeper than 512 levels");
  EXPECT_EQ(load_error(b, "deep.glb"), "PATH: GLB JSON chunk: nested deeper than 512 levels");
  nlohmann::json shallow = nlohmann::json::array();
  for (int i = 0; i < 400; ++i) shallow = nlohmann::json::array({std::move(shallow)});
  b.doc["extras"] = std::move(shallow);
  EXPECT_NO_THROW(load(b, "shallow.gltf"));
}

TEST(GltfErrors, MissingBinAndImage) {
  GltfBuilder b = test::quad_gltf();
  std::filesystem::remove(tmp("external/quad.bin"));  // written by an earlier run
  test::write_bytes(tmp("external/quad.gltf"), b.with_buffer("quad.bin").dump());
  EXPECT_EQ(input_error([] { load_gltf_scene(tmp("external/quad.gltf")); }),
            tmp("external/quad.gltf") + ": buffers[0].uri: cannot open " + tmp("external/quad.bin") +
                ": No such file or directory");
  // With the .bin beside it, it loads.
  test::write_bytes(tmp("external/quad.bin"), std::string(b.bin.begin(), b.bin.end()));
  EXPECT_EQ(load_gltf_scene(tmp("external/quad.gltf")).meshes, load(b, "quad.gltf").meshes);

  b.add("images", {{"uri", "missing.png"}});
  EXPECT_EQ(load_error(b, "image.gltf"), "PATH: images[0].uri: cannot open " + tmp("missing.png") +
                                             ": No such file or directory");

  // A folder where the .bin should be (tinygltf said "File not found").
  std::filesystem::create_directories(tmp("folder/quad.bin"));
  test::write_bytes(tmp("folder/quad.gltf"), test::quad_gltf().with_buffer("quad.bin").dump());
  EXPECT_EQ(input_error([] { load_gltf_scene(tmp("folder/quad.gltf")); }),
            tmp("folder/quad.gltf") + ": buffers[0].uri: " + tmp("folder/quad.bin") + " is a folder, not a file");
}

// Found by tests/fuzz/fuzz_gltf.cpp: tinygltf hands an image's bufferView to
// the decoder without checking that the view lies inside its buffer, and
// stb_image read past the end of it.
TEST(GltfErrors, AnImageInABufferViewPastItsBuffer) {
  for (const char* name : {"view.glb", "view.gltf"}) {
    GltfBuilder b = test::quad_gltf();
    const int view = b.add("bufferViews", {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 100000}});
    b.add("images", {{"bufferView", view}, {"mimeType", "image/png"}});
    EXPECT_EQ(load_error(b, name), "PATH: bufferViews[2]: byteOffset 40 + byteLength 100000 exceeds buffers[0] (60 bytes)")
        << name;
  }
  // The fuzzer's input, kept in the corpus.
  const std::string corpus = std::string(OCTRACE_SOURCE_DIR) + "/tests/fuzz/corpus/gltf/";
  EXPECT_EQ(input_error([&] { load_gltf_scene(corpus + "regression_image_view_past_buffer.glb"); }),
            corpus + "regression_image_view_past_buffer.glb: bufferViews[3]: byteOffset 840 + byteLength 2433 "
                     "exceeds buffers[0] (1636 bytes)");
}

TEST(GltfErrors, AnImageThatCannotBeDecoded) {
  GltfBuilder b = test::quad_gltf();
  const std::string junk = "not an image at all";
  b.add("images", {{"uri", "data:image/png;base64," +
                               test::base64(reinterpret_cast<const uint8_t*>(junk.data()), junk.size())}});
  EXPECT_EQ(load_error(b, "junk.gltf"), "PATH: images[0]: cannot be decoded (unknown image type)");
}

// A file's images are decoded on the host's threads (optimisation log 109):
// each into its own texture, in data URIs and in bufferViews alike, and of
// several broken images the first by index is the one named, however the
// threads finish.
TEST(Gltf, ManyImagesDecodeEachIntoItsOwnTexture) {
  for (const bool in_views : {false, true}) {
    GltfBuilder b = test::quad_gltf();
    for (int i = 0; i < 12; ++i) {
      const std::vector<uint8_t> texels = {uint8_t(10 * i), 1, 2, 255, 3, uint8_t(200 - i), 4, 255};
      const std::string png = test::png(2, 1, texels);
      if (in_views) {
        const int view = b.add_view(png.data(), png.size());
        b.add("images", {{"bufferView", view}, {"mimeType", "image/png"}});
        b.add("textures", {{"source", i}});
      } else {
        b.add_texture(png);
      }
      b.add("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}, {"metallicFactor", 0}}}});
    }
    const Scene s = load(b, in_views ? "views.glb" : "uris.gltf");
    ASSERT_EQ(s.textures.size(), 12u);
    for (uint32_t i = 0; i < 12; ++i) {
      const Texture& t = s.textures.at(*s.materials.at(i).base_color_texture);
      EXPECT_EQ(t.texels, (std::vector<uint32_t>{0xff020100u | (10 * i), 0xff040000u | ((200 - i) << 8) | 3u}))
          << (in_views ? "view " : "uri ") << i;
    }
  }
}

TEST(GltfErrors, OfSeveralBrokenImagesTheFirstIsNamed) {
  const std::string junk = "not an image at all";
  for (const bool in_views : {false, true}) {
    GltfBuilder b = test::quad_gltf();
    for (int i = 0; i < 12; ++i) {
      const std::string bytes = i == 5 || i == 9 ? junk : test::png(2, 1, kTwoTexels);
      if (in_views) {
        const int view = b.add_view(bytes.data(), bytes.size());
        b.add("images", {{"bufferView", view}, {"mimeType", "image/png"}});
      } else {
        b.add("images", {{"uri", "data:image/png;base64," +
                                     test::base64(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())}});
      }
    }
    EXPECT_EQ(load_error(b, in_views ? "views.glb" : "uris.gltf"), "PATH: images[5]: cannot be decoded (unknown image type)")
        << (in_views ? "views" : "uris");
  }
}

TEST(GltfErrors, TexturesSamplersAndEmission) {
  const GltfBuilder textured = test::textured_quad_gltf(test::png(2, 1, kTwoTexels));
  GltfBuilder b = textured;
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3;
  EXPECT_EQ(load_error(b, "index.gltf"),
            "PATH: materials[0].pbrMetallicRoughness.baseColorTexture.index: index 3 out of range (1 texture)");
  b = textured;
  b.doc["materials"][0]["emissiveTexture"] = {{"index", 1}};
  EXPECT_EQ(load_error(b, "emissive_index.gltf"), "PATH: materials[0].emissiveTexture.index: index 1 out of range (1 texture)");
  b = textured;
  b.doc["textures"][0]["source"] = 2;
  EXPECT_EQ(load_error(b, "source.gltf"), "PATH: textures[0].source: index 2 out of range (1 image)");
  b = textured;
  b.doc["textures"][0].erase("source");
  EXPECT_EQ(load_error(b, "no_source.gltf"),
            "PATH: textures[0]: has no source image (octrace reads the images of the core spec, PNG and JPEG)");
  b = textured;
  b.doc["textures"][0]["sampler"] = 4;
  EXPECT_EQ(load_error(b, "sampler.gltf"), "PATH: textures[0].sampler: index 4 out of range (1 sampler)");
  b = textured;
  b.doc["samplers"][0]["wrapT"] = 1234;
  EXPECT_EQ(load_error(b, "wrap.gltf"), "PATH: samplers[0].wrapT: unknown wrap mode 1234 (expected 10497 REPEAT, "
                                        "33071 CLAMP_TO_EDGE or 33648 MIRRORED_REPEAT)");
  b = textured;
  b.doc["materials"][0]["emissiveFactor"] = {2, 0, 0};
  EXPECT_EQ(load_error(b, "factor.gltf"), "PATH: materials[0].emissiveFactor: must be 3 numbers in [0, 1], got [2, 0, 0]");
  b = textured;
  b.doc["materials"][0]["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}};
  EXPECT_EQ(load_error(b, "strength.gltf"), "PATH: materials[0].extensions.KHR_materials_emissive_strength."
                                            "emissiveStrength: must be a finite number >= 0, got -1");
  b.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = "bright";
  EXPECT_EQ(load_error(b, "strength_type.gltf"), "PATH: materials[0].extensions.KHR_materials_emissive_strength."
                                                 "emissiveStrength: expected a number, got \"bright\"");
  // An image cut short: its header reads, its pixels do not.
  const std::string png = test::png(2, 1, kTwoTexels);
  b = test::textured_quad_gltf(png.substr(0, png.size() - 20));
  const std::string message = load_error(b, "cut.gltf");
  EXPECT_EQ(message.rfind("PATH: images[0]: cannot be decoded (", 0), 0u) << message;
}

TEST(GltfErrors, BuffersViewsAccessorsAndIndicesOutOfRange) {
  GltfBuilder b = test::quad_gltf();
  b.doc["bufferViews"][1]["byteLength"] = 100;
  EXPECT_EQ(load_error(b, "view.gltf"), "PATH: bufferViews[1]: byteOffset 48 + byteLength 100 exceeds buffers[0] (60 bytes)");

  b = test::quad_gltf();
  b.doc["accessors"][0]["count"] = 900;
  EXPECT_EQ(load_error(b, "count.gltf"), "PATH: accessors[0]: count 900 exceeds bufferView 0 (4 elements)");
  // A count far past the view is refused before the reader allocates it
  // (it said "out of host memory" at 2^32 - 1, and allocated 1.2 GB at 1e8).
  b.doc["accessors"][0]["count"] = 4294967295u;
  EXPECT_EQ(load_error(b, "huge_count.gltf"), "PATH: accessors[0]: count 4294967295 exceeds bufferView 0 (4 elements)");
  b.doc["accessors"][0]["count"] = 4;
  b.doc["accessors"][0]["byteOffset"] = 4;
  EXPECT_EQ(load_error(b, "offset.gltf"), "PATH: accessors[0]: count 4 exceeds bufferView 0 (3 elements)");

  b = GltfBuilder();
  const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  b.add_mesh(positions, b.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 7}));
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  EXPECT_EQ(load_error(b, "index.gltf"), "PATH: accessors[1][5]: index 7 out of range (4 vertices)");

  b = test::quad_gltf();
  b.doc["nodes"][0]["mesh"] = 3;
  EXPECT_EQ(load_error(b, "mesh.gltf"), "PATH: nodes[0].mesh: index 3 out of range (1 mesh)");
  b = test::quad_gltf();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 2;
  EXPECT_EQ(load_error(b, "attribute.gltf"),
            "PATH: meshes[0].primitives[0].attributes.POSITION: index 2 out of range (2 accessors)");
}

TEST(GltfErrors, NonFinitePositions) {
  GltfBuilder b;
  b.add_mesh(b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, NAN, 0}}));
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  EXPECT_EQ(load_error(b, "nan.glb"), "PATH: accessors[0][2]: must be 3 finite numbers, got [1, nan, 0]");
}

TEST(GltfErrors, WhatTheSpecForbids) {
  GltfBuilder b = test::quad_gltf();
  b.doc["meshes"][0]["primitives"][0]["mode"] = 9;
  EXPECT_EQ(load_error(b, "mode.gltf"), "PATH: meshes[0].primitives[0].mode: unknown mode 9 (expected 0 to 6)");
  b = test::quad_gltf();
  b.doc["accessors"][1]["count"] = 5;
  EXPECT_EQ(load_error(b, "whole.gltf"),
            "PATH: meshes[0].primitives[0]: 5 vertices do not make whole triangles (TRIANGLES takes 3 each)");
  b = test::quad_gltf();
  b.doc["accessors"][0]["type"] = "VEC2";
  EXPECT_EQ(load_error(b, "vec2.gltf"), "PATH: accessors[0]: POSITION must be VEC3, got VEC2");
  b = test::quad_gltf();
  b.add("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {1.5, 0, 0, 1}}}}});
  EXPECT_EQ(load_error(b, "colour.gltf"),
            "PATH: materials[0].pbrMetallicRoughness.baseColorFactor: must be 4 numbers in [0, 1], got [1.5, 0, 0, 1]");
  b = test::quad_gltf();
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(load_error(b, "projective.gltf"), "PATH: nodes[0].matrix: must be an affine transform (last row 0, 0, 0, 1)");
  b = test::quad_gltf();
  b.doc["asset"]["version"] = "1.0";
  EXPECT_EQ(load_error(b, "old.gltf"), "PATH: asset.version: glTF 1.0 is not supported (only 2.x)");
}

TEST(GltfErrors, UnsupportedRequiredExtension) {
  GltfBuilder b = test::quad_gltf();
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  EXPECT_NO_THROW(load(b, "used.gltf"));  // used, not required: the plain data is there
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_EQ(load_error(b, "required.gltf"),
            "PATH: extensionsRequired[0]: extension KHR_draco_mesh_compression is not supported");
}

TEST(GltfErrors, NodesThatDoNotFormTrees) {
  GltfBuilder b = test::quad_gltf();
  b.doc["nodes"] = json::array();
  b.add("nodes", {{"children", {1}}});
  b.add("nodes", {{"children", {2}}});
  b.add("nodes", {{"children", {0}}, {"mesh", 0}});
  EXPECT_EQ(load_error(b, "loop.gltf"), "PATH: nodes[2].children[0]: node 0 is its own ancestor (the node hierarchy loops)");
  b.doc["nodes"][2] = {{"mesh", 0}};
  b.doc["nodes"][0]["children"] = {1, 2};
  EXPECT_EQ(load_error(b, "dag.gltf"), "PATH: nodes[0].children[1]: node 2 is placed twice (glTF nodes form trees)");
  b.doc["nodes"][0]["children"] = {1};
  b.doc["nodes"][1] = json::object();
  b.set_scene({0, 2});
  EXPECT_NO_THROW(load(b, "trees.gltf"));
  b.set_scene({0, 0});
  EXPECT_EQ(load_error(b, "root.gltf"), "PATH: scenes[0].nodes[1]: node 0 is placed twice (glTF nodes form trees)");
}

// tinygltf would read a property of the wrong type as absent; the schema says no.
TEST(GltfErrors, PropertiesOfTheWrongType) {
  GltfBuilder b = test::quad_gltf();
  b.doc["scene"] = "hello";
  EXPECT_EQ(load_error(b, "scene.gltf"), "PATH: scene: expected an index (an integer >= 0), got \"hello\"");
  b = test::quad_gltf();
  b.doc["meshes"][0]["primitives"] = {{"not an array", 1}};
  EXPECT_EQ(load_error(b, "array.gltf"), "PATH: meshes[0].primitives: expected an array, got {\"not an array\":1}");
  b = test::quad_gltf();
  b.doc["accessors"][0]["count"] = "4";
  EXPECT_EQ(load_error(b, "count.gltf"), "PATH: accessors[0].count: expected an integer >= 0, got \"4\"");
  b = test::quad_gltf();
  b.doc["nodes"][0]["name"] = 42;
  EXPECT_EQ(load_error(b, "name.gltf"), "PATH: nodes[0].name: expected a string, got 42");
  b = test::quad_gltf();
  b.doc["nodes"][0]["translation"] = {1, 2};
  EXPECT_EQ(load_error(b, "translation.gltf"), "PATH: nodes[0].translation: expected an array of 3 numbers, got [1,2]");
  b = test::quad_gltf();
  b.doc.erase("asset");
  EXPECT_EQ(load_error(b, "asset.gltf"), "PATH: asset: missing required property");
}

// ---------------------------------------------------------------------------
// Debian's assimp-testmodels
// ---------------------------------------------------------------------------

const std::string kModels = "/usr/share/assimp/models/glTF2/";

TEST(AssimpModels, TheTwoCylinderEngine) {
  const std::string path = kModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  const Scene s = load_gltf_scene(path);
  EXPECT_EQ(s.meshes.size(), 29u);
  EXPECT_EQ(s.instances.size(), 67u);  // of its 82 nodes, 67 place a mesh
  EXPECT_EQ(unique_triangle_count(s), 75730u);
  EXPECT_EQ(instanced_triangle_count(s), 121496u);
  EXPECT_EQ(s.materials.size(), 34u);
  EXPECT_FLOAT_EQ(s.camera.vfov, float(glm::degrees(0.3143463730812073)));
  EXPECT_NO_THROW(validate_scene(s, path));
}

TEST(AssimpModels, BoxTexturedAsGltfAndGlb) {
  std::vector<std::string> warnings;
  GltfOptions opts;
  opts.warn = [&](const std::string& w) { warnings.push_back(w); };
  const std::string gltf = kModels + "BoxTextured-glTF/BoxTextured.gltf";
  const Scene s = load_gltf_scene(gltf, opts);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangle_count(), 12u);
  EXPECT_EQ(s.meshes[0].positions.size(), 24u);
  EXPECT_EQ(s.meshes[0].normals.size(), 24u);
  EXPECT_EQ(s.meshes[0].uvs.size(), 24u);
  // CesiumLogoFlat.png, 211x211, mirrored along u and clamped along v; metallicFactor 0: no warning.
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 211u);
  EXPECT_EQ(s.textures[0].height, 211u);
  EXPECT_EQ(s.textures[0].wrap_s, Wrap::MirroredRepeat);
  EXPECT_EQ(s.textures[0].wrap_t, Wrap::ClampToEdge);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].base_color_texture, 0u);
  EXPECT_TRUE(warnings.empty()) << warnings.at(0);
  // The .glb (image in the binary chunk) and the embedded .gltf (data URIs)
  // decode to the same texels; their sampler repeats both ways.
  for (const char* other : {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    const Scene o = load_gltf_scene(kModels + other, opts);
    EXPECT_EQ(o.meshes, s.meshes) << other;
    EXPECT_EQ(o.materials, s.materials) << other;
    ASSERT_EQ(o.textures.size(), 1u) << other;
    EXPECT_EQ(o.textures[0].texels, s.textures[0].texels) << other;
    EXPECT_EQ(o.textures[0].wrap_s, Wrap::Repeat) << other;
    EXPECT_EQ(o.textures[0].wrap_t, Wrap::Repeat) << other;
  }
}

TEST(AssimpModels, BrokenFilesGiveOneLineNamingTheFile) {
  const std::pair<std::string, std::string> cases[] = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "accessors[0][0]: index 255 out of range (24 vertices)"},
      {"MissingBin/BoxTextured.gltf", "buffers[0].uri: cannot open " + kModels +
                                          "MissingBin/BoxTextured0.bin: No such file or directory"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
       "accessors[2][0]: must be 3 finite numbers, got [-inf, -0.5, 0.5]"},
      {"RecursiveNodes/RecursiveNodes.gltf", "nodes[1].children[0]: node 0 is its own ancestor (the node hierarchy loops)"},
      {"SchemaFailures/sceneWrongType.gltf", "scene: expected an index (an integer >= 0), got \"hello\""},
  };
  for (const auto& [file, what] : cases) {
    const std::string message = input_error([&] { load_gltf_scene(kModels + file); });
    EXPECT_EQ(message, kModels + file + ": " + what);
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace octrace
