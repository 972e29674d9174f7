// The rtiow generator, scene validation and the JSON format: what a user sees
// (sphere counts, placement, determinism, lossless files, error messages),
// mesh references included (the glTF files themselves: gltf_test.cpp).
#include "scene/scene.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/errors.h"
#include "core/text.h"
#include "scene/gltf_builder.h"
#include "test_util.h"

namespace octrace {
namespace {

constexpr int kBig = 4;  // ground + three big spheres

Scene rtiow(uint64_t spheres, float radius, uint64_t seed = 1) {
  RtiowParams p;
  p.spheres = spheres;
  p.radius = radius;
  p.seed = seed;
  return make_rtiow_scene(p);
}

using test::input_error;

std::string parse_error(const std::string& json) {
  return input_error([&] { parse_scene_json(json, "scene.json"); });
}

// A valid scene file with `sphere` as its only sphere, to vary one field at a time.
std::string one_sphere(const std::string& sphere) {
  return R"({"materials": [{"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}], "spheres": [)" + sphere + "]}";
}

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// Every float of both scenes has the same bit pattern (== would let -0 equal 0).
void expect_bit_identical(const Scene& a, const Scene& b) {
  std::vector<float> fa, fb;
  const auto collect = [](const Scene& s, std::vector<float>& out) {
    const auto add = [&](glm::vec3 v) { out.insert(out.end(), {v.x, v.y, v.z}); };
    add(s.camera.lookfrom), add(s.camera.lookat), add(s.camera.vup);
    out.insert(out.end(), {s.camera.vfov, s.camera.aperture, s.camera.focus_dist});
    add(s.sky.down), add(s.sky.up), add(s.sky.radiance);
    for (const Material& m : s.materials) add(m.albedo), add(m.radiance), out.insert(out.end(), {m.fuzz, m.ior});
    for (const Sphere& sp : s.spheres) add(sp.center), out.push_back(sp.radius);
  };
  collect(a, fa);
  collect(b, fb);
  ASSERT_EQ(fa.size(), fb.size());
  for (size_t i = 0; i < fa.size(); ++i) ASSERT_EQ(bits(fa[i]), bits(fb[i])) << "float " << i << ": " << fa[i];
  EXPECT_EQ(a, b);
}

std::string test_path(const std::string& name) {
  std::filesystem::create_directories(OCTRACE_TEST_TMP);
  return std::string(OCTRACE_TEST_TMP) + "/" + name;
}

// ---------------------------------------------------------------------------
// rtiow
// ---------------------------------------------------------------------------

TEST(Rtiow, HasTheBigSpheresOfTheBook) {
  const Scene s = rtiow(0, 0.2f);
  ASSERT_EQ(s.spheres.size(), 4u);
  const auto expect_sphere = [&](int i, glm::vec3 center, float radius) {
    EXPECT_EQ(s.spheres[i].center, center) << i;
    EXPECT_EQ(s.spheres[i].radius, radius) << i;
  };
  expect_sphere(0, {0, -1000, 0}, 1000);
  expect_sphere(1, {0, 1, 0}, 1);
  expect_sphere(2, {-4, 1, 0}, 1);
  expect_sphere(3, {4, 1, 0}, 1);
  const auto material = [&](int i) { return s.materials[s.spheres[i].material]; };
  EXPECT_EQ(material(0).type, MaterialType::Lambertian);
  EXPECT_EQ(material(0).albedo, glm::vec3(0.5f));
  EXPECT_EQ(material(1).type, MaterialType::Dielectric);
  EXPECT_EQ(material(1).ior, 1.5f);
  EXPECT_EQ(material(2).type, MaterialType::Lambertian);
  EXPECT_EQ(material(2).albedo, glm::vec3(0.4f, 0.2f, 0.1f));
  EXPECT_EQ(material(3).type, MaterialType::Metal);
  EXPECT_EQ(material(3).albedo, glm::vec3(0.7f, 0.6f, 0.5f));
  EXPECT_EQ(material(3).fuzz, 0.0f);
  EXPECT_EQ(s.camera, Camera{});
  EXPECT_EQ(s.camera.lookfrom, glm::vec3(13, 2, 3));
}

TEST(Rtiow, HasExactlyTheRequestedSphereCount) {
  for (uint64_t n : {0, 1, 2, 488, 10000}) {
    const Scene s = rtiow(n, 0.05f);
    EXPECT_EQ(s.spheres.size(), kBig + n) << n;
    EXPECT_NO_THROW(validate_scene(s, "rtiow")) << n;
  }
}

TEST(Rtiow, IsDeterministicForASeedAndDiffersAcrossSeeds) {
  EXPECT_EQ(rtiow(488, 0.2f, 7), rtiow(488, 0.2f, 7));
  EXPECT_NE(rtiow(488, 0.2f, 7).spheres, rtiow(488, 0.2f, 8).spheres);
  EXPECT_NE(rtiow(1, 0.2f, 7).spheres, rtiow(1, 0.2f, 8).spheres);
}

// Small spheres do not overlap each other nor the big ones, sit on the ground and
// stay inside the 20x20 field; checked exactly (in double) on the floats stored.
void expect_well_placed(const Scene& s, float radius) {
  const size_t n = s.spheres.size();
  for (size_t i = kBig; i < n; ++i) {
    const Sphere& a = s.spheres[i];
    ASSERT_EQ(a.radius, radius);
    ASSERT_EQ(a.center.y, radius) << "sphere " << i << " does not stand on the ground";
    ASSERT_LE(std::abs(double(a.center.x)) + radius, 10.0) << "sphere " << i << " outside the field";
    ASSERT_LE(std::abs(double(a.center.z)) + radius, 10.0) << "sphere " << i << " outside the field";
    for (size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const Sphere& b = s.spheres[j];
      const glm::dvec3 d = glm::dvec3(a.center) - glm::dvec3(b.center);
      const double reach = double(a.radius) + double(b.radius);
      ASSERT_GE(d.x * d.x + d.y * d.y + d.z * d.z, reach * reach) << "spheres " << i << " and " << j << " overlap";
    }
  }
}

TEST(Rtiow, SmallSpheresDoNotOverlapAndStayInTheField) {
  expect_well_placed(rtiow(488, 0.2f), 0.2f);
  expect_well_placed(rtiow(10000, 0.05f, 3), 0.05f);
  expect_well_placed(rtiow(1, 0.2f), 0.2f);
  expect_well_placed(rtiow(5, 1.5f), 1.5f);
}

