// Textures and emission as the renderer draws them: glTF's uv origin at the
// image's top-left, sRGB decoded exactly, bilinear filtering in linear colour,
// each wrap mode, emission = factor x texture x strength, and a lambertian
// emitter that still reflects. The set-ups make every pixel exact rather than
// noisy: quads facing a pinhole camera under a uniform sky (radiance 1) or a
// black one, so that a path scatters once off the quad's plane and never meets
// it again: a pixel is albedo x 1 (plus the emission), or the emission alone.
#include <cmath>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/gltf.h"
#include "scene/gltf_builder.h"
#include "test_util.h"

namespace octrace {
namespace {

class TextureTest : public test::VulkanTest {};

// The sRGB EOTF (IEC 61966-2-1) of an 8-bit value, in double.
double srgb(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Largest error allowed for a colour of about 1 in each precision: fp32
// (rounding and the GPU's pow), half (2^-11 relative, twice).
float tolerance(Precision p) { return p == Precision::FP32 ? 1e-5f : 2e-3f; }

const Precision kPrecisions[] = {Precision::FP32, Precision::FP16, Precision::FP16All};

// A pinhole camera looking down -z at the rectangle [0, w] x [0, h] of the
// plane z = 0, which fills an image of 8 pixels per unit exactly.
void frame(Scene& s, float w, float h) {
  const float distance = 10.0f;
  s.camera.lookfrom = {w / 2, h / 2, distance};
  s.camera.lookat = {w / 2, h / 2, 0};
  s.camera.vup = {0, 1, 0};
  s.camera.vfov = float(glm::degrees(2.0 * std::atan(0.5 * h / distance)));
  s.camera.aperture = 0;
  s.camera.focus_dist = distance;
}

RenderResult render_framed(const Scene& s, float w, float h, Precision precision, uint32_t spp = 1) {
  RenderSettings settings;
  settings.width = int(8 * w);
  settings.height = int(8 * h);
  settings.spp = spp;
  settings.precision = precision;
  RenderResult r = render(test::shared_context(), s, settings);
  EXPECT_EQ(r.nonfinite_samples, 0u);
  return r;
}

// The pixel that shows the point (x, y) of the plane (see frame()).
glm::vec3 at(const RenderResult& r, float x, float y) {
  const int px = int(8 * x), py = r.mean.height - 1 - int(8 * y);
  const float* p = &r.mean.rgb[3 * (size_t(py) * size_t(r.mean.width) + size_t(px))];
  return {p[0], p[1], p[2]};
}

void expect_near(glm::vec3 got, glm::dvec3 want, float tol, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << ", channel " << c;
}

// Renders the unit quad of `s` (framed 1 x 1) in every precision and checks
// the colour seen near each corner: top left, top right, bottom left,
// bottom right.
void expect_corners(const Scene& s, const glm::dvec3 (&want)[4]) {
  for (Precision p : kPrecisions) {
    const RenderResult r = render_framed(s, 1, 1, p);
    const std::string name = precision_name(p);
    expect_near(at(r, 0.1f, 0.9f), want[0], tolerance(p), name + " top left");
    expect_near(at(r, 0.9f, 0.9f), want[1], tolerance(p), name + " top right");
    expect_near(at(r, 0.1f, 0.1f), want[2], tolerance(p), name + " bottom left");
    expect_near(at(r, 0.9f, 0.1f), want[3], tolerance(p), name + " bottom right");
  }
}

Scene uniform_sky() {
  Scene s;
  s.sky.type = SkyType::Uniform;
  s.sky.radiance = glm::vec3(1.0f);
  return s;
}

// A quad (x, y) .. (x + 1, y + 1) on z = 0 facing +z, every vertex at the same
// uv: each of its pixels samples the texture at exactly that point.
void add_uv_quad(Mesh& m, float x, float y, glm::vec2 uv, uint32_t material) {
  const auto base = uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), {{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
  m.uvs.insert(m.uvs.end(), 4, uv);
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  m.materials.insert(m.materials.end(), 2, material);
}

// glTF files load as pbr materials, whose specular layer makes a pixel
// noisy; these tests check the textures, which shade a lambertian material
// the same way, exactly.
Scene as_lambertian(Scene s) {
  for (Material& m : s.materials) m.type = MaterialType::Lambertian;
  return s;
}

Material textured(uint32_t texture) {
  Material m = test::lambertian(1.0f);
  m.base_color_texture = texture;
  return m;
}

// A 2x2 image of four colours on the glTF quad (uv (0, 0) at its top-left
// corner as seen from +z): each corner of the render shows its texel, so the
// image is neither flipped nor mirrored. Clamped, so that the corners are
// the texels alone rather than blends with the opposite edge.
TEST_F(TextureTest, UvOriginIsTheImagesTopLeft) {
  const std::string png = test::png(2, 2, {255, 0, 0, 255, 0, 255, 0, 255,       // top: red, green
                                           0, 0, 255, 255, 255, 255, 255, 255});  // bottom: blue, white
  const std::string path = test::tmp_path("texture_orientation.glb");
  test::textured_quad_gltf(png, test::kClampToEdge, test::kClampToEdge).write(path);
  Scene s = as_lambertian(load_gltf_scene(path));
  s.sky = uniform_sky().sky;
  frame(s, 1, 1);
  expect_corners(s, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}});
}

// KHR_texture_transform on the same quad and image: offset (1, -1), rotation
// pi/2, scale (2, 1), applied as uv' = T R S uv (the rotation counter-clockwise
// in uv space). The corners then sample (0.8, 0.2) green, (0.8, 1.8) white,
// (-0.8, 0.2) red and (-0.8, 1.8) blue, clamped to the image's corners. The
// transform left out, or any one part of it, or the rotation the other way,
// or S and R swapped, shows another pattern.
TEST_F(TextureTest, TextureTransformOffsetsRotatesAndScalesTheUvs) {
  const std::string png = test::png(2, 2, {255, 0, 0, 255, 0, 255, 0, 255,       // top: red, green
                                           0, 0, 255, 255, 255, 255, 255, 255});  // bottom: blue, white
  test::GltfBuilder b = test::textured_quad_gltf(png, test::kClampToEdge, test::kClampToEdge);
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {1, -1}}, {"rotation", 1.5707963267948966}, {"scale", {2, 1}}}}};
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  b.doc["extensionsRequired"] = {"KHR_texture_transform"};
  const std::string path = test::tmp_path("texture_transform.gltf");
  b.write(path);
  std::vector<std::string> warnings;
  GltfOptions opts;
  opts.warn = [&](const std::string& w) { warnings.push_back(w); };
  Scene s = as_lambertian(load_gltf_scene(path, opts));
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  s.sky = uniform_sky().sky;
  frame(s, 1, 1);
  expect_corners(s, {{0, 1, 0}, {1, 1, 1}, {1, 0, 0}, {0, 0, 1}});
}

