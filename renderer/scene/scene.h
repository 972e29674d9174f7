// The scene as plain CPU structs: what the renderer draws, independent of Vulkan.
// Sources: the built-in `rtiow` generator, the JSON format (README "Scene
// format") and glTF files (scene/gltf.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x2.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace octrace {

// Values match the MAT_* constants in shaders/shared/shared.h (static_assert in render/gpu_layout.h).
// Lambertian, Metal, Dielectric and Emissive are the materials of "Ray
// Tracing in One Weekend"; Pbr is glTF 2.0's metallic-roughness material
// (Appendix B; shaders/shading/pbr.glsl).
enum class MaterialType : uint32_t { Lambertian = 0, Metal = 1, Dielectric = 2, Emissive = 3, Pbr = 4 };

// glTF's alpha modes (3.9.6). Values match the ALPHA_* constants in
// shaders/shared/shared.h (static_assert in render/gpu_layout.h).
enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

struct Material {
  MaterialType type = MaterialType::Lambertian;
  glm::vec3 albedo{0.5f};    // lambertian, metal; pbr: the base colour
  float fuzz = 0.0f;         // metal
  float ior = 1.5f;          // dielectric; pbr: of the dielectric layer (F0 = ((ior - 1) / (ior + 1))^2)
  glm::vec3 radiance{0.0f};  // emissive
  // Lambertian and pbr only. From glTF files (JSON materials have none): the
  // albedo is multiplied by this texture (its rgb decoded from sRGB) at the
  // surface's uv (glTF's baseColorTexture) ...
  std::optional<uint32_t> base_color_texture;  // index into Scene::textures
  // ... and the surface emits `emission` (times this texture, sRGB) besides
  // reflecting, as a glTF surface with an emissive factor does (a JSON pbr
  // material may have an emission, never a texture).
  glm::vec3 emission{0.0f};
  std::optional<uint32_t> emission_texture;    // index into Scene::textures
  // Pbr only, glTF's defaults. metallic and roughness in [0, 1] (alpha =
  // roughness^2); transmission in [0, 1] (KHR_materials_transmission): the
  // share of the dielectric layer's unreflected light that passes through the
  // surface (rough refraction, Walter et al. 2007) instead of being diffused.
  float metallic = 1.0f;
  float roughness = 1.0f;
  float transmission = 0.0f;
  // Pbr with transmission only. false: the surface bounds a closed solid of
  // index `ior` (a JSON pbr material; a glTF one with KHR_materials_volume,
  // thickness > 0): rays refract in and out. true: glTF's thin-walled default
  // (no KHR_materials_volume): light passes through without bending (the
  // roughness still blurs it).
  bool thin_walled = false;
  // Pbr with transmission only: the transmission times this texture's red
  // channel (linear; glTF's transmissionTexture).
  std::optional<uint32_t> transmission_texture;  // index into Scene::textures
  // A solid (not thin-walled) with transmission only: Beer-Lambert
  // absorption inside it (KHR_materials_volume): light that travels a
  // distance d inside keeps attenuation_color^(d / attenuation_distance),
  // i.e. exp(-sigma d) with sigma = -ln(attenuation_color) /
  // attenuation_distance. Colour in [0, 1], distance > 0; an infinite
  // distance (the default) absorbs nothing.
  glm::vec3 attenuation_color{1.0f};
  float attenuation_distance = INFINITY;
  // Multiplies them: metallic x its blue, roughness x its green channel
  // (linear, not sRGB; glTF's metallicRoughnessTexture).
  std::optional<uint32_t> metallic_roughness_texture;  // index into Scene::textures
  // Lambertian and pbr: a tangent-space normal map (glTF's normalTexture,
  // linear; its x and y times normal_scale), in the frame of the mesh's
  // tangents (Mesh::tangents) where the file has them, else of the
  // triangle's uv directions (computed per triangle from the uvs).
  std::optional<uint32_t> normal_texture;  // index into Scene::textures
  float normal_scale = 1.0f;
  // The uv transform of each texture reference (glTF's KHR_texture_transform),
  // a 2x3 matrix by columns: the texture is sampled at uv' = m * (uv, 1).
  // Identity by default.
  glm::mat3x2 base_color_uv{1.0f};
  glm::mat3x2 emission_uv{1.0f};
  glm::mat3x2 metallic_roughness_uv{1.0f};
  glm::mat3x2 normal_uv{1.0f};
  glm::mat3x2 transmission_uv{1.0f};
  // glTF's alpha (3.9.6; JSON materials are opaque): alpha = alpha x the base
  // colour texture's alpha (linear) at the hit. Opaque ignores it; Mask cuts
  // the surface out where alpha < alpha_cutoff (finite, >= 0); Blend cuts it
  // out with probability 1 - alpha (a stochastic cut-out: coverage alpha on
  // average). Applies to mesh triangles; a cut-out point is not hit by any ray.
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  float alpha = 1.0f;  // baseColorFactor.a, in [0, 1]
  // glTF's doubleSided: false, a mesh triangle's back face (the side its
  // winding's normal points away from) is not hit by any ray (camera or
  // bounce), as if culled. JSON materials are double-sided.
  bool double_sided = true;