TEST(Rtiow, SpreadsOverTheWholeField) {
  const Scene s = rtiow(488, 0.2f);
  int quadrant[4] = {};
  for (size_t i = kBig; i < s.spheres.size(); ++i)
    ++quadrant[(s.spheres[i].center.x > 0 ? 1 : 0) + (s.spheres[i].center.z > 0 ? 2 : 0)];
  for (int q : quadrant) EXPECT_GT(q, 488 / 4 - 40);
}

TEST(Rtiow, MaterialMixIsAbout80_15_5) {
  const uint64_t n = 100000;
  const Scene s = rtiow(n, 0.02f);
  double counts[3] = {};
  for (size_t i = kBig; i < s.spheres.size(); ++i) {
    const Material& m = s.materials[s.spheres[i].material];
    ++counts[static_cast<int>(m.type)];
    if (m.type == MaterialType::Lambertian) {
      ASSERT_TRUE(m.albedo.x >= 0 && m.albedo.x < 1);
    } else if (m.type == MaterialType::Metal) {
      ASSERT_TRUE(m.albedo.y >= 0.5f && m.albedo.y <= 1) << m.albedo.y;
      ASSERT_TRUE(m.fuzz >= 0 && m.fuzz <= 0.5f) << m.fuzz;
    } else {
      ASSERT_EQ(m.type, MaterialType::Dielectric);
      ASSERT_EQ(m.ior, 1.5f);
    }
  }
  EXPECT_NEAR(counts[0] / n, 0.80, 0.01);
  EXPECT_NEAR(counts[1] / n, 0.15, 0.01);
  EXPECT_NEAR(counts[2] / n, 0.05, 0.01);
  // Glass spheres share one material; the others each have their own.
  EXPECT_NEAR(double(s.materials.size()), kBig + 0.95 * n, 0.01 * n);
}

TEST(Rtiow, StillMakesNSpheresWhenTheyCannotFitApart) {
  // 10000 spheres of radius 0.2 cover more than the field: they overlap, but all are made.
  const Scene dense = rtiow(10000, 0.2f);
  EXPECT_EQ(dense.spheres.size(), kBig + 10000u);
  EXPECT_NO_THROW(validate_scene(dense, "rtiow"));
  // Radius 50: the big spheres' keep-out zones cover the whole field.
  EXPECT_EQ(rtiow(10, 50.0f).spheres.size(), kBig + 10u);
}

TEST(Rtiow, MakesAMillionSpheres) {
  const Scene s = rtiow(1000000, 0.01f);
  EXPECT_EQ(s.spheres.size(), kBig + 1000000u);
  EXPECT_NO_THROW(validate_scene(s, "rtiow"));
}

TEST(Rtiow, RefusesBadParameters) {
  EXPECT_EQ(input_error([] { rtiow(10, -1.0f); }), "rtiow.radius: must be a finite number > 0, got -1");
  EXPECT_EQ(input_error([] { rtiow(10, 0.0f); }), "rtiow.radius: must be a finite number > 0, got 0");
  EXPECT_EQ(input_error([] { rtiow(10, NAN); }), "rtiow.radius: must be a finite number > 0, got nan");
  EXPECT_EQ(input_error([] { rtiow(10, INFINITY); }), "rtiow.radius: must be a finite number > 0, got inf");
  EXPECT_EQ(input_error([] { rtiow(100000001, 0.01f); }),
            "rtiow.spheres: at most 100000000 small spheres, got 100000001");
}

// ---------------------------------------------------------------------------
// validate_scene (scenes built in code)
// ---------------------------------------------------------------------------

TEST(Validate, NamesTheSourceAndTheField) {
  Scene s = rtiow(20, 0.2f);
  s.spheres[12].radius = -1;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }), "mine: spheres[12].radius: must be a finite number > 0, got -1");
  s = rtiow(20, 0.2f);
  s.spheres[5].material = 9999;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }),
            "mine: spheres[5].material: index 9999 out of range (" + std::to_string(s.materials.size()) + " materials)");
  s = rtiow(0, 0.2f);
  s.spheres[1].center.y = NAN;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }), "mine: spheres[1].center: must be 3 finite numbers, got [0, nan, 0]");
  s = rtiow(0, 0.2f);
  s.materials[3].fuzz = 1.5f;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }), "mine: materials[3].fuzz: must be a number in [0, 1], got 1.5");
  s = rtiow(0, 0.2f);
  s.materials[0].albedo.z = -0.5f;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }),
            "mine: materials[0].albedo: must be 3 finite numbers >= 0, got [0.5, 0.5, -0.5]");
  s = rtiow(0, 0.2f);
  s.materials[1].ior = 0;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }), "mine: materials[1].ior: must be a finite number > 0, got 0");
  s = rtiow(0, 0.2f);
  s.sky.up.x = INFINITY;
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }), "mine: sky.up: must be 3 finite numbers >= 0, got [inf, 0.7, 1]");
}

TEST(Validate, RefusesCamerasThatCannotSee) {
  const auto camera_error = [](auto change) {
    Scene s = rtiow(0, 0.2f);
    change(s.camera);
    return input_error([&] { validate_scene(s, "cam"); });
  };
  EXPECT_EQ(camera_error([](Camera& c) { c.vfov = 0; }), "cam: camera.vfov: must be a finite number in (0, 180) degrees, got 0");
  EXPECT_EQ(camera_error([](Camera& c) { c.vfov = 180; }), "cam: camera.vfov: must be a finite number in (0, 180) degrees, got 180");
  EXPECT_EQ(camera_error([](Camera& c) { c.aperture = -0.1f; }), "cam: camera.aperture: must be a finite number >= 0, got -0.1");
  EXPECT_EQ(camera_error([](Camera& c) { c.focus_dist = 0; }), "cam: camera.focus_dist: must be a finite number > 0, got 0");
  EXPECT_EQ(camera_error([](Camera& c) { c.lookat = c.lookfrom; }), "cam: camera.lookat: must differ from camera.lookfrom");
  EXPECT_EQ(camera_error([](Camera& c) { c.vup = glm::vec3(0); }), "cam: camera.vup: must not be the zero vector");
  EXPECT_EQ(camera_error([](Camera& c) { c.vup = c.lookat - c.lookfrom; }),
            "cam: camera.vup: must not be parallel to the view direction (lookat - lookfrom), got [-13, -2, -3]");
  EXPECT_EQ(camera_error([](Camera& c) { c.lookfrom = {0, 10, 0}; }),
            "cam: camera.vup: must not be parallel to the view direction (lookat - lookfrom), got [0, 1, 0]");
}