// The mean of the pixels of the unit square at (x, 0) of a render framed by frame().
glm::dvec3 mean_over(const RenderResult& r, int x) {
  glm::dvec3 mean(0.0);
  for (int py = 0; py < 8; ++py)
    for (int px = 8 * x; px < 8 * x + 8; ++px)
      for (int c = 0; c < 3; ++c) mean[c] += r.mean.rgb[3 * (size_t(py) * size_t(r.mean.width) + size_t(px)) + c];
  return mean / 64.0;
}

// What a lambertian of albedo 1 facing +z shows under the gradient sky when
// its shading normal has y component `ny` (see NormalMapTiltsTheShadingNormal).
glm::dvec3 gradient_sky_mean(double ny) {
  const double f = 0.5 * (2.0 / 3.0 * ny + 1.0);
  return (1.0 - f) * glm::dvec3(1.0) + f * glm::dvec3(0.5, 0.7, 1.0);
}

// The unit tangent-space normal of a normal map's texel (glTF 3.9.4).
glm::dvec3 texel_normal(int r, int g, int b) {
  return glm::normalize(glm::dvec3(2 * r / 255.0 - 1, 2 * g / 255.0 - 1, 2 * b / 255.0 - 1));
}

// A normal map tilts the shading normal. The quad (facing +z, u along +x, v
// along -y) under the gradient sky (dir.y = -1 white, +1 (0.5, 0.7, 1)),
// lambertian of albedo 1: a path scatters once, cosine-weighted about the
// shading normal n, whose mean direction is 2/3 n (directions below the
// quad are mirrored across it, which keeps their y), and the sky is linear
// in dir.y: a pixel's mean is the sky at dir.y = 2/3 n.y. A map of texels
// (128, 128, 255) leaves n about +z; one of (128, 218, 218) tilts it 45
// degrees towards the texel's +Y, "up" in the image (glTF 3.9.4), which is
// -v, +y on the quad, where the sky is bluer.
TEST_F(TextureTest, NormalMapTiltsTheShadingNormal) {
  for (const auto& [r, g, b] : {std::tuple{128, 128, 255}, std::tuple{128, 218, 218}}) {
    const std::string png = test::png(1, 1, {uint8_t(r), uint8_t(g), uint8_t(b), 255});
    test::GltfBuilder builder = test::textured_quad_gltf(png);
    builder.doc["materials"][0] = {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}, {"normalTexture", {{"index", 0}}}};
    const std::string path = test::tmp_path("normal_map.gltf");
    builder.write(path);
    Scene s = as_lambertian(load_gltf_scene(path));
    frame(s, 1, 1);
    // The texel's +Y is up in the image: -v, which is +y.
    const glm::dvec3 want = gradient_sky_mean(texel_normal(r, g, b).y);
    for (Precision p : kPrecisions) {
      const RenderResult res = render_framed(s, 1, 1, p, 256);
      // 16384 samples of a sky colour whose spread is under 0.25: 4 sigma < 0.008.
      expect_near(glm::vec3(mean_over(res, 0)), want, 0.008f,
                  std::string(precision_name(p)) + " texel g " + std::to_string(g));
    }
  }
}