  bool operator==(const Material&) const = default;
};

// Every texture reference of a material, with its field name: the one list
// that code treating them alike (rebasing, range checks) walks.
struct MaterialTexture {
  const char* field;
  std::optional<uint32_t> Material::*index;
};
inline constexpr MaterialTexture kMaterialTextures[] = {
    {"base_color_texture", &Material::base_color_texture},
    {"emission_texture", &Material::emission_texture},
    {"metallic_roughness_texture", &Material::metallic_roughness_texture},
    {"normal_texture", &Material::normal_texture},
    {"transmission_texture", &Material::transmission_texture},
};
// Whether the material samples any texture.
inline bool has_texture(const Material& m) {
  for (const MaterialTexture& t : kMaterialTextures)
    if (m.*t.index) return true;
  return false;
}

// The absorption coefficient sigma (per unit length, per channel) inside
// the solid a material bounds: -ln(attenuation_color) /
// attenuation_distance (Beer-Lambert; KHR_materials_volume), +Inf where a
// channel is 0; 0 where nothing is absorbed: a material that is no
// transmissive solid (thin-walled, or no transmission: no ray travels
// inside it) or whose distance is infinite.
inline glm::vec3 absorption_coefficient(const Material& m) {
  glm::vec3 sigma(0.0f);
  if (m.type != MaterialType::Pbr || !(m.transmission > 0.0f) || m.thin_walled || std::isinf(m.attenuation_distance))
    return sigma;
  for (int c = 0; c < 3; ++c)
    if (m.attenuation_color[c] < 1.0f)
      sigma[c] = float(-std::log(double(m.attenuation_color[c])) / double(m.attenuation_distance));
  return sigma;
}

// How texture coordinates outside [0, 1] map onto the image (glTF's sampler
// wrapS / wrapT). Values match the WRAP_* constants in shaders/shared/shared.h
// (static_assert in render/gpu_layout.h).
enum class Wrap : uint32_t { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };

// An image decoded to RGBA8, with its sampler's wrap modes. Texel (x, y) is
// texels[y * width + x], y = 0 the top row: glTF's uv (0, 0) is the image's
// top-left corner, u to the right, v down. The bytes are as the file stores
// them (colour textures sRGB-encoded); the shader decodes them where they
// are used, so that a slot that holds linear data can read the same texels.
struct Texture {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint32_t> texels;  // r | g << 8 | b << 16 | a << 24
  Wrap wrap_s = Wrap::Repeat;    // along u
  Wrap wrap_t = Wrap::Repeat;    // along v

  bool operator==(const Texture&) const = default;
};

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
  uint32_t material = 0;  // index into Scene::materials

  bool operator==(const Sphere&) const = default;
};