// ---------------------------------------------------------------------------
// JSON round trip
// ---------------------------------------------------------------------------

TEST(Json, RtiowRoundTripsBitExactly) {
  const Scene s = rtiow(10000, 0.05f, 42);
  expect_bit_identical(parse_scene_json(scene_to_json(s), "rt.json"), s);
}

// Every material and sky type, and floats that are hard to print: not exactly
// representable, tiny, huge, subnormal, negative zero.
Scene every_kind() {
  Scene s;
  s.camera.lookfrom = {0.1f, -0.0f, 3.4028235e38f};
  s.camera.lookat = {1e-7f, 2.5f, 1e-40f};
  s.camera.vup = {0.0f, 1.0f, 0.3f};
  s.camera.vfov = 179.9f;
  s.camera.aperture = 0.0f;
  s.camera.focus_dist = 1.17549435e-38f;
  Material m;
  m.albedo = {0.2f, 1.0f / 3.0f, 0.999999f};
  s.materials.push_back(m);
  m = Material{};
  m.type = MaterialType::Metal;
  m.albedo = {0.7f, 0.6f, 0.5f};
  m.fuzz = 0.123456789f;
  s.materials.push_back(m);
  m = Material{};
  m.type = MaterialType::Dielectric;
  m.ior = 1.333f;
  s.materials.push_back(m);
  m = Material{};
  m.type = MaterialType::Emissive;
  m.radiance = {4.0f, 16777217.0f, 1e20f};
  s.materials.push_back(m);
  for (uint32_t i = 0; i < 4; ++i) s.spheres.push_back({{float(i) * 0.1f, -1000.0f, 1e-5f}, 0.3f + float(i), i});
  return s;
}

TEST(Json, EveryMaterialAndSkyRoundTripsBitExactly) {
  Scene s = every_kind();
  s.sky.type = SkyType::Gradient;
  s.sky.down = {0.9f, 0.8f, 0.7f};
  s.sky.up = {0.1f, 0.2f, 0.3f};
  expect_bit_identical(parse_scene_json(scene_to_json(s), "rt.json"), s);

  s = every_kind();
  s.sky.type = SkyType::Uniform;
  s.sky.radiance = {0.25f, 0.5f, 2.0f};
  expect_bit_identical(parse_scene_json(scene_to_json(s), "rt.json"), s);

  s = every_kind();
  s.sky.type = SkyType::None;
  expect_bit_identical(parse_scene_json(scene_to_json(s), "rt.json"), s);
}

// glTF's metallic-roughness material: every field but the type optional,
// with glTF's defaults; a round trip keeps every field bit for bit.
TEST(Json, PbrMaterialsTakeGltfDefaultsAndRoundTripBitExactly) {
  const Scene d = parse_scene_json(R"({"materials": [{"type": "pbr"}], "spheres": []})", "pbr.json");
  ASSERT_EQ(d.materials.size(), 1u);
  const Material& m = d.materials[0];
  EXPECT_EQ(m.type, MaterialType::Pbr);
  EXPECT_EQ(m.albedo, glm::vec3(1.0f));
  EXPECT_EQ(m.metallic, 1.0f);
  EXPECT_EQ(m.roughness, 1.0f);
  EXPECT_EQ(m.emission, glm::vec3(0.0f));
  EXPECT_EQ(m.transmission, 0.0f);
  EXPECT_EQ(m.ior, 1.5f);

  Scene s = every_kind();
  Material p = test::pbr(0.3f, 0.25f, 1.0f / 3.0f);
  p.albedo = {0.1f, 0.2f, 1.0f};
  p.emission = {0.5f, 7.0f, 1e-3f};
  p.ior = 1.33f;
  s.materials.push_back(p);
  s.spheres.push_back({{0, 0, 0}, 1, 4});
  expect_bit_identical(parse_scene_json(scene_to_json(s), "rt.json"), s);
}

// Transmission is rendered: a JSON pbr material with it is a closed solid
// (never thin-walled), and it loads without a warning.
TEST(Json, PbrTransmissionIsASolidWithoutWarning) {
  testing::internal::CaptureStderr();
  const Scene s = parse_scene_json(R"({"materials": [{"type": "pbr", "transmission": 0.5}, {"type": "pbr"},
                                                     {"type": "pbr", "transmission": 1}], "spheres": []})",
                                   "glass.json");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(s.materials[0].transmission, 0.5f);
  EXPECT_FALSE(s.materials[0].thin_walled);
  EXPECT_FALSE(s.materials[2].thin_walled);
}

TEST(JsonErrors, PbrValuesOutOfRange) {
  const auto error = [](const std::string& material) {
    return parse_error(R"({"materials": [)" + material + R"(], "spheres": []})");
  };
  EXPECT_EQ(error(R"({"type": "pbr", "roughness": -0.5})"),
            "scene.json: materials[0].roughness: must be a number in [0, 1], got -0.5");
  EXPECT_EQ(error(R"({"type": "pbr", "metallic": 2})"),
            "scene.json: materials[0].metallic: must be a number in [0, 1], got 2");
  EXPECT_EQ(error(R"({"type": "pbr", "ior": 0})"), "scene.json: materials[0].ior: must be a finite number > 0, got 0");
  EXPECT_EQ(error(R"({"type": "pbr", "transmission": 1.5})"),
            "scene.json: materials[0].transmission: must be a number in [0, 1], got 1.5");
  EXPECT_EQ(error(R"({"type": "pbr", "base_color": [1.5, 0, 0]})"),
            "scene.json: materials[0].base_color: must be 3 numbers in [0, 1], got [1.5, 0, 0]");
  EXPECT_EQ(error(R"({"type": "pbr", "emission": [1, -1, 0]})"),
            "scene.json: materials[0].emission: must be 3 finite numbers >= 0, got [1, -1, 0]");
  EXPECT_EQ(error(R"({"type": "pbr", "albedo": [1, 1, 1]})"),
            "scene.json: materials[0].albedo: unknown key (expected type, base_color, metallic, roughness, emission, "
            "transmission, ior)");
}

