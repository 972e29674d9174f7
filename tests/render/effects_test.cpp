// Simulate only the effects a scene calls for: the features a scene uses are
// detected on the CPU, the pipeline is specialised to them, and the image is
// the same as the general pipeline's (`--effects all`), bit for bit: every
// effect draws from its own bounce's random stream, and an effect that is
// compiled out would only have added exact zeros.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "test_util.h"

namespace octrace {
namespace {

using test::emitter;
using test::glass;
using test::lambertian;
using test::metal;

// Three spheres on a ground, all of one material, pinhole camera, gradient sky.
Scene family(Material m) {
  Scene s;
  s.camera.lookfrom = {0, 1.5f, 6};
  s.camera.lookat = {0, 0.5f, 0};
  s.camera.aperture = 0;
  s.materials = {m};
  s.spheres = {{{0, -1000, 0}, 1000, 0}, {{0, 0.7f, 0}, 0.7f, 0}, {{1.4f, 0.4f, 0.6f}, 0.4f, 0}, {{-1.4f, 0.4f, 0.6f}, 0.4f, 0}};
  return s;
}

struct EffectsCase {
  const char* name;
  Scene (*make)();
  std::vector<std::string> expected;  // feature_names of the scene
};
void PrintTo(const EffectsCase& c, std::ostream* os) { *os << c.name; }

const EffectsCase CASES[] = {
    {"lambertian_only", [] { return family(lambertian({0.7f, 0.4f, 0.3f})); }, {"lambertian", "sky_gradient"}},
    {"mirror_only", [] { return family(metal({0.8f, 0.7f, 0.6f}, 0.0f)); }, {"metal", "sky_gradient"}},
    {"fuzzy_metal_only", [] { return family(metal({0.8f, 0.7f, 0.6f}, 0.3f)); }, {"metal", "fuzzy_metal", "sky_gradient"}},
    {"glass_only", [] { return family(glass(1.5f)); }, {"dielectric", "sky_gradient"}},
    {"mixed_rtiow", [] { return make_rtiow_scene({60, 0.25f, 2}); },
     {"lambertian", "metal", "fuzzy_metal", "dielectric", "defocus", "sky_gradient"}},
    {"emissive_black_sky",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.materials.push_back(emitter({4, 3, 2}));
       s.spheres[1].material = 1;
       s.sky.type = SkyType::None;
       return s;
     },
     {"lambertian", "emissive", "sphere_lights", "sky_none", "sky_black"}},
    {"punctual_lights_only",
     [] {
       Scene s = family(test::pbr(0.8f, 0.0f, 0.5f));
       s.sky.type = SkyType::None;
       Light spot;
       spot.type = LightType::Spot;
       spot.position = {0, 3, 0};
       s.lights = {test::point_light({1, 2, 1}), spot, test::directional_light(glm::normalize(glm::vec3(1, -1, 0)))};
       return s;
     },
     {"pbr", "punctual", "sky_none", "sky_black"}},
    {"sphere_and_punctual_lights_under_sky",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       Material glowing = lambertian(0.5f);
       glowing.emission = {1, 2, 3};
       s.materials.push_back(glowing);
       s.materials.push_back(emitter({40, 30, 20}));
       s.spheres[2].material = 1;
       s.spheres.push_back({{0, 2, 0}, 0.1f, 2});
       s.lights = {test::point_light({1, 2, 1})};
       return s;
     },
     {"lambertian", "emissive", "surface_emission", "sphere_lights", "punctual", "sky_gradient"}},
    {"lens_rtiow", [] { return make_rtiow_scene({60, 0.25f, 3}); },
     {"lambertian", "metal", "fuzzy_metal", "dielectric", "defocus", "sky_gradient"}},
    {"pinhole_rtiow",
     [] {
       Scene s = make_rtiow_scene({60, 0.25f, 3});
       s.camera.aperture = 0;
       return s;
     },
     {"lambertian", "metal", "fuzzy_metal", "dielectric", "sky_gradient"}},
    {"no_light",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.sky.type = SkyType::Uniform;
       s.sky.radiance = glm::vec3(0.0f);
       return s;
     },
     {"lambertian", "sky_uniform", "sky_black", "no_light"}},
    {"unused_glass_material",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.materials.push_back(glass(1.5f));
       return s;
     },
     {"lambertian", "sky_gradient"}},
    {"meshes_flat",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.materials.push_back(glass(1.5f));
       test::place(s, test::icosphere(2, 1), glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.6f, 0.8f)) *
                                                 glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"lambertian", "dielectric", "triangles", "sky_gradient"}},
    {"meshes_smooth_only",
     [] {
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.spheres.clear();
       test::place(s, test::icosphere(2, 0, true), glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.6f, 0)));
       return s;
     },
     {"lambertian", "triangles", "vertex_normals", "sky_gradient"}},
    {"textured_emissive_mesh",
     [] {
       // A smooth icosphere, textured and emitting through a texture, over
       // textured ground spheres (uv 0) under the gradient sky.
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.textures = {{2, 2, {0xff2040c0u, 0xffc08020u, 0xff808080u, 0xff10f010u}, Wrap::Repeat, Wrap::MirroredRepeat}};
       s.materials[0].base_color_texture = 0;
       Material glow = lambertian({0.8f, 0.8f, 0.8f});
       glow.base_color_texture = 0;
       glow.emission = {2.0f, 1.5f, 1.0f};
       glow.emission_texture = 0;
       s.materials.push_back(glow);
       Mesh ball = test::icosphere(2, 1, true);
       for (glm::vec3 p : ball.positions) ball.uvs.push_back({2.0f * p.x, 1.5f * p.y - 0.5f});
       test::place(s, ball, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.6f, 1.2f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"lambertian", "triangles", "vertex_normals", "textures", "surface_emission", "triangle_lights", "sky_gradient"}},
    {"pbr_spheres_and_textured_mesh",
     [] {
       // glTF's material on spheres (metal, dielectric, in between, rough and
       // smooth, emitting) and on a smooth icosphere with base colour,
       // metallic-roughness and normal textures.
       Scene s = family(test::pbr(0.8f, 1.0f, 0.3f));
       s.materials.push_back(test::pbr(0.6f, 0.0f, 0.0f));
       s.materials.push_back(test::pbr(0.9f, 0.5f, 1.0f));
       s.materials[2].emission = {0.5f, 0.25f, 0.0f};
       s.spheres[2].material = 1;
       s.spheres[3].material = 2;
       s.textures = {{2, 2, {0xff2040c0u, 0xffc08020u, 0xff808080u, 0xff10f010u}, Wrap::Repeat, Wrap::Repeat}};
       Material textured = test::pbr(1.0f, 1.0f, 1.0f);
       textured.base_color_texture = 0;
       textured.metallic_roughness_texture = 0;
       // ... and a normal map, through a uv transform.
       textured.normal_texture = 0;
       textured.normal_scale = 0.7f;
       textured.normal_uv = glm::mat3x2(glm::vec2(0.0f, 2.0f), glm::vec2(-1.5f, 0.0f), glm::vec2(0.25f, 0.1f));
       s.materials.push_back(textured);
       Mesh ball = test::icosphere(2, 3, true);
       for (glm::vec3 p : ball.positions) ball.uvs.push_back({2.0f * p.x, 1.5f * p.y - 0.5f});
       test::place(s, ball, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.6f, 1.2f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"pbr", "triangles", "vertex_normals", "textures", "surface_emission", "normal_maps", "sphere_lights", "sky_gradient"}},
    {"alpha_mask_single_sided_and_blend_meshes",
     [] {
       // Two icospheres over the spheres: one MASK through a texture whose
       // alpha varies (cut-outs in camera and bounce rays alike), one BLEND
       // (a stochastic cut-out).
       Scene s = family(lambertian({0.5f, 0.5f, 0.5f}));
       s.textures = {{2, 2, {0x002040c0u, 0xffc08020u, 0x80808080u, 0xff10f010u}, Wrap::Repeat, Wrap::Repeat}};
       Material mask = test::pbr(0.9f, 0.0f, 0.5f);
       mask.base_color_texture = 0;
       mask.alpha_mode = AlphaMode::Mask;
       mask.alpha_cutoff = 0.6f;
       mask.double_sided = false;  // its back faces (inside the ball) are not hit either
       s.materials.push_back(mask);
       Material blend = lambertian({0.8f, 0.3f, 0.3f});
       blend.alpha_mode = AlphaMode::Blend;
       blend.alpha = 0.5f;
       s.materials.push_back(blend);
       Mesh ball = test::icosphere(2, 1);
       for (glm::vec3 p : ball.positions) ball.uvs.push_back({2.0f * p.x, 1.5f * p.y - 0.5f});
       test::place(s, ball, glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.6f, 1.2f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       test::place(s, test::icosphere(2, 2), glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.6f, 1.2f)) *
                                                 glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"lambertian", "pbr", "triangles", "textures", "alpha", "single_sided", "sky_gradient"}},
    {"envmap_sky",
     [] {
       Scene s = family(metal({0.8f, 0.7f, 0.6f}, 0.2f));
       s.sky = test::envmap_sky(test::test_envmap(32, 16, 500.0f), 1.5f, 30.0f);
       return s;
     },
     {"metal", "fuzzy_metal", "sky_light", "sky_envmap"}},
    // The envmap as the only light: NEE compiles sky sampling only.
    {"envmap_sun_lambertian",
     [] {
       Scene s = family(lambertian({0.7f, 0.4f, 0.3f}));
       s.sky = test::envmap_sky(test::test_envmap(32, 16, 2000.0f), 1.0f, 200.0f);
       return s;
     },
     {"lambertian", "sky_light", "sky_envmap"}},
    // The sky and a sphere light in one list, a pbr surface sampling both.
    {"envmap_and_sphere_light",
     [] {
       Scene s = family(test::pbr(0.8f, 0.0f, 0.4f));
       s.materials.push_back(emitter({40, 30, 20}));
       s.spheres.push_back({{0.5f, 1.8f, 0.5f}, 0.1f, 1});
       s.sky = test::envmap_sky(test::test_envmap(32, 16, 2000.0f), 1.0f, 200.0f);
       return s;
     },
     {"emissive", "pbr", "sphere_lights", "sky_light", "sky_envmap"}},
    // Emissive triangles as lights beside a sphere light: one single-sided
    // quad mesh placed twice (two lights per placement), over pbr spheres.
    {"triangle_and_sphere_lights",
     [] {
       Scene s = family(test::pbr(0.8f, 0.0f, 0.4f));
       s.sky.type = SkyType::None;
       s.materials.push_back(emitter({40, 30, 20}));
       s.spheres.push_back({{0.5f, 1.8f, 0.5f}, 0.1f, 1});
       Material panel = emitter({5, 8, 12});
       panel.double_sided = false;
       s.materials.push_back(panel);
       const glm::mat4 down = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));
       s.meshes.push_back(test::grid(1, 2));
       s.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, 2.0f, -0.5f)) * down});
       s.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 1.6f, 0.5f)) * down *
                                     glm::scale(glm::mat4(1.0f), glm::vec3(0.5f))});
       return s;
     },
     {"emissive", "pbr", "triangles", "single_sided", "sphere_lights", "triangle_lights", "sky_none", "sky_black"}},
    {"envmap_strength_0",
     [] {
       Scene s = family(metal({0.8f, 0.7f, 0.6f}, 0.2f));
       s.sky = test::envmap_sky(test::test_envmap(32, 16), 0.0f);
       return s;
     },
     {"metal", "fuzzy_metal", "sky_envmap", "sky_black", "no_light"}},
    {"transmission_solids_and_thin_walled_mesh",
     [] {
       // pbr with transmission: a smooth solid sphere, a rough one that is
       // half diffuse and half metal, and a thin-walled icosphere, over a
       // pbr ground without transmission.
       Scene s = family(test::pbr(0.8f, 0.0f, 0.5f));
       Material clear = test::pbr(1.0f, 0.0f, 0.0f);
       clear.transmission = 1.0f;
       s.materials.push_back(clear);
       Material frosted = test::pbr(0.9f, 0.3f, 0.4f);
       frosted.albedo = {0.9f, 0.6f, 0.4f};
       frosted.transmission = 0.5f;
       frosted.ior = 2.4f;
       s.materials.push_back(frosted);
       Material thin = test::pbr(1.0f, 0.0f, 0.2f);
       thin.transmission = 1.0f;
       thin.thin_walled = true;
       s.materials.push_back(thin);
       s.spheres[1].material = 1;
       s.spheres[2].material = 2;
       test::place(s, test::icosphere(2, 3), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.6f, 1.6f)) *
                                                 glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"pbr", "triangles", "transmission", "sky_gradient"}},
    {"absorbing_solids_transmission_texture_and_tangents",
     [] {
       // Beer-Lambert absorption in two solid spheres (one tinted, one
       // black: sigma +Inf), and a smooth icosphere whose transmission
       // comes through a texture (with a uv transform) and whose normal map
       // takes the mesh's own tangents.
       Scene s = family(test::pbr(0.8f, 0.0f, 0.5f));
       Material tinted = test::pbr(1.0f, 0.0f, 0.1f);
       tinted.transmission = 1.0f;
       tinted.attenuation_color = {0.9f, 0.5f, 0.2f};
       tinted.attenuation_distance = 0.7f;
       s.materials.push_back(tinted);
       Material black = tinted;
       black.attenuation_color = {0.0f, 0.3f, 1.0f};
       s.materials.push_back(black);
       s.spheres[1].material = 1;
       s.spheres[2].material = 2;
       s.textures = {{2, 2, {0xff2040c0u, 0xffc08020u, 0xff808080u, 0xff10f010u}, Wrap::Repeat, Wrap::Repeat}};
       Material frosted = test::pbr(0.9f, 0.0f, 0.3f);
       frosted.transmission = 0.8f;
       frosted.transmission_texture = 0;
       frosted.transmission_uv = glm::mat3x2(glm::vec2(0.0f, 2.0f), glm::vec2(-1.5f, 0.0f), glm::vec2(0.25f, 0.1f));
       frosted.normal_texture = 0;
       s.materials.push_back(frosted);
       Mesh ball = test::icosphere(2, 3, true);
       for (glm::vec3 p : ball.positions) {
         ball.uvs.push_back({2.0f * p.x, 1.5f * p.y - 0.5f});
         ball.tangents.push_back({glm::normalize(glm::vec3(-p.z, 0.1f, p.x)), p.y > 0.0f ? 1.0f : -1.0f});
       }
       test::place(s, ball, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.6f, 1.6f)) *
                                glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)));
       return s;
     },
     {"pbr", "triangles", "vertex_normals", "textures", "normal_maps", "transmission", "absorption", "sky_gradient"}},
    {"every_effect",
     [] {
       // Every effect the pipeline can switch off, on at once: the rtiow
       // materials on spheres through a lens, a sphere light, a punctual
       // light and the envmap's sun as lights, and on smooth icospheres a
       // textured pbr surface that emits through a normal map, a single-sided
       // MASK cut-out, an absorbing transmissive solid, and an emissive
       // single-sided quad (a triangle light).
       Scene s = family(lambertian({0.7f, 0.4f, 0.3f}));
       s.camera.aperture = 0.1f;
       s.camera.focus_dist = 6.0f;
       s.materials.push_back(metal({0.8f, 0.7f, 0.6f}, 0.2f));
       s.materials.push_back(glass(1.5f));
       s.materials.push_back(emitter({40, 30, 20}));
       s.spheres[2].material = 1;
       s.spheres[3].material = 2;
       s.spheres.push_back({{0.5f, 1.8f, 0.5f}, 0.1f, 3});
       s.lights = {test::point_light({1, 2, 1})};
       s.sky = test::envmap_sky(test::test_envmap(32, 16, 2000.0f), 1.0f, 200.0f);
       s.textures = {{2, 2, {0x802040c0u, 0xffc08020u, 0xff808080u, 0xff10f010u}, Wrap::Repeat, Wrap::Repeat}};
       Material textured = test::pbr(1.0f, 1.0f, 1.0f);
       textured.base_color_texture = 0;
       textured.metallic_roughness_texture = 0;
       textured.normal_texture = 0;
       textured.emission = {0.5f, 0.25f, 0.0f};
       s.materials.push_back(textured);  // 4
       Material mask = test::pbr(0.9f, 0.0f, 0.5f);
       mask.base_color_texture = 0;
       mask.alpha_mode = AlphaMode::Mask;
       mask.alpha_cutoff = 0.6f;
       mask.double_sided = false;
       s.materials.push_back(mask);  // 5
       Material tinted = test::pbr(1.0f, 0.0f, 0.1f);
       tinted.transmission = 1.0f;
       tinted.attenuation_color = {0.9f, 0.5f, 0.2f};
       tinted.attenuation_distance = 0.7f;
       s.materials.push_back(tinted);  // 6
       Material panel = emitter({5, 8, 12});
       panel.double_sided = false;
       s.materials.push_back(panel);  // 7
       const glm::mat4 half = glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
       for (auto [material, x] : {std::pair{4u, -1.0f}, {5u, 0.0f}, {6u, 1.0f}}) {
         Mesh ball = test::icosphere(2, material, true);
         for (glm::vec3 p : ball.positions) ball.uvs.push_back({2.0f * p.x, 1.5f * p.y - 0.5f});
         test::place(s, ball, glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.6f, 1.4f)) * half);
       }
       test::place(s, test::grid(1, 7),
                   glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, 2.0f, -0.5f)) *
                       glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0)));
       return s;
     },
     {"lambertian", "metal", "fuzzy_metal", "dielectric", "emissive", "pbr", "defocus", "triangles", "vertex_normals",
      "textures", "surface_emission", "normal_maps", "alpha", "single_sided", "transmission", "absorption",
      "sphere_lights", "punctual", "sky_light", "triangle_lights", "sky_envmap"}},
};

