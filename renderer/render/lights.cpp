#include "render/lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "accel/aabb.h"
#include "scene/envmap.h"

namespace octrace {

namespace {

constexpr double kPi = std::numbers::pi;

// The bounding sphere's radius of the scene's primitives (0 for an empty
// scene): half the diagonal of their box.
double scene_radius(const Scene& scene) {
  Aabb box;
  for (const Sphere& s : scene.spheres) box.extend({s.center - s.radius, s.center + s.radius});
  for (const Instance& inst : scene.instances) {
    const Mesh& mesh = scene.meshes[inst.mesh];
    for (uint32_t i : mesh.indices) {
      const glm::vec3 p(inst.transform * glm::vec4(mesh.positions[i], 1.0f));
      box.extend({p, p});
    }
  }
  if (box.empty()) return 0.0;
  const glm::dvec3 d = glm::dvec3(box.hi) - glm::dvec3(box.lo);
  return 0.5 * std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

}  // namespace

double luminance(glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

AliasTable build_alias_table(const std::vector<double>& weights) {
  AliasTable t;
  double total = 0.0;
  for (double w : weights) total += w;
  if (!(total > 0.0)) return t;
  const size_t n = weights.size();
  t.q.assign(n, 1.0f);
  t.alias.resize(n);
  t.pmf.resize(n);
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    t.alias[i] = uint32_t(i);
    t.pmf[i] = float(weights[i] / total);
    scaled[i] = weights[i] / total * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  // Vose: pair each column below 1 with one above, which gives it the rest.
  while (!small.empty() && !large.empty()) {
    const uint32_t s = small.back(), l = large.back();
    small.pop_back();
    large.pop_back();
    t.q[s] = float(scaled[s]);
    t.alias[s] = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    (scaled[l] < 1.0 ? small : large).push_back(l);
  }
  // What is left is 1 up to rounding: kept whole (q = 1, alias itself).
  return t;
}

LightList build_light_list(const Scene& scene) {
  LightList out;
  std::vector<double> power;
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const glm::vec3 radiance = sphere_radiance(scene.materials[s.material]);
    const double lum = luminance(radiance);
    if (!(lum > 0.0)) continue;
    if (out.sphere_lights.empty()) out.sphere_lights.assign(scene.spheres.size(), gpu::NO_LIGHT);
    out.sphere_lights[i] = uint32_t(out.lights.size());
    gpu::GpuLight l{};
    l.type = gpu::LIGHT_SPHERE;
    l.position = s.center;
    l.radius = s.radius;
    l.intensity = radiance;
    l.sphere = uint32_t(i);
    out.lights.push_back(l);
    power.push_back(4.0 * kPi * kPi * double(s.radius) * double(s.radius) * lum);
  }
  const double radius = scene_radius(scene);
  for (const Light& light : scene.lights) {
    const glm::vec3 intensity = light.color * light.intensity;
    const double lum = luminance(intensity);
    if (!(lum > 0.0)) continue;
    gpu::GpuLight l{};
    l.type = uint32_t(light.type) + 1;  // gpu_layout.h checks the order
    l.position = light.position;
    l.direction = light.direction;
    l.intensity = intensity;
    l.sphere = gpu::NO_LIGHT;
    l.cos_inner = float(std::cos(double(light.inner_cone) * kPi / 180.0));
    l.cos_outer = float(std::cos(double(light.outer_cone) * kPi / 180.0));
    double p = 0.0;
    switch (light.type) {
      case LightType::Point: p = 4.0 * kPi * lum; break;
      case LightType::Spot: p = 2.0 * kPi * (1.0 - 0.5 * (double(l.cos_inner) + double(l.cos_outer))) * lum; break;
      // A scene of no extent still gets a positive share.
      case LightType::Directional: p = kPi * std::max(radius * radius, 1.0) * lum; break;
    }
    out.lights.push_back(l);
    power.push_back(p);
  }
  // Emissive triangles, one light per triangle of each instance, with its
  // world-space vertices. A triangle of no area (never hit) is no light.
  out.triangle_lights.assign(1, 0u);
  for (size_t k = 0; k < scene.instances.size(); ++k) {
    const Instance& inst = scene.instances[k];
    const Mesh& mesh = scene.meshes[inst.mesh];
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const glm::vec3 emission = triangle_emission(scene.materials[mesh.materials[t]]);
      const double lum = luminance(emission);
      if (!(lum > 0.0)) continue;
      glm::vec3 v[3];
      for (int j = 0; j < 3; ++j) v[j] = glm::vec3(inst.transform * glm::vec4(mesh.positions[mesh.indices[3 * t + j]], 1.0f));
      const glm::dvec3 c = glm::cross(glm::dvec3(v[1]) - glm::dvec3(v[0]), glm::dvec3(v[2]) - glm::dvec3(v[0]));
      const double area = 0.5 * std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
      if (!(area > 0.0) || !std::isfinite(area)) continue;
      if (out.triangle_lights[0] == 0u) {
        out.triangle_lights.assign(1 + scene.instances.size(), gpu::NO_LIGHT);
        out.triangle_lights[0] = uint32_t(scene.instances.size());
      }
      if (out.triangle_lights[1 + k] == gpu::NO_LIGHT) {
        out.triangle_lights[1 + k] = uint32_t(out.triangle_lights.size());
        out.triangle_lights.resize(out.triangle_lights.size() + mesh.triangle_count(), gpu::NO_LIGHT);
      }
      out.triangle_lights[out.triangle_lights[1 + k] + t] = uint32_t(out.lights.size());
      gpu::GpuLight l{};
      l.type = gpu::LIGHT_TRIANGLE;
      l.position = v[0];
      l.direction = v[1];
      l.intensity = v[2];
      l.radius = float(area);
      l.sphere = gpu::NO_LIGHT;
      l.instance = uint32_t(k);
      l.triangle = uint32_t(t);
      out.lights.push_back(l);
      power.push_back(kPi * area * lum);
    }
  }
  // The sky, when it is an envmap that can be sampled: the list's last entry
  // (the shader finds it there for the MIS weight of a path that escapes).
  // Its power is pbrt-v4's ImageInfiniteLight::Phi: the flux through a disk
  // of the scene's radius R from every direction, pi R^2 x the integral of
  // the luminance over the sphere of directions; for the equirectangular map
  // that integral is 2 pi^2 x the mean of f = luminance x sin theta over the
  // texels (scene/envmap.h), the inverse of the tables' density scale. As for
  // a directional light, R can make it dwarf a small lamp's power; the
  // defensive mixture below keeps every other light at least 1 / (2n).
  // Gradient and uniform skies are not lights: their radiance varies slowly
  // or not at all, so cosine-weighted BSDF sampling is already close to the
  // ideal density for them and a light sample would only add a shadow ray.
  if (scene.sky.type == SkyType::Envmap && scene.sky.strength > 0.0f) {
    const float scale = build_envmap_tables(scene.sky.image).marginal[scene.sky.image.height + 1];
    if (scale > 0.0f) {
      gpu::GpuLight l{};
      l.type = gpu::LIGHT_ENVMAP;
      l.sphere = gpu::NO_LIGHT;
      out.lights.push_back(l);
      const double integral = 2.0 * kPi * kPi / double(scale) * double(scene.sky.strength);
      power.push_back(kPi * std::max(radius * radius, 1.0) * integral);
    }
  }
  // Every sphere gets an entry once there is any light: the shader reads it
  // at every hit of a path that sampled a light.
  if (!out.lights.empty() && out.sphere_lights.empty()) out.sphere_lights.assign(scene.spheres.size(), gpu::NO_LIGHT);
  // Defensive mixture: half by power, half uniform (Hesterberg 1995,
  // "Weighted Average Importance Sampling and Defensive Mixture
  // Distributions", Technometrics 37(2)). Power alone starves a light whose
  // power says little about what it adds where the camera looks: a
  // directional light's power grows with the scene's extent (a ground
  // sphere of radius 1000 gives it ~1e6 times a nearby lamp's), and a
  // lamp picked once in a million draws is a firefly of a million.
  double total = 0.0;
  for (double p : power) total += p;
  if (total > 0.0)
    for (double& p : power) p = 0.5 * p / total + 0.5 / double(power.size());
  const AliasTable table = build_alias_table(power);
  for (size_t i = 0; i < out.lights.size(); ++i) {
    out.lights[i].pmf = table.pmf[i];
    out.lights[i].alias_q = table.q[i];
    out.lights[i].alias = table.alias[i];
  }
  return out;
}

}  // namespace octrace