// The quad of NormalMapTiltsTheShadingNormal with vertex normals (+z) and a
// TANGENT attribute (glTF 3.7.2.1) whose frame is not the uvs' (T = +x, B =
// +y): the map follows the file's. A texel tilted along the tangent's +X
// by a tangent along +y tilts the normal up (the uvs' frame: sideways,
// where the gradient sky does not change); a texel tilted along +Y with w =
// -1 tilts it down (bitangent = cross(normal, tangent) * w = -y; the uvs':
// up), and with w = +1 up, as the uvs' frame does. Placed by `nodes` (a
// translation and scale each: the second mirrors its quad onto [1, 2] x
// [0, 1], where the bitangent must stay where the mirror puts it, -y for w
// = -1, rather than flip with the mirrored cross product): one node is baked
// into world space (render/gpu_scene.cpp), two share the mesh as instances.
Scene tangent_quad(glm::vec4 tangent, std::tuple<int, int, int> texel, int nodes) {
  const auto [r, g, b] = texel;
  test::GltfBuilder builder;
  const int positions = builder.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const int normals = builder.add_vec3(std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
  const int uvs = builder.add_vec2({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int tangents =
      builder.add_accessor(builder.add_view(std::vector<glm::vec4>(4, tangent)), test::kFloat, 4, "VEC4");
  const int indices = builder.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  const int texture = builder.add_texture(test::png(1, 1, {uint8_t(r), uint8_t(g), uint8_t(b), 255}));
  builder.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}, {"normalTexture", {{"index", texture}}}});
  builder.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", positions},
                                                          {"NORMAL", normals},
                                                          {"TEXCOORD_0", uvs},
                                                          {"TANGENT", tangents}}},
                                          {"indices", indices},
                                          {"material", 0}}}}});
  builder.add("nodes", {{"mesh", 0}});
  if (nodes == 2) builder.add("nodes", {{"mesh", 0}, {"translation", {2, 0, 0}}, {"scale", {-1, 1, 1}}});
  builder.set_scene(nodes == 2 ? std::vector<int>{0, 1} : std::vector<int>{0});
  const std::string path = test::tmp_path("tangent_quad.gltf");
  builder.write(path);
  Scene s = as_lambertian(load_gltf_scene(path));
  frame(s, float(nodes), 1);
  return s;
}

