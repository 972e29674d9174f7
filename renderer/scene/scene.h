// The scene as plain CPU structs: what the renderer draws, independent of Vulkan.
// Sources: the built-in `rtiow` generator and the JSON format (README "Scene format").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace octrace {

// Values match the MAT_* constants in shaders/shared/shared.h (static_assert in render/gpu_layout.h).
enum class MaterialType : uint32_t { Lambertian = 0, Metal = 1, Dielectric = 2, Emissive = 3 };

struct Material {
  MaterialType type = MaterialType::Lambertian;
  glm::vec3 albedo{0.5f};    // lambertian, metal
  float fuzz = 0.0f;         // metal
  float ior = 1.5f;          // dielectric
  glm::vec3 radiance{0.0f};  // emissive

  bool operator==(const Material&) const = default;
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
enum class SkyType : uint32_t { Gradient = 0, Uniform = 1, None = 2 };

struct Sky {
  SkyType type = SkyType::Gradient;
  glm::vec3 down{1.0f, 1.0f, 1.0f};    // gradient: colour at dir.y = -1
  glm::vec3 up{0.5f, 0.7f, 1.0f};      // gradient: colour at dir.y = +1
  glm::vec3 radiance{1.0f};            // uniform

  bool operator==(const Sky&) const = default;
};

struct Scene {
  Camera camera;
  Sky sky;
  std::vector<Material> materials;
  std::vector<Sphere> spheres;

  // Field by field with float ==, so -0 equals 0; tests that need bit-exactness compare bits.
  bool operator==(const Scene&) const = default;
};

struct RtiowParams {
  uint64_t spheres = 488;  // small spheres, besides the ground and the three big ones
  float radius = 0.2f;     // radius of the small spheres
  uint64_t seed = 1;       // seeds the generator (not the sampler)
};

// The "Ray Tracing in One Weekend" final scene, generalised to any sphere count
// (up to 100,000,000). Small spheres overlap neither each other nor the big ones
// unless there is no room for that many of that radius (scene.cpp says how).
// Throws SettingError ("rtiow.radius", "rtiow.spheres") for parameters that
// cannot make a scene (radius <= 0, ...).
Scene make_rtiow_scene(const RtiowParams& params);

// JSON (README "Scene format"). `source` names the input in error
// messages ("scene.json: spheres[12].radius: must be a finite number > 0, got -1").
Scene parse_scene_json(const std::string& text, const std::string& source);
Scene load_scene_json(const std::string& path);
std::string scene_to_json(const Scene& scene);
// Written atomically (temporary file, then rename).
void save_scene_json(const Scene& scene, const std::string& path);

// Checks references and values of a scene built in code (the JSON loader checks
// as it parses). Throws InputError naming `source` and the offending field.
void validate_scene(const Scene& scene, const std::string& source);

}  // namespace octrace