// NaN cannot come from JSON; a scene built in code is checked the same way.
TEST(SceneValidation, PbrNanIsRefused) {
  Scene s;
  s.materials = {test::pbr(1.0f, 1.0f, std::nanf(""))};
  EXPECT_EQ(input_error([&] { validate_scene(s, "mine"); }),
            "mine: materials[0].roughness: must be a number in [0, 1], got nan");
}

TEST(Json, WritesShortNumbersAndOneSpherePerLine) {
  const std::string text = scene_to_json(rtiow(3, 0.2f));
  EXPECT_NE(text.find(R"("aperture": 0.1,)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"(    {"center": [0, -1000, 0], "radius": 1000, "material": 0},)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"(    {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0},)"), std::string::npos) << text;
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 3 + (2 + 4 + 3) + (2 + 4 + 3) + 1) << text;  // {, camera, sky; materials; spheres; }
}

TEST(Json, SaveAndLoadRoundTripAndLeaveNoTemporaryFile) {
  const std::string dir = test_path("save_load");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Scene s = rtiow(488, 0.2f, 5);
  save_scene_json(s, dir + "/scene.json");
  save_scene_json(s, dir + "/scene.json");  // overwrites
  expect_bit_identical(load_scene_json(dir + "/scene.json"), s);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(Json, SaveToAMissingFolderIsARuntimeError) {
  const std::string path = test_path("no_such_folder/scene.json");
  try {
    save_scene_json(rtiow(0, 0.2f), path);
    ADD_FAILURE() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot write: No such file or directory");
  }
}

TEST(Json, OmittedOptionalFieldsTakeTheirDefaults) {
  const Scene s = parse_scene_json(R"({"materials": [{"type": "metal", "albedo": [1, 1, 1]}, {"type": "dielectric"}],
                                       "spheres": [], "camera": {"vfov": 40}})",
                                   "scene.json");
  Camera camera;
  camera.vfov = 40;
  EXPECT_EQ(s.camera, camera);
  EXPECT_EQ(s.sky, Sky{});
  EXPECT_EQ(s.materials[0].fuzz, 0.0f);
  EXPECT_EQ(s.materials[1].ior, 1.5f);
  EXPECT_TRUE(s.spheres.empty());
}

// ---------------------------------------------------------------------------
// JSON errors: file, path, expectation
// ---------------------------------------------------------------------------

TEST(JsonErrors, MissingRequiredField) {
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "material": 0})")),
            "scene.json: spheres[0].radius: missing required field");
  EXPECT_EQ(parse_error(R"({"spheres": []})"), "scene.json: materials: missing required field");
  EXPECT_EQ(parse_error(R"({"materials": [{"albedo": [1, 1, 1]}], "spheres": []})"),
            "scene.json: materials[0].type: missing required field");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "sky": {"type": "uniform"}})"),
            "scene.json: sky.radiance: missing required field");
}

TEST(JsonErrors, WrongType) {
  EXPECT_EQ(parse_error(R"({"camera": {"lookfrom": [1, 2]}, "materials": [], "spheres": []})"),
            "scene.json: camera.lookfrom: expected an array of 3 numbers, got [1,2]");
  EXPECT_EQ(parse_error(R"({"camera": {"lookfrom": "far"}, "materials": [], "spheres": []})"),
            "scene.json: camera.lookfrom: expected an array of 3 numbers, got \"far\"");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": "1", "material": 0})")),
            "scene.json: spheres[0].radius: expected a number, got \"1\"");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": 1, "material": 1.5})")),
            "scene.json: spheres[0].material: expected a material index (an integer >= 0), got 1.5");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": 1, "material": -1})")),
            "scene.json: spheres[0].material: expected a material index (an integer >= 0), got -1");
  EXPECT_EQ(parse_error(one_sphere("[1, 2, 3]")), "scene.json: spheres[0]: expected an object, got [1,2,3]");
  EXPECT_EQ(parse_error(one_sphere("7")), "scene.json: spheres[0]: expected an object, got 7");
  EXPECT_EQ(parse_error(R"({"materials": {}, "spheres": []})"), "scene.json: materials: expected an array, got {}");
  EXPECT_EQ(parse_error(R"({"materials": [{"type": "lambertian", "albedo": [1, 1, 1]}, "red"], "spheres": []})"),
            "scene.json: materials[1]: expected an object, got \"red\"");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": 3})"), "scene.json: spheres: expected an array, got 3");
  EXPECT_EQ(parse_error("[]"), "scene.json: expected a JSON object at the top level, got []");
}

TEST(JsonErrors, NumbersBeyondFloatRange) {
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 1e999, 0], "radius": 1, "material": 0})")),
            "scene.json: spheres[0].center[1]: number out of range of a 32-bit float, got 1e999");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": -1e39, "material": 0})")),
            "scene.json: spheres[0].radius: number out of range of a 32-bit float, got -1e39");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "camera": {"vfov": 1e39}})"),
            "scene.json: camera.vfov: number out of range of a 32-bit float, got 1e39");
}

TEST(JsonErrors, ValuesOutOfRange) {
  const std::string spheres = R"({"center": [0, 0, 0], "radius": 1, "material": 0}, )";
  std::string many;
  for (int i = 0; i < 12; ++i) many += spheres;
  EXPECT_EQ(parse_error(one_sphere(many + R"({"center": [0, 0, 0], "radius": -1, "material": 0})")),
            "scene.json: spheres[12].radius: must be a finite number > 0, got -1");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": 1, "material": 7})")),
            "scene.json: spheres[0].material: index 7 out of range (1 material)");
  EXPECT_EQ(parse_error(R"({"materials": [{"type": "metal", "albedo": [1, 1, 1], "fuzz": 2}], "spheres": []})"),
            "scene.json: materials[0].fuzz: must be a number in [0, 1], got 2");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "camera": {"vfov": 200}})"),
            "scene.json: camera.vfov: must be a finite number in (0, 180) degrees, got 200");
}

TEST(JsonErrors, UnknownTypes) {
  EXPECT_EQ(parse_error(R"({"materials": [{"type": "lambertian", "albedo": [1, 1, 1]}, {"type": "glas", "ior": 1.5}],
                             "spheres": []})"),
            "scene.json: materials[1].type: unknown material type \"glas\" (expected lambertian, metal, dielectric, emissive, pbr)");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "sky": {"type": "sunset"}})"),
            "scene.json: sky.type: unknown sky type \"sunset\" (expected gradient, uniform, none, envmap)");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "sky": {"type": 1}})"),
            "scene.json: sky.type: unknown sky type 1 (expected gradient, uniform, none, envmap)");
}