TEST_F(TextureTest, NormalMapsFollowTheFilesTangents) {
  const std::tuple<int, int, int> along_x{218, 128, 218}, along_y{128, 218, 218};
  const double tilt = texel_normal(128, 218, 218).y;  // = texel_normal(218, 128, 218).x
  struct Case {
    glm::vec4 tangent;
    std::tuple<int, int, int> texel;
    double ny;  // the shading normal's y
    const char* what;
  };
  const Case cases[] = {{{0, 1, 0, 1}, along_x, tilt, "tangent +y, texel +X"},
                        {{1, 0, 0, -1}, along_y, -tilt, "tangent +x, w -1, texel +Y"},
                        {{1, 0, 0, 1}, along_y, tilt, "tangent +x, w +1, texel +Y"}};
  for (const Case& c : cases) {
    const Scene s = tangent_quad(c.tangent, c.texel, 1);
    // The frame is worked out in fp32 in every variant: the half ones once, for the case where w matters.
    for (Precision p : kPrecisions) {
      if (p != Precision::FP32 && c.tangent.w > 0.0f) continue;
      expect_near(glm::vec3(mean_over(render_framed(s, 1, 1, p, 256), 0)), gradient_sky_mean(c.ny), 0.008f,
                  std::string(precision_name(p)) + " " + c.what);
    }
  }
  const Scene s = tangent_quad({1, 0, 0, -1}, along_y, 2);
  const RenderResult r = render_framed(s, 2, 1, Precision::FP32, 256);
  expect_near(glm::vec3(mean_over(r, 0)), gradient_sky_mean(-tilt), 0.008f, "instance");
  expect_near(glm::vec3(mean_over(r, 1)), gradient_sky_mean(-tilt), 0.008f, "mirrored instance");
}

// A mirrored placement baked into world space (a mesh placed once) keeps the
// bitangent where the mirror puts it too.
TEST_F(TextureTest, BakedMirroredMeshKeepsTheFilesBitangent) {
  Scene s = tangent_quad({1, 0, 0, -1}, {128, 218, 218}, 1);
  s.instances[0].transform = glm::scale(glm::translate(glm::mat4(1.0f), {1, 0, 0}), {-1, 1, 1});
  expect_near(glm::vec3(mean_over(render_framed(s, 1, 1, Precision::FP32, 256), 0)),
              gradient_sky_mean(-texel_normal(128, 218, 218).y), 0.008f, "baked mirror");
}

// KHR_materials_transmission's transmissionTexture: its red channel,
// linear, times the factor, through its own uv transform. A thin-walled
// (no KHR_materials_volume) smooth quad of ior 1 (F0 = 0: nothing reflected
// head-on) with base colour 1 in front of an emitting quad of radiance 1,
// under a black sky: light passes straight through with probability t and
// is otherwise diffused toward the camera's side, where nothing shines, so
// a pixel's expectation is t. The texture's two texels have red 255 (t = 1)
// and 64 (t = 0.251 read as linear; 0.051 if it were decoded as sRGB), and
// the uv transform mirrors u (scale -1, offset 1): the quad's left quarter
// shows the second texel, its right quarter the first (clamped: no blend).
// 16 pixels x 256 samples of 0 or ~1 each side: 5 sigma <= 0.035.
TEST_F(TextureTest, TransmissionTextureScalesTransmissionByItsRedChannel) {
  test::GltfBuilder b = test::textured_quad_gltf(test::png(2, 1, {255, 0, 0, 255, 64, 255, 255, 255}),
                                                 test::kClampToEdge, test::kClampToEdge);
  nlohmann::json texture = {{"index", 0}};
  texture["extensions"]["KHR_texture_transform"] = {{"offset", {1, 0}}, {"scale", {-1, 1}}};
  b.doc["materials"][0] = {{"pbrMetallicRoughness", {{"metallicFactor", 0}, {"roughnessFactor", 0}}}};
  b.doc["materials"][0]["extensions"]["KHR_materials_ior"] = {{"ior", 1.0}};
  b.doc["materials"][0]["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1},
                                                                       {"transmissionTexture", texture}};
  Scene s = load_gltf_scene(b.write(test::tmp_path("transmission_texture.gltf")));
  s.sky.type = SkyType::None;
  s.materials.push_back(test::emitter(glm::vec3(1.0f)));
  Mesh behind;
  add_uv_quad(behind, 0, 0, glm::vec2(0.0f), uint32_t(s.materials.size() - 1));
  test::place(s, behind, glm::translate(glm::mat4(1.0f), {-1, -1, -1}) * glm::scale(glm::mat4(1.0f), {3, 3, 1}));
  frame(s, 1, 1);
  for (Precision p : {Precision::FP32, Precision::FP16}) {
    const RenderResult r = render_framed(s, 1, 1, p, 256);
    for (const auto& [x0, want, what] : {std::tuple{0, 64.0 / 255.0, "left (red 64)"},
                                         std::tuple{6, 1.0, "right (red 255)"}}) {
      double mean = 0;
      for (int y = 0; y < 8; ++y)
        for (int x = x0; x < x0 + 2; ++x) mean += r.mean.pixel(x, y)[1] / 16.0;
      EXPECT_NEAR(mean, want, 0.035) << precision_name(p) << " " << what;
    }
  }
}