struct Camera {
  glm::vec3 lookfrom{13.0f, 2.0f, 3.0f};
  glm::vec3 lookat{0.0f};
  glm::vec3 vup{0.0f, 1.0f, 0.0f};
  float vfov = 30.0f;        // degrees, vertical
  float aperture = 0.1f;     // lens diameter; 0 = pinhole
  float focus_dist = 10.0f;

  bool operator==(const Camera&) const = default;
};

// Values match the SKY_* constants in shaders/shared/shared.h (static_assert in render/gpu_layout.h).
enum class SkyType : uint32_t { Gradient = 0, Uniform = 1, None = 2, Envmap = 3 };

// An environment map's texels: linear RGB, 3 floats per texel, row y = 0 the
// top (+y), texel (x, y) at rgb[3 * (y * width + x)]. Finite and >= 0.
struct EnvmapImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgb;

  bool operator==(const EnvmapImage&) const = default;
};

struct Sky {
  SkyType type = SkyType::Gradient;
  glm::vec3 down{1.0f, 1.0f, 1.0f};    // gradient: colour at dir.y = -1
  glm::vec3 up{0.5f, 0.7f, 1.0f};      // gradient: colour at dir.y = +1
  glm::vec3 radiance{1.0f};            // uniform
  // Envmap: an equirectangular (latitude-longitude) image; the radiance
  // from direction d is strength x the texel d falls in (nearest texel,
  // piecewise constant). The convention (docs/design.md "Environment map"):
  // +y up; v = 0 at the top (+y), v = 1 at the bottom (-y); the image
  // centre (u = 0.5) faces -z, and u grows towards +x (clockwise seen from
  // above: u = 0.25 faces -x, 0.75 faces +x, 0 and 1 face +z). `rotate`
  // turns the map about +y by that many degrees, counter-clockwise seen from
  // above (right-handed): with rotate 90 the image centre faces -x.
  std::string file;         // as written in the scene file (relative to it)
  float strength = 1.0f;    // finite, >= 0
  float rotate = 0.0f;      // degrees, finite
  EnvmapImage image;        // the file's texels

  bool operator==(const Sky&) const = default;
};

// A punctual light (glTF's KHR_lights_punctual; JSON's "lights"): a point,
// a spot or a directional light, reached by next-event estimation only (a
// ray can never hit it: with --nee off it adds nothing). Units are
// octrace's radiometric ones (the radiance of a sky of 1 is 1):
//   point, spot  color x intensity is the radiant intensity I (radiance
//                scale x area, "W/sr"): a surface at distance r, at angle
//                theta to the light, receives E = I cos(theta) / r^2;
//   directional  color x intensity is the irradiance E ("W/m^2") on a
//                surface facing the light.
// glTF's photometric units are converted when a file is loaded (scene/gltf.h).
// A spot lights the cone around `direction`, with glTF's smooth falloff
// between inner_cone and outer_cone (degrees, as the JSON file's other
// angles, so that a round trip is exact; 0 <= inner < outer <= 90).
// `direction` (unit) is where the light travels: a directional light lights
// surfaces that face -direction.
enum class LightType : uint32_t { Point = 0, Spot = 1, Directional = 2 };

struct Light {
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};            // point, spot
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot, directional (unit)
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float inner_cone = 0.0f;             // spot, degrees
  float outer_cone = 45.0f;            // spot, degrees (glTF's default, pi/4)

  bool operator==(const Light&) const = default;
};

// A triangle mesh in its own (object) space, stored once however many times
// it is placed. Triangle k is indices[3k..3k+2]; counter-clockwise seen from
// the front (glTF's convention), which decides the geometric normal.
struct Mesh {
  std::string name;                 // names it in messages and summaries
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // per vertex (smooth shading), or empty (flat)
  std::vector<glm::vec2> uvs;       // UV set 0 per vertex, or empty
  std::vector<uint32_t> indices;    // three per triangle
  std::vector<uint32_t> materials;  // per triangle: index into Scene::materials
  // Per vertex, or empty: glTF's TANGENT (3.7.2.1), the frame of a normal
  // map: xyz the tangent (along +u), w = +1 or -1 the handedness, bitangent
  // = cross(normal, xyz) * w. Kept only beside normals and under a material
  // with a normal map; (0, 0, 0, 0) for a vertex of a primitive without one
  // (its frame comes from the uvs).
  std::vector<glm::vec4> tangents;