class EffectsTest : public test::VulkanTest, public ::testing::WithParamInterface<EffectsCase> {};

TEST_P(EffectsTest, FeaturesAreDetected) {
  EXPECT_EQ(feature_names(scene_features(GetParam().make())), GetParam().expected);
}

TEST_P(EffectsTest, SpecialisedImageIsBitIdenticalToGeneral) {
  Scene scene = GetParam().make();
  for (Precision precision : {Precision::FP32, Precision::FP16}) {
    RenderSettings s;
    s.width = 48;
    s.height = 32;
    s.spp = 4;
    s.precision = precision;
    s.all_effects = false;
    RenderResult specialised = render(test::shared_context(), scene, s);
    s.all_effects = true;
    RenderResult general = render(test::shared_context(), scene, s);
    ASSERT_EQ(specialised.mean.rgb.size(), general.mean.rgb.size());
    size_t differing = 0;
    for (size_t i = 0; i < general.mean.rgb.size(); ++i)
      differing += std::memcmp(&specialised.mean.rgb[i], &general.mean.rgb[i], sizeof(float)) != 0;
    EXPECT_EQ(differing, 0u) << precision_name(precision) << ": values that differ between --effects auto and all";
    EXPECT_EQ(specialised.nonfinite_samples, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, EffectsTest, ::testing::ValuesIn(CASES),
                         [](const auto& info) { return std::string(info.param.name); });

// On software devices the constants are applied to the SPIR-V before the
// driver sees it (vk/specialize.h); the image is the one the driver's own
// specialisation gives, bit for bit (OCTRACE_SPECIALIZE=0 turns it off).
// Two scenes that between them switch every boolean constant of the scene's
// features both ways but HAS_SPHERES, HAS_LAMBERTIAN and ANY_LIGHT (on in
// both: a scene has a material, every scene here has spheres, and one
// without light renders black, which any module matches) and give SKY two
// of its four values: every_effect has them all on (the envmap sky),
// lambertian_only every other one off (the gradient sky); the auto against
// all test above runs every scene through the specialised module. Each
// driver-specialised pipeline is the whole path tracer translated by
// llvmpipe, whatever the scene: 51-69 s for each of seven small scenes
// alone (the ahead-of-driver module included), every_effect 121 s, on a
// 2-core machine of 2026-12-06 with a cold shader cache (lambertian_only
// 59 s; about a second when this test was written, before the glTF
// materials, NEE, the envmap and the tail queue), so each scene is a test
// of its own, which ctest runs beside the others. Six scenes were 322 s of
// a cold suite's process time, three (with mixed_rtiow and
// triangle_and_sphere_lights, which also switched HAS_LAMBERTIAN and gave
// SKY a third value) 235 s.
const char* const AHEAD_OF_DRIVER_SCENES[] = {"every_effect", "lambertian_only"};

class AheadOfDriverTest : public test::VulkanTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(AheadOfDriverTest, SpecialisationIsBitIdentical) {
  const auto c = std::find_if(std::begin(CASES), std::end(CASES),
                              [&](const EffectsCase& e) { return std::string(e.name) == GetParam(); });
  ASSERT_NE(c, std::end(CASES)) << GetParam() << " is not a scene of CASES";
  Scene scene = c->make();
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.spp = 4;
  setenv("OCTRACE_SPECIALIZE", "1", 1);
  RenderResult ahead = render(test::shared_context(), scene, s);
  setenv("OCTRACE_SPECIALIZE", "0", 1);
  RenderResult driver = render(test::shared_context(), scene, s);
  unsetenv("OCTRACE_SPECIALIZE");
  ASSERT_EQ(ahead.mean.rgb.size(), driver.mean.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < driver.mean.rgb.size(); ++i)
    differing += std::memcmp(&ahead.mean.rgb[i], &driver.mean.rgb[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << c->name << ": values that differ between the specialised module and the driver's";
}

INSTANTIATE_TEST_SUITE_P(Scenes, AheadOfDriverTest, ::testing::ValuesIn(AHEAD_OF_DRIVER_SCENES),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace octrace