// A texel of 128 is 0.2158605 in linear colour (the exact EOTF; the 2.2 power
// gives 0.2176, a texel used as it is 0.502), here as the albedo under a sky
// of radiance 1.
TEST_F(TextureTest, SrgbTexelsAreDecodedWithTheExactCurve) {
  Scene s = uniform_sky();
  Mesh m;
  add_uv_quad(m, 0, 0, {0.5f, 0.5f}, 0);
  test::place(s, m);
  s.textures = {{1, 1, {0xff0a8040u}, Wrap::Repeat, Wrap::Repeat}};  // r 64, g 128, b 10
  s.materials = {textured(0)};
  frame(s, 1, 1);
  for (Precision p : kPrecisions)
    expect_near(at(render_framed(s, 1, 1, p), 0.5f, 0.5f), {srgb(64), srgb(128), srgb(10)}, tolerance(p),
                precision_name(p));
}

// Halfway between a black and a white texel is 0.5 in linear colour: texels
// are decoded before they are blended (blending the sRGB values would give 0.214).
TEST_F(TextureTest, BilinearFilteringBlendsInLinearColour) {
  Scene s = uniform_sky();
  Mesh m;
  add_uv_quad(m, 0, 0, {0.5f, 0.5f}, 0);   // midway between the two texel centres
  add_uv_quad(m, 1, 0, {0.375f, 0.5f}, 0);  // a quarter of the way
  test::place(s, m);
  s.textures = {{2, 1, {0xff000000u, 0xffffffffu}, Wrap::ClampToEdge, Wrap::ClampToEdge}};
  s.materials = {textured(0)};
  frame(s, 2, 1);
  const RenderResult r = render_framed(s, 2, 1, Precision::FP32);
  expect_near(at(r, 0.5f, 0.5f), glm::dvec3(0.5), 1e-5f, "midpoint");
  expect_near(at(r, 1.5f, 0.5f), glm::dvec3(0.25), 1e-5f, "quarter");
}

// Each wrap mode at coordinates outside [0, 1], along u and v at once: a 4x4
// texture whose red grows with x and green with y (bytes 0, 85, 170, 255),
// sampled at uv = (c, c) on a row of quads per wrap mode, one quad per c.
// A last row mirrors along u and clamps along v (as BoxTextured does), which
// tells the two axes apart.
TEST_F(TextureTest, WrapModesRepeatClampAndMirror) {
  const int bytes[4] = {0, 85, 170, 255};
  Texture t{4, 4, {}, Wrap::Repeat, Wrap::Repeat};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) t.texels.push_back(0xff000000u | uint32_t(bytes[y]) << 8 | uint32_t(bytes[x]));
  const double lin[4] = {srgb(0), srgb(85), srgb(170), srgb(255)};
  // Texel centres lie at 0.125, 0.375, 0.625, 0.875.
  const float coords[5] = {0.375f, 1.125f, -0.375f, 1.0f, 2.375f};
  struct Row {
    Wrap s, t;
    double expected[5];  // linear value along an axis of that wrap, per coordinate
  };
  const double seam = 0.5 * (lin[3] + lin[0]);  // REPEAT at 1.0: halfway between the last texel and the first
  const Row rows[] = {
      {Wrap::Repeat, Wrap::Repeat, {lin[1], lin[0], lin[2], seam, lin[1]}},
      {Wrap::ClampToEdge, Wrap::ClampToEdge, {lin[1], lin[3], lin[0], lin[3], lin[3]}},
      {Wrap::MirroredRepeat, Wrap::MirroredRepeat, {lin[1], lin[3], lin[1], lin[3], lin[1]}},
  };
  Scene s = uniform_sky();
  Mesh m;
  for (size_t r = 0; r < 4; ++r) {
    Texture tr = t;
    tr.wrap_s = r < 3 ? rows[r].s : Wrap::MirroredRepeat;
    tr.wrap_t = r < 3 ? rows[r].t : Wrap::ClampToEdge;
    s.textures.push_back(tr);
    s.materials.push_back(textured(uint32_t(r)));
    for (int c = 0; c < 5; ++c) add_uv_quad(m, float(c), float(r), glm::vec2(coords[c]), uint32_t(r));
  }
  test::place(s, m);
  frame(s, 5, 4);
  const RenderResult r = render_framed(s, 5, 4, Precision::FP32);
  const char* names[] = {"REPEAT", "CLAMP_TO_EDGE", "MIRRORED_REPEAT"};
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 5; ++c) {
      const double u = row < 3 ? rows[row].expected[c] : rows[2].expected[c];
      const double v = row < 3 ? rows[row].expected[c] : rows[1].expected[c];
      expect_near(at(r, c + 0.5f, row + 0.5f), {u, v, 0}, 1e-5f,
                  std::string(row < 3 ? names[row] : "MIRRORED_REPEAT along u, CLAMP_TO_EDGE along v") + " at " +
                      std::to_string(coords[c]));
    }
}