  size_t triangle_count() const { return indices.size() / 3; }
  bool operator==(const Mesh&) const = default;
};

// One placement of a mesh in the scene.
struct Instance {
  uint32_t mesh = 0;                  // index into Scene::meshes
  glm::mat4 transform{1.0f};          // object -> world (column-major, as glTF)

  bool operator==(const Instance&) const = default;
};

// A mesh file a JSON scene refers to ("meshes": [{"file", "material",
// "transform"}]), kept so that --dump-scene writes the reference back rather
// than the triangles. Its meshes, instances and materials are in the Scene.
struct MeshRef {
  std::string file;                  // as written in the scene file (relative to it)
  std::optional<uint32_t> material;  // overrides the file's own materials
  glm::mat4 transform{1.0f};
  std::optional<uint32_t> scene;     // which of the file's scenes (default: its default scene)

  bool operator==(const MeshRef&) const = default;
};

struct Scene {
  Camera camera;
  Sky sky;
  std::vector<Material> materials;
  // Textures come only from mesh files: JSON writes none, and loading the
  // references adds them again.
  std::vector<Texture> textures;
  std::vector<Sphere> spheres;
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Light> lights;       // punctual lights
  std::vector<MeshRef> mesh_refs;  // JSON scenes, and a glTF scene's reference to its file
  // The last `mesh_file_materials` of `materials` came from the mesh files
  // (appended as each reference was loaded), not from the scene file: JSON
  // writes only the others, and loading the references adds these again.
  size_t mesh_file_materials = 0;
  // Likewise the last `mesh_file_lights` of `lights` came from the mesh
  // files (KHR_lights_punctual): JSON writes only the others.
  size_t mesh_file_lights = 0;

  // Field by field with float ==, so -0 equals 0; tests that need bit-exactness compare bits.
  bool operator==(const Scene&) const = default;
};

// Triangles stored (each mesh once) and placed (each mesh once per instance).
uint64_t unique_triangle_count(const Scene& scene);
uint64_t instanced_triangle_count(const Scene& scene);

struct RtiowParams {
  uint64_t spheres = 488;  // small spheres, besides the ground and the three big ones
  float radius = 0.2f;     // radius of the small spheres
  uint64_t seed = 1;       // seeds the generator (not the sampler)
};

// The "Ray Tracing in One Weekend" final scene, generalised to any sphere count
// (up to 100,000,000). Small spheres overlap neither each other nor the big ones
// unless there is no room for that many of that radius (scene.cpp says how).
// Throws SettingError ("rtiow.radius", "rtiow.spheres") for parameters that
// cannot make a scene (radius <= 0, ...): check_rtiow_params, which a
// command that makes several scenes (bench) calls for each before the first.
Scene make_rtiow_scene(const RtiowParams& params);
void check_rtiow_params(const RtiowParams& params);

// JSON (README "Scene format"). `source` names the input in error
// messages ("scene.json: spheres[12].radius: must be a finite number > 0, got -1")
// and is where the file lies: mesh files are found relative to its folder.
Scene parse_scene_json(const std::string& text, const std::string& source);
Scene load_scene_json(const std::string& path);
// Meshes are written as the references they were loaded from (mesh_refs, with
// the transform as a matrix), never as triangles: a scene with meshes but no
// references cannot be written (InputError).
std::string scene_to_json(const Scene& scene);
// Written atomically (temporary file, then rename).
void save_scene_json(const Scene& scene, const std::string& path);

// Checks references and values of a scene built in code (the JSON loader checks
// as it parses). Throws InputError naming `source` and the offending field.
void validate_scene(const Scene& scene, const std::string& source);

}  // namespace octrace