TEST(JsonErrors, UnknownKeys) {
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "camera": {"lokfrom": [1, 2, 3]}})"),
            "scene.json: camera.lokfrom: unknown key (expected lookfrom, lookat, vup, vfov, aperture, focus_dist)");
  EXPECT_EQ(parse_error(R"({"materials": [{"type": "dielectric", "fuzz": 0}], "spheres": []})"),
            "scene.json: materials[0].fuzz: unknown key (expected type, ior)");
  EXPECT_EQ(parse_error(one_sphere(R"({"center": [0, 0, 0], "radius": 1, "material": 0, "colour": 1})")),
            "scene.json: spheres[0].colour: unknown key (expected center, radius, material)");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "light": []})"),
            "scene.json: light: unknown key (expected camera, sky, materials, spheres, meshes, lights)");
  EXPECT_EQ(parse_error(R"({"materials": [], "spheres": [], "spheres": []})"), "scene.json: spheres: appears twice");
  EXPECT_EQ(parse_error(R"({"materials": [], "materials": [], "spheres": []})"), "scene.json: materials: appears twice");
}

Scene with_lights() {
  Scene s;
  Light point;
  point.position = {1.0f / 3.0f, 2.0f, -0.0f};
  point.color = {1.0f, 0.9f, 0.7f};
  point.intensity = 12.5f;
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.0f, 4.0f, 1e-7f};
  spot.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.2f));
  spot.intensity = 1e6f;
  spot.inner_cone = 12.3f;
  spot.outer_cone = 30.0f;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -3.0f, 0.5f));
  sun.color = {1.0f, 0.95f, 0.9f};
  sun.intensity = 3.0f;
  s.lights = {point, spot, sun};
  return s;
}

TEST(Json, LightsRoundTripBitExactly) {
  const Scene s = with_lights();
  EXPECT_EQ(parse_scene_json(scene_to_json(s), "rt.json"), s);
}

TEST(Json, LightsTakeGltfDefaultsAndDirectionsAreNormalised) {
  const Scene s = parse_scene_json(R"({"materials": [], "lights": [
      {"type": "point", "position": [0, 1, 0]},
      {"type": "spot", "position": [0, 1, 0], "direction": [0, -2, 0]},
      {"type": "directional", "direction": [3, 0, 4]}]})", "l.json");
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f));
  EXPECT_EQ(s.lights[0].intensity, 1.0f);
  EXPECT_EQ(s.lights[1].inner_cone, 0.0f);
  EXPECT_EQ(s.lights[1].outer_cone, 45.0f);
  EXPECT_EQ(s.lights[1].direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(s.lights[2].direction, glm::vec3(0.6f, 0, 0.8f));
}

TEST(JsonErrors, LightValues) {
  const auto light = [](const std::string& l) {
    return parse_error(R"({"materials": [], "lights": [)" + l + "]}");
  };
  EXPECT_EQ(light(R"({"type": "area"})"),
            "scene.json: lights[0].type: unknown light type \"area\" (expected point, spot, directional)");
  EXPECT_EQ(light(R"({"type": "point"})"), "scene.json: lights[0].position: missing required field");
  EXPECT_EQ(light(R"({"type": "point", "position": [0, 0, 0], "direction": [0, 1, 0]})"),
            "scene.json: lights[0].direction: unknown key (expected type, position, color, intensity)");
  EXPECT_EQ(light(R"({"type": "directional", "direction": [0, 0, 0]})"),
            "scene.json: lights[0].direction: must be a non-zero vector, got [0,0,0]");
  EXPECT_EQ(light(R"({"type": "point", "position": [0, 0, 0], "intensity": -1})"),
            "scene.json: lights[0].intensity: must be a finite number >= 0, got -1");
  EXPECT_EQ(light(R"({"type": "point", "position": [0, 0, 0], "color": [1, -1, 1]})"),
            "scene.json: lights[0].color: must be 3 finite numbers >= 0, got [1, -1, 1]");
  EXPECT_EQ(light(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "outer_cone": 91})"),
            "scene.json: lights[0].outer_cone: must be a number in (0, 90] degrees, got 91");
  EXPECT_EQ(light(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "inner_cone": 30, "outer_cone": 30})"),
            "scene.json: lights[0].inner_cone: must be a number in [0, outer_cone) degrees, got 30");
  EXPECT_EQ(parse_error(R"({"materials": [], "lights": {}})"), "scene.json: lights: expected an array, got {}");
}

TEST(JsonErrors, SyntaxErrorsGiveLineAndColumn) {
  const std::string message = parse_error("{\n  \"materials\": [],\n  \"spheres\": [,]\n}");
  EXPECT_EQ(message.rfind("scene.json: invalid JSON at line 3, column 15: syntax error", 0), 0u) << message;
  const std::string truncated = parse_error(R"({"materials": [], "spheres": [)");
  EXPECT_EQ(truncated.rfind("scene.json: invalid JSON at line 1, column 31: ", 0), 0u) << truncated;
  const std::string nan = parse_error(R"({"materials": [], "spheres": [], "camera": {"vfov": NaN}})");
  EXPECT_EQ(nan.rfind("scene.json: invalid JSON at line 1, column ", 0), 0u) << nan;
}

// nlohmann parses any depth, but describing a value (dump()) recurses: a
// scene nested many thousand levels deep overflowed the stack. Refused while
// parsing, past 512 levels; 512 itself still reads as far as the parser goes.
TEST(JsonErrors, DeepNestingIsRefusedNotACrash) {
  const auto nested = [](int levels) { return std::string(size_t(levels), '[') + std::string(size_t(levels), ']'); };
  EXPECT_EQ(parse_error(nested(100000)), "scene.json: nested deeper than 512 levels");
  EXPECT_EQ(parse_error(R"({"materials": [], "camera": )" + nested(600) + "}"),
            "scene.json: nested deeper than 512 levels");
  EXPECT_EQ(parse_error(nested(500)), "scene.json: expected a JSON object at the top level, got an array of 1 elements");
}

TEST(JsonErrors, MissingFile) {
  const std::string path = test_path("does_not_exist.json");
  EXPECT_EQ(input_error([&] { load_scene_json(path); }), path + ": cannot open file: No such file or directory");
}