// A glTF quad with emissiveFactor (1, 0.5, 0.25), emissiveStrength 4 and an
// emissive texture seen under a black sky: every pixel is the emission (the
// pbr material as loaded); under a sky of radiance 1 the surface also
// reflects it (shaded lambertian, albedo 0.5, for an exact pixel).
TEST_F(TextureTest, EmissionIsFactorTimesTextureTimesStrengthAndTheSurfaceStillReflects) {
  test::GltfBuilder b = test::textured_quad_gltf(test::png(1, 1, {255, 128, 64, 255}));
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  nlohmann::json& m = b.doc["materials"][0];
  m["pbrMetallicRoughness"] = {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0}};
  m["emissiveFactor"] = {1, 0.5, 0.25};
  m["emissiveTexture"] = {{"index", 0}};
  m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}};
  const std::string path = b.write(test::tmp_path("texture_emission.glb"));
  Scene s = load_gltf_scene(path);
  s.sky.type = SkyType::None;
  frame(s, 1, 1);
  EXPECT_EQ(feature_names(scene_features(s)),
            (std::vector<std::string>{"pbr", "triangles", "textures", "surface_emission", "single_sided",
                                      "triangle_lights", "sky_none", "sky_black"}));
  const glm::dvec3 emission(4 * srgb(255), 2 * srgb(128), 1 * srgb(64));
  for (Precision p : kPrecisions) {
    const RenderResult r = render_framed(s, 1, 1, p);
    expect_near(at(r, 0.5f, 0.5f), emission, 4 * tolerance(p), std::string(precision_name(p)) + " black sky");
  }
  s = as_lambertian(s);
  s.sky = uniform_sky().sky;
  const RenderResult lit = render_framed(s, 1, 1, Precision::FP32);
  expect_near(at(lit, 0.5f, 0.5f), emission + glm::dvec3(0.5), 4e-5f, "under a sky of 1");
}

