#include "scene/features.h"

#include <algorithm>

namespace octrace {

namespace {

bool is_black(glm::vec3 c) { return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f; }

}  // namespace

glm::vec3 sphere_radiance(const Material& m) {
  switch (m.type) {
    case MaterialType::Emissive: return m.radiance;
    case MaterialType::Lambertian:
    case MaterialType::Pbr: return m.emission_texture ? glm::vec3(0.0f) : m.emission;
    default: return glm::vec3(0.0f);
  }
}

glm::vec3 triangle_emission(const Material& m) {
  switch (m.type) {
    case MaterialType::Emissive: return m.radiance;
    case MaterialType::Lambertian:
    case MaterialType::Pbr: return m.emission;
    default: return glm::vec3(0.0f);
  }
}

SceneFeatures scene_features(const Scene& scene) {
  SceneFeatures f;
  std::vector<bool> used(scene.materials.size(), false);
  for (const Sphere& s : scene.spheres)
    if (s.material < used.size()) used[s.material] = true;
  std::vector<bool> placed(scene.meshes.size(), false);
  for (const Instance& inst : scene.instances)
    if (inst.mesh < placed.size()) placed[inst.mesh] = true;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!placed[m] || mesh.triangle_count() == 0) continue;
    f.triangles = true;
    f.vertex_normals |= !mesh.normals.empty();
    for (uint32_t material : mesh.materials)
      if (material < used.size()) {
        used[material] = true;
        f.alpha |= scene.materials[material].alpha_mode != AlphaMode::Opaque;
        f.single_sided |= !scene.materials[material].double_sided;
        f.triangle_lights |= !is_black(triangle_emission(scene.materials[material]));
      }
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    if (!used[i]) continue;
    const Material& m = scene.materials[i];
    switch (m.type) {
      case MaterialType::Lambertian:
        f.lambertian = true;
        f.textures |= has_texture(m);
        f.normal_maps |= m.normal_texture.has_value();
        f.surface_emission |= !is_black(m.emission);
        break;
      case MaterialType::Metal:
        f.metal = true;
        f.fuzzy_metal |= m.fuzz > 0.0f;
        break;
      case MaterialType::Dielectric: f.dielectric = true; break;
      case MaterialType::Emissive: f.emissive |= !is_black(m.radiance); break;
      case MaterialType::Pbr:
        f.pbr = true;
        f.textures |= has_texture(m);
        f.normal_maps |= m.normal_texture.has_value();
        f.surface_emission |= !is_black(m.emission);
        f.transmission |= m.transmission > 0.0f;
        f.absorption |= absorption_coefficient(m) != glm::vec3(0.0f);
        break;
    }
  }
  f.defocus = scene.camera.aperture > 0.0f;
  f.sky = scene.sky.type;
  switch (scene.sky.type) {
    case SkyType::None: f.sky_black = true; break;
    case SkyType::Uniform: f.sky_black = is_black(scene.sky.radiance); break;
    case SkyType::Gradient: f.sky_black = is_black(scene.sky.down) && is_black(scene.sky.up); break;
    case SkyType::Envmap:
      f.sky_black = scene.sky.strength == 0.0f ||
                    std::all_of(scene.sky.image.rgb.begin(), scene.sky.image.rgb.end(), [](float c) { return c == 0.0f; });
      break;
  }
  for (const Sphere& s : scene.spheres) f.sphere_lights |= !is_black(sphere_radiance(scene.materials[s.material]));
  for (const Light& l : scene.lights) f.punctual |= l.intensity > 0.0f && !is_black(l.color);
  f.sky_light = scene.sky.type == SkyType::Envmap && !f.sky_black;
  f.any_light = f.emissive || f.surface_emission || !f.sky_black || f.punctual;
  f.spheres = !scene.spheres.empty();
  f.empty = !f.spheres && !f.triangles;
  return f;
}

SceneFeatures all_features(const Scene& scene) {
  SceneFeatures f;
  f.lambertian = f.metal = f.fuzzy_metal = f.dielectric = f.emissive = f.pbr = f.defocus = true;
  f.sky = scene.sky.type;
  f.sky_black = false;
  f.any_light = true;
  f.empty = false;
  f.spheres = f.triangles = f.vertex_normals = f.textures = f.surface_emission = f.normal_maps = f.alpha = f.single_sided = true;
  f.transmission = f.absorption = true;
  f.sphere_lights = f.punctual = f.sky_light = f.triangle_lights = true;
  return f;
}

std::vector<std::string> feature_names(const SceneFeatures& f) {
  std::vector<std::string> names;
  if (f.lambertian) names.push_back("lambertian");
  if (f.metal) names.push_back("metal");
  if (f.fuzzy_metal) names.push_back("fuzzy_metal");
  if (f.dielectric) names.push_back("dielectric");
  if (f.emissive) names.push_back("emissive");
  if (f.pbr) names.push_back("pbr");
  if (f.defocus) names.push_back("defocus");
  if (f.triangles) names.push_back("triangles");
  if (f.vertex_normals) names.push_back("vertex_normals");
  if (f.textures) names.push_back("textures");
  if (f.surface_emission) names.push_back("surface_emission");
  if (f.normal_maps) names.push_back("normal_maps");
  if (f.alpha) names.push_back("alpha");
  if (f.single_sided) names.push_back("single_sided");
  if (f.transmission) names.push_back("transmission");
  if (f.absorption) names.push_back("absorption");
  if (f.sphere_lights) names.push_back("sphere_lights");
  if (f.punctual) names.push_back("punctual");
  if (f.sky_light) names.push_back("sky_light");
  if (f.triangle_lights) names.push_back("triangle_lights");
  constexpr const char* kSkyNames[] = {"sky_gradient", "sky_uniform", "sky_none", "sky_envmap"};
  names.push_back(kSkyNames[static_cast<uint32_t>(f.sky)]);
  if (f.sky_black) names.push_back("sky_black");
  if (!f.any_light) names.push_back("no_light");
  if (f.empty) names.push_back("empty");
  return names;
}

}  // namespace octrace