TEST(JsonErrors, LoadNamesTheFile) {
  const std::string path = test_path("bad_radius.json");
  std::ofstream(path) << one_sphere(R"({"center": [0, 0, 0], "radius": 0, "material": 0})");
  EXPECT_EQ(input_error([&] { load_scene_json(path); }),
            path + ": spheres[0].radius: must be a finite number > 0, got 0");
}

// ---------------------------------------------------------------------------
// meshes: references to glTF files
// ---------------------------------------------------------------------------

// A folder of the test's own (ctest runs the tests as parallel processes)
// with quad.glb in it: a unit square, 2 triangles, no materials.
std::string mesh_folder() {
  const std::string dir = test_path(std::string("meshes_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  test::quad_gltf().write(dir + "/quad.glb");
  return dir;
}

Scene parse_with_meshes(const std::string& json) { return parse_scene_json(json, mesh_folder() + "/scene.json"); }

std::string mesh_error(const std::string& meshes) {
  const std::string dir = mesh_folder();
  std::string message = input_error([&] {
    parse_scene_json(R"({"materials": [{"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}], "meshes": )" + meshes + "}",
                     dir + "/scene.json");
  });
  for (size_t at; (at = message.find(dir)) != std::string::npos;) message.replace(at, dir.size(), "DIR");
  return message;
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST(JsonMeshes, FilesAreFoundBesideTheSceneFile) {
  const Scene s = parse_with_meshes(R"({"materials": [{"type": "metal", "albedo": [1, 1, 1]}],
      "meshes": [{"file": "quad.glb"}, {"file": "quad.glb", "material": 0, "transform": {"translate": [0, 0, 5]}}]})");
  // Each reference adds its file's meshes; the first its materials too (glTF's
  // default one here), the second is coloured by the scene's material 0.
  ASSERT_EQ(s.meshes.size(), 2u);
  ASSERT_EQ(s.instances.size(), 2u);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[1], test::gltf_default_material());
  EXPECT_EQ(s.mesh_file_materials, 1u);
  EXPECT_EQ(s.meshes[0].materials, (std::vector<uint32_t>{1, 1}));
  EXPECT_EQ(s.meshes[1].materials, (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(s.instances[1].mesh, 1u);
  EXPECT_EQ(apply(s.instances[1].transform, {1, 1, 0}), glm::vec3(1, 1, 5));
  ASSERT_EQ(s.mesh_refs.size(), 2u);
  EXPECT_EQ(s.mesh_refs[1].file, "quad.glb");
  EXPECT_EQ(s.mesh_refs[1].material, 0u);
  EXPECT_TRUE(s.spheres.empty());
}

// Every texture slot of a second file's materials points past the first
// file's textures (a normal map once kept the index it had in its own file).
TEST(JsonMeshes, EveryTextureOfASecondFileIsRebased) {
  const std::string dir = mesh_folder();
  const std::string png = test::png(1, 1, {128, 128, 255, 255});
  test::textured_quad_gltf(png).write(dir + "/first.glb");
  test::GltfBuilder second = test::textured_quad_gltf(png);
  second.doc["materials"][0] = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}},
                                                          {"metallicRoughnessTexture", {{"index", 0}}}}},
                                {"emissiveTexture", {{"index", 0}}},
                                {"emissiveFactor", {1, 1, 1}},
                                {"normalTexture", {{"index", 0}}}};
  second.write(dir + "/second.glb");
  const Scene s = parse_with_meshes(R"({"materials": [], "meshes": [{"file": "first.glb"}, {"file": "second.glb"}]})");
  ASSERT_EQ(s.textures.size(), 2u);
  const Material& m = s.materials.back();
  EXPECT_EQ(m.base_color_texture, 1u);
  EXPECT_EQ(m.metallic_roughness_texture, 1u);
  EXPECT_EQ(m.emission_texture, 1u);
  EXPECT_EQ(m.normal_texture, 1u);
}

// References to the same file with the same scene and material override
// load it once: its meshes and materials are shared and the later references
// add instances only, with the transforms two loads would give, bit for bit.
TEST(JsonMeshes, TheSameFileReferencedTwiceIsLoadedOnce) {
  const Scene twice = parse_with_meshes(R"({"materials": [],
      "meshes": [{"file": "quad.glb"}, {"file": "./quad.glb", "transform": {"translate": [0, 0, 5], "scale": 3}}]})");
  const Scene once = parse_with_meshes(R"({"materials": [], "meshes": [{"file": "quad.glb"}]})");
  const Scene moved = parse_with_meshes(
      R"({"materials": [], "meshes": [{"file": "quad.glb", "transform": {"translate": [0, 0, 5], "scale": 3}}]})");
  ASSERT_EQ(twice.meshes.size(), once.meshes.size());
  EXPECT_EQ(twice.materials.size(), once.materials.size());
  EXPECT_EQ(twice.mesh_file_materials, once.mesh_file_materials);
  ASSERT_EQ(twice.instances.size(), 2 * once.instances.size());
  EXPECT_EQ(twice.instances[0], once.instances[0]);
  EXPECT_EQ(std::memcmp(&twice.instances[1].transform, &moved.instances[0].transform, sizeof(glm::mat4)), 0);
  EXPECT_EQ(twice.instances[1].mesh, twice.instances[0].mesh);
  EXPECT_EQ(twice.mesh_refs.size(), 2u);
  // Another material override is another load (its triangles carry other materials).
  const Scene other = parse_with_meshes(R"({"materials": [{"type": "metal", "albedo": [1, 1, 1]}],
      "meshes": [{"file": "quad.glb"}, {"file": "quad.glb", "material": 0}]})");
  EXPECT_EQ(other.meshes.size(), 2 * once.meshes.size());
}

TEST(JsonMeshes, AScenePlacesSpheresAndMeshesOrNeither) {
  EXPECT_EQ(parse_scene_json(R"({"materials": []})", "scene.json"), Scene{});
  const Scene s = parse_with_meshes(R"({"materials": [], "meshes": [{"file": "quad.glb"}]})");
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.materials.size(), 1u);
}