// The metallic-roughness texture is linear data, blue = metallic, green =
// roughness, times the factors (1 here). Quads facing a pinhole camera under
// a sky of radiance 1, each sampling one texel (alpha clamped to 1e-3 for
// roughness 0: a mirror to 1e-3):
//   black base, texel (0, 0, 255): a black mirror metal, F0 = 0: black;
//   black base, texel (0, 0, 0):   a dielectric mirror: F0 = 0.04 (ior 1.5),
//                                  and the red channel is not read either;
//   white base, texel (0, 0, 255): a white mirror metal: 1;
//   white base, texel (0, 255, 255): a white metal of roughness 1, whose
//                                  albedo at normal view is 0.31: < 0.5.
TEST_F(TextureTest, MetallicRoughnessTextureIsBlueMetalGreenRoughness) {
  Scene s = uniform_sky();
  s.textures = {{4, 1, {0xffff0000u, 0xff000000u, 0xff0000ffu, 0xffffff00u}, Wrap::ClampToEdge, Wrap::ClampToEdge}};
  for (float base : {0.0f, 1.0f}) {
    Material m = test::pbr(base, 1.0f, 1.0f);
    m.metallic_roughness_texture = 0;
    s.materials.push_back(m);
  }
  Mesh quads;
  add_uv_quad(quads, 0, 0, {0.125f, 0.5f}, 0);  // black, (0, 0, 255)
  add_uv_quad(quads, 1, 0, {0.375f, 0.5f}, 0);  // black, (0, 0, 0)
  add_uv_quad(quads, 2, 0, {0.625f, 0.5f}, 0);  // black, (255, 0, 0)
  add_uv_quad(quads, 3, 0, {0.125f, 0.5f}, 1);  // white, (0, 0, 255)
  add_uv_quad(quads, 4, 0, {0.875f, 0.5f}, 1);  // white, (0, 255, 255)
  test::place(s, quads);
  frame(s, 5, 1);
  for (Precision p : kPrecisions) {
    const RenderResult r = render_framed(s, 5, 1, p, 16);
    const std::string name = precision_name(p);
    expect_near(at(r, 0.5f, 0.5f), glm::dvec3(0.0), 1e-3f, name + " black mirror metal");
    expect_near(at(r, 1.5f, 0.5f), glm::dvec3(0.04), 1e-3f, name + " dielectric mirror");
    expect_near(at(r, 2.5f, 0.5f), glm::dvec3(0.04), 1e-3f, name + " dielectric mirror, red texel");
    expect_near(at(r, 3.5f, 0.5f), glm::dvec3(1.0), 2e-3f, name + " white mirror metal");
    EXPECT_LT(at(r, 4.5f, 0.5f).g, 0.5f) << name << " white rough metal";
  }
}

// The texels of a scene go into one storage buffer: more than the device
// allows is refused in one line naming them (lavapipe allows 128 MiB).
TEST_F(TextureTest, TexelsBeyondOneStorageBufferAreRefused) {
  const uint64_t limit = test::shared_context().limits.maxStorageBufferRange;
  if (limit > (uint64_t(1) << 28)) GTEST_SKIP() << "the device allows " << limit << " bytes per buffer";
  const uint32_t side = uint32_t(std::sqrt(double(limit / 4))) + 1;
  Scene s = uniform_sky();
  Mesh m;
  add_uv_quad(m, 0, 0, {0.5f, 0.5f}, 0);
  test::place(s, m);
  s.textures = {{side, side, std::vector<uint32_t>(size_t(side) * side), Wrap::Repeat, Wrap::Repeat}};
  s.materials = {textured(0)};
  frame(s, 1, 1);
  const std::string message = test::input_error([&] { render_framed(s, 1, 1, Precision::FP32); });
  EXPECT_EQ(message.rfind("the texels of 1 texture need ", 0), 0u) << message;
  EXPECT_NE(message.find(" per buffer"), std::string::npos) << message;
}

// glTF's alpha: a quad whose material cuts it out (MASK or BLEND) in front
// of a large quad at z = -1 that emits `behind` (and so shows it exactly).
// A camera ray through the cut-out part meets the quad behind; one that hits
// the front quad scatters to +z, where only the uniform sky is.
Scene alpha_scene(const test::GltfBuilder& b, const std::string& name, glm::vec3 behind) {
  const std::string path = test::tmp_path(name);
  b.write(path);
  Scene s = as_lambertian(load_gltf_scene(path));
  s.sky = uniform_sky().sky;
  Material glow;
  glow.type = MaterialType::Emissive;
  glow.radiance = behind;
  s.materials.push_back(glow);
  Mesh back;
  back.positions = {{-5, -5, -1}, {6, -5, -1}, {6, 6, -1}, {-5, 6, -1}};
  back.indices = {0, 1, 2, 0, 2, 3};
  back.materials = {uint32_t(s.materials.size() - 1), uint32_t(s.materials.size() - 1)};
  test::place(s, back);
  frame(s, 1, 1);
  return s;
}