// scale, then rotate (right-handed, degrees), then translate.
TEST(JsonMeshes, TransformsApplyScaleThenRotateThenTranslate) {
  const auto transform = [](const std::string& t) {
    return parse_with_meshes(R"({"materials": [], "meshes": [{"file": "quad.glb", "transform": )" + t + "}]}")
        .instances.at(0)
        .transform;
  };
  const glm::mat4 t = transform(R"({"translate": [0, 0, 5], "rotate": [0, 0, 2, 90], "scale": 2})");
  const glm::vec3 p = apply(t, {1, 0, 0});  // (2, 0, 0), then (0, 2, 0), then (0, 2, 5)
  EXPECT_NEAR(p.x, 0.0f, 1e-6f);
  EXPECT_NEAR(p.y, 2.0f, 1e-6f);
  EXPECT_NEAR(p.z, 5.0f, 1e-6f);
  EXPECT_EQ(apply(transform(R"({"scale": [1, 2, -3]})"), {1, 1, 1}), glm::vec3(1, 2, -3));
  EXPECT_EQ(transform(R"({"matrix": [2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 5, 6, 7, 1]})"),
            glm::mat4(2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 5, 6, 7, 1));
}

// Written back as references (the transform as a matrix), without the files'
// own materials; loading that gives the same scene, and writing it the same text.
TEST(JsonMeshes, RoundTripAsReferences) {
  const Scene s = parse_with_meshes(R"({"materials": [{"type": "lambertian", "albedo": [0.1, 0.2, 0.3]}],
      "spheres": [{"center": [0, 0, 0], "radius": 1, "material": 0}],
      "meshes": [{"file": "quad.glb", "transform": {"scale": 1.5, "rotate": [0, 1, 0, 35], "translate": [0.3, 0, -0.2]}},
                 {"file": "quad.glb", "material": 0, "scene": 0}]})");
  const std::string text = scene_to_json(s);
  EXPECT_NE(text.find(R"(  "materials": [
    {"type": "lambertian", "albedo": [0.1, 0.2, 0.3]}
  ],)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"(    {"file": "quad.glb", "transform": {"matrix": [)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"(    {"file": "quad.glb", "material": 0, "scene": 0}
  ])"), std::string::npos) << text;
  const Scene again = parse_with_meshes(text);
  EXPECT_EQ(again, s);
  EXPECT_EQ(scene_to_json(again), text);
}

// Textures come only from the files: the dump refers to the file again, and
// loading it brings the same textures back (a reference with a material of
// the scene's takes none).
TEST(JsonMeshes, TexturesRoundTripThroughTheirFiles) {
  const std::string dir = mesh_folder();
  test::textured_quad_gltf(test::png(1, 2, {10, 20, 30, 255, 40, 50, 60, 255})).write(dir + "/tiles.glb");
  const Scene s = parse_with_meshes(R"({"materials": [{"type": "lambertian", "albedo": [0.1, 0.2, 0.3]}],
      "meshes": [{"file": "tiles.glb"}, {"file": "tiles.glb", "material": 0}, {"file": "tiles.glb"}]})");
  // The first and third references share one load: one texture, one material of the file's.
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].texels, (std::vector<uint32_t>{0xff1e140au, 0xff3c3228u}));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[1].base_color_texture, 0u);
  EXPECT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(s.instances[2].mesh, s.instances[0].mesh);
  const std::string text = scene_to_json(s);
  EXPECT_EQ(text.find("texture"), std::string::npos) << text;
  EXPECT_EQ(parse_with_meshes(text), s);
}

TEST(JsonMeshes, TexturesAndEmissionOfTheScenesOwnMaterialsCannotBeWritten) {
  Scene s;
  s.materials = {test::lambertian(0.5f)};
  s.materials[0].emission = glm::vec3(1.0f);
  EXPECT_EQ(input_error([&] { scene_to_json(s); }),
            "scene: materials[0]: textures (and a lambertian material's emission) come only from mesh files and cannot be written");
}

TEST(JsonMeshes, MeshesWithoutReferencesCannotBeWritten) {
  Scene s;
  s.materials.push_back({});
  s.meshes.push_back({"tri", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {0, 1, 2}, {0}});
  EXPECT_EQ(input_error([&] { scene_to_json(s); }),
            "scene: meshes: only meshes loaded from files can be written (as references to the files)");
}

TEST(JsonMeshes, Errors) {
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"rotate": [0, 0, 0, 30]}}])"),
            "DIR/scene.json: meshes[0].transform.rotate: the axis must not be the zero vector");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"rotate": [0, 1, 0]}}])"),
            "DIR/scene.json: meshes[0].transform.rotate: expected [axis x, y, z, angle in degrees], got [0,1,0]");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"scale": 2, "matrix": []}}])"),
            "DIR/scene.json: meshes[0].transform.matrix: excludes scale, rotate and translate (give one form or the other)");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]}}])"),
            "DIR/scene.json: meshes[0].transform.matrix: expected an array of 16 numbers (column-major), got "
            "[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0]");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"matrix": [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}}])"),
            "DIR/scene.json: meshes[0].transform.matrix: must be an affine transform (last row, elements 3, 7, 11 and 15: "
            "0, 0, 0, 1)");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"scale": [1, 0, 1]}}])"),
            "DIR/scene.json: meshes[0].transform.scale: must not be 0 (it would flatten the mesh), got [1,0,1]");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "transform": {"shear": 1}}])"),
            "DIR/scene.json: meshes[0].transform.shear: unknown key (expected scale, rotate, translate, matrix)");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb"}, {"file": "quad.glb", "material": 1}])"),
            "DIR/scene.json: meshes[1].material: index 1 out of range (1 material)");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "colour": 1}])"),
            "DIR/scene.json: meshes[0].colour: unknown key (expected file, material, transform, scene)");
  EXPECT_EQ(mesh_error(R"([{"material": 0}])"), "DIR/scene.json: meshes[0].file: missing required field");
  EXPECT_EQ(mesh_error(R"([{"file": ""}])"),
            "DIR/scene.json: meshes[0].file: expected a file name (a non-empty string), got \"\"");
  EXPECT_EQ(mesh_error(R"([{"file": "none.glb"}])"),
            "DIR/scene.json: meshes[0].file: DIR/none.glb: cannot open file: No such file or directory");
  EXPECT_EQ(mesh_error(R"([{"file": "quad.glb", "scene": 1}])"),
            "DIR/scene.json: meshes[0].scene: index 1 out of range (DIR/quad.glb has 1 scene)");
  EXPECT_EQ(mesh_error(R"({"file": "quad.glb"})"), "DIR/scene.json: meshes: expected an array, got {\"file\":\"quad.glb\"}");
  // An error inside the file names the scene file, the reference and the glTF path.
  test::GltfBuilder broken = test::quad_gltf();
  broken.doc["accessors"][0]["count"] = 900;
  broken.write(mesh_folder() + "/broken.glb");
  EXPECT_EQ(mesh_error(R"([{"file": "broken.glb"}])"),
            "DIR/scene.json: meshes[0].file: DIR/broken.glb: accessors[0]: count 900 exceeds bufferView 0 (4 elements)");
}

TEST(Validate, TexturesAndTheMaterialsThatUseThem) {
  const auto error = [](auto change) {
    Scene s;
    s.materials.push_back({});
    s.materials[0].base_color_texture = 0;
    s.textures.push_back({2, 1, {0xffffffffu, 0xff000000u}, Wrap::Repeat, Wrap::ClampToEdge});
    change(s);
    return input_error([&] { validate_scene(s, "mine"); });
  };
  EXPECT_EQ(error([](Scene& s) { s.materials[0].base_color_texture = 1; }),
            "mine: materials[0].base_color_texture: index 1 out of range (1 texture)");
  EXPECT_EQ(error([](Scene& s) { s.materials[0].emission_texture = 3; }),
            "mine: materials[0].emission_texture: index 3 out of range (1 texture)");
  EXPECT_EQ(error([](Scene& s) { s.materials[0].emission = {1, -1, 0}; }),
            "mine: materials[0].emission: must be 3 finite numbers >= 0, got [1, -1, 0]");
  EXPECT_EQ(error([](Scene& s) { s.materials[0].type = MaterialType::Metal; }),
            "mine: materials[0]: only lambertian and pbr materials take textures and an emission (an emissive one has a radiance)");
  EXPECT_EQ(error([](Scene& s) { s.textures[0].texels.pop_back(); }), "mine: textures[0].texels: 1 texels for 2x1");
  EXPECT_EQ(error([](Scene& s) { s.textures[0].height = 0; }), "mine: textures[0]: must be at least 1x1 texels, got 2x0");
  EXPECT_EQ(error([](Scene& s) { s.textures[0].wrap_t = Wrap(7); }), "mine: textures[0].wrap_t: unknown wrap mode 7");
}

// The transmission texture, the volume's attenuation and a mesh's tangents.
TEST(Validate, TransmissionTextureAttenuationAndTangents) {
  const auto error = [](auto change) {
    Scene s;
    Material m;
    m.type = MaterialType::Pbr;
    m.transmission = 1.0f;
    s.materials.push_back(m);
    s.meshes.push_back({"tri", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {0, 1, 2}, {0}});
    s.instances.push_back({0, glm::mat4(1.0f)});
    change(s);
    return input_error([&] { validate_scene(s, "mine"); });
  };
  EXPECT_EQ(error([](Scene& s) { s.materials[0].transmission_texture = 0; }),
            "mine: materials[0].transmission_texture: index 0 out of range (0 textures)");
  EXPECT_EQ(error([](Scene& s) { s.materials[0].attenuation_color = {0.5f, 1.5f, 0.0f}; }),
            "mine: materials[0].attenuation_color: must be 3 numbers in [0, 1], got [0.5, 1.5, 0]");
  EXPECT_EQ(error([](Scene& s) { s.materials[0].attenuation_color.z = NAN; }),
            "mine: materials[0].attenuation_color: must be 3 numbers in [0, 1], got [1, 1, nan]");
  for (float d : {0.0f, -1.0f, NAN})
    EXPECT_EQ(error([d](Scene& s) { s.materials[0].attenuation_distance = d; }),
              "mine: materials[0].attenuation_distance: must be a number > 0 (infinite: no absorption), got " +
                  float_string(d));
  EXPECT_EQ(error([](Scene& s) {
              s.materials[0].type = MaterialType::Lambertian;
              s.materials[0].attenuation_distance = 1.0f;
            }),
            "mine: materials[0]: only pbr materials take a transmission texture and an attenuation");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].tangents.assign(3, {1, 0, 0, 1}); }),
            "mine: meshes[0].tangents: tangents need normals");
  EXPECT_EQ(error([](Scene& s) {
              s.meshes[0].normals.assign(3, {0, 0, 1});
              s.meshes[0].tangents.assign(2, {1, 0, 0, 1});
            }),
            "mine: meshes[0].tangents: 2 tangents for 3 positions (must be as many, or none)");
  EXPECT_EQ(error([](Scene& s) {
              s.meshes[0].normals.assign(3, {0, 0, 1});
              s.meshes[0].tangents.assign(3, {1, 0, 0, 0.5f});
            }),
            "mine: meshes[0].tangents[0]: must be a finite tangent with w = 1 or -1 (or all 0: none), got [1, 0, 0, 0.5]");
}

TEST(Validate, MeshesAndInstances) {
  const auto error = [](auto change) {
    Scene s;
    s.materials.push_back({});
    s.meshes.push_back({"tri", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {0, 1, 2}, {0}});
    s.instances.push_back({0, glm::mat4(1.0f)});
    change(s);
    return input_error([&] { validate_scene(s, "mine"); });
  };
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].indices[2] = 3; }), "mine: meshes[0].indices[2]: index 3 out of range (3 vertices)");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].indices.push_back(0); }),
            "mine: meshes[0].indices: 4 indices do not make whole triangles");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].positions[1].y = NAN; }),
            "mine: meshes[0].positions[1]: must be 3 finite numbers, got [1, nan, 0]");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].normals = {{0, 0, 1}}; }),
            "mine: meshes[0].normals: 1 normals for 3 positions (must be as many, or none)");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, INFINITY}}; }),
            "mine: meshes[0].normals[2]: must be 3 finite numbers, got [0, 0, inf]");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].uvs = {{0, 0}, {1, 0}, {0, NAN}}; }),
            "mine: meshes[0].uvs[2]: must be 2 finite numbers, got [0, nan]");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].materials = {0, 0}; }),
            "mine: meshes[0].materials: 2 materials for 1 triangles (must be one each)");
  EXPECT_EQ(error([](Scene& s) { s.meshes[0].materials = {4}; }), "mine: meshes[0].materials[0]: index 4 out of range (1 material)");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].mesh = 1; }), "mine: instances[0].mesh: index 1 out of range (1 mesh)");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].transform[3][0] = NAN; }),
            "mine: instances[0].transform: must be 16 finite numbers");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].transform[1][1] = 0; }), "mine: instances[0].transform: must be invertible");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].transform[2][3] = 1; }),
            "mine: instances[0].transform: must be an affine transform (last row 0, 0, 0, 1)");
}

}  // namespace
}  // namespace octrace