// MASK: a texture of two halves, alpha 0 (left, red) and 1 (right, white):
// the left half shows the quad behind, exactly, in camera rays; the right
// half is the texel's colour under the sky.
TEST_F(TextureTest, MaskCutsOutTexelsBelowTheCutoff) {
  const std::string png = test::png(2, 1, {255, 0, 0, 0, 255, 255, 255, 255});
  test::GltfBuilder b = test::textured_quad_gltf(png, test::kClampToEdge, test::kClampToEdge);
  b.doc["materials"][0]["alphaMode"] = "MASK";
  const Scene s = alpha_scene(b, "alpha_mask.gltf", {0.2f, 0.4f, 0.6f});
  ASSERT_TRUE(scene_features(s).alpha);
  for (Precision p : kPrecisions) {
    const RenderResult r = render_framed(s, 1, 1, p);
    const std::string name = precision_name(p);
    expect_near(at(r, 0.1f, 0.5f), {0.2, 0.4, 0.6}, tolerance(p), name + " cut-out half");
    expect_near(at(r, 0.4f, 0.2f), {0.2, 0.4, 0.6}, tolerance(p), name + " cut-out half");
    expect_near(at(r, 0.9f, 0.5f), {1, 1, 1}, tolerance(p), name + " opaque half");
    expect_near(at(r, 0.8f, 0.8f), {1, 1, 1}, tolerance(p), name + " opaque half");
  }
  // OPAQUE (the same file without alphaMode) hides the quad behind.
  b.doc["materials"][0].erase("alphaMode");
  const Scene opaque = alpha_scene(b, "alpha_opaque.gltf", {0.2f, 0.4f, 0.6f});
  EXPECT_FALSE(scene_features(opaque).alpha);
  expect_near(at(render_framed(opaque, 1, 1, Precision::FP32), 0.1f, 0.5f), {srgb(255), 0, 0}, 1e-5f, "opaque");
}

// BLEND with alpha 0.5 (baseColorFactor.a, no texture), white, in front of a
// black emitter: a sample is 1 where the stochastic cut-out keeps the quad,
// 0 where it lets the ray through, so the image's mean is the coverage.
// 64 pixels x 256 samples of a Bernoulli(0.5) (independent: hashed per
// pixel and sample): standard deviation 0.5 / sqrt(16384) = 0.0039; the
// bound is 5 of them.
TEST_F(TextureTest, BlendIsAStochasticCutOutWithCoverageAlpha) {
  test::GltfBuilder b = test::quad_gltf();
  b.add("materials", {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.5}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  const Scene s = alpha_scene(b, "alpha_blend.gltf", glm::vec3(0.0f));
  const RenderResult r = render_framed(s, 1, 1, Precision::FP32, 256);
  double sum = 0;
  for (size_t i = 0; i < r.mean.rgb.size(); i += 3) {
    EXPECT_EQ(r.mean.rgb[i], r.mean.rgb[i + 1]);
    sum += r.mean.rgb[i];
  }
  const double coverage = sum / double(r.mean.rgb.size() / 3);
  EXPECT_NEAR(coverage, 0.5, 5 * 0.0039);
  // And it is deterministic: the same render again is the same image.
  EXPECT_EQ(render_framed(s, 1, 1, Precision::FP32, 256).mean.rgb, r.mean.rgb);
}

// doubleSided false (glTF's default): a quad wound to face -z, seen from +z,
// shows its back face, which is not hit: the quad behind shows through.
// doubleSided true: the quad is hit (white under the sky).
TEST_F(TextureTest, SingleSidedBackFacesAreNotHit) {
  test::GltfBuilder b = test::quad_gltf();
  const int flipped = b.add_indices(std::vector<uint16_t>{0, 2, 1, 0, 3, 2});
  b.doc["meshes"][0]["primitives"][0]["indices"] = flipped;
  b.add("materials", {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  const Scene single = alpha_scene(b, "single_sided.gltf", {0.2f, 0.4f, 0.6f});
  EXPECT_TRUE(scene_features(single).single_sided);
  b.doc["materials"][0]["doubleSided"] = true;
  const Scene both = alpha_scene(b, "double_sided.gltf", {0.2f, 0.4f, 0.6f});
  EXPECT_FALSE(scene_features(both).single_sided);
  for (Precision p : kPrecisions) {
    const std::string name = precision_name(p);
    expect_near(at(render_framed(single, 1, 1, p), 0.5f, 0.5f), {0.2, 0.4, 0.6}, tolerance(p), name + " single-sided");
    expect_near(at(render_framed(both, 1, 1, p), 0.5f, 0.5f), {1, 1, 1}, tolerance(p), name + " double-sided");
  }
}

}  // namespace
}  // namespace octrace
