// SceneFeatures: which effects a scene uses, so that the pipeline can be
// specialised to simulate only those (a scene without glass runs no glass
// code). Computed on the CPU from the Scene; no Vulkan here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace octrace {

struct SceneFeatures {
  bool lambertian = false;   // some primitive is lambertian
  bool metal = false;        // some primitive is metal ...
  bool fuzzy_metal = false;  // ... with fuzz > 0
  bool dielectric = false;   // some primitive is glass
  bool emissive = false;     // some primitive emits
  bool pbr = false;          // some primitive has glTF's metallic-roughness material (microfacet lobes)
  bool defocus = false;      // camera aperture > 0
  SkyType sky = SkyType::Gradient;
  bool sky_black = false;    // the sky adds nothing (type none, or a black colour)
  // Some path can carry light to the camera: an emitter, or a sky that is
  // not black. Without it every pixel is 0 and no pass needs to run.
  bool any_light = true;
  bool empty = false;        // no primitives
  bool spheres = true;       // some sphere
  bool triangles = false;    // some instanced mesh triangle
  bool vertex_normals = false;  // some instanced mesh has vertex normals (smooth shading)
  bool textures = false;          // some material samples a texture
  bool surface_emission = false;  // some lambertian or pbr material emits (glTF emission)
  bool normal_maps = false;       // some lambertian or pbr material on a mesh has a normal map
  bool alpha = false;             // some mesh material is not opaque (alpha MASK or BLEND)
  bool single_sided = false;      // some mesh material is single-sided (back faces not hit)
  bool transmission = false;      // some pbr material transmits (refraction through a rough surface)
  bool absorption = false;        // some transmissive solid absorbs (KHR_materials_volume's attenuation)
  // Lights that next-event estimation samples (render/lights.h):
  bool sphere_lights = false;     // some sphere emits (sphere_radiance not black)
  bool punctual = false;          // some punctual light (point, spot, directional) is not black
  // The sky is a light: an envmap that is not black. A gradient or uniform
  // sky is not (render/lights.h says why): paths find it by escaping only.
  bool sky_light = false;
  bool triangle_lights = false;   // some placed mesh triangle emits (triangle_emission not black)

  // Some light that next-event estimation samples: with NEE on, a path
  // casts a shadow ray toward one at its bounces.
  bool nee_lights() const { return sphere_lights || punctual || sky_light || triangle_lights; }

  bool operator==(const SceneFeatures&) const = default;
};

// The radiance a sphere of material m emits, and so whether it is a light
// (0 for none): an emissive material's radiance, a lambertian or pbr
// material's emission. An emission texture makes it no light (NEE cannot
// read the texture at a point it picks by direction only; such a sphere is
// still found by the paths that hit it).
glm::vec3 sphere_radiance(const Material& m);

// The emission factor of a triangle of material m, and so whether it is a
// light (0 for none): an emissive material's radiance, a lambertian or pbr
// material's emission (glTF's emissiveFactor x emissive_strength). An
// emission texture is left out here (the light's power takes the factor
// alone) but not where the light is sampled: NEE picks a point on the
// triangle and reads the texture there, as a hit does.
glm::vec3 triangle_emission(const Material& m);

// Only the materials that primitives use count (an unused glass material in
// the list does not make the scene need glass code); only meshes that some
// instance places count.
SceneFeatures scene_features(const Scene& scene);

// Every effect on: the general pipeline (`--effects all`).
SceneFeatures all_features(const Scene& scene);

// Names of the features that are on, for --json and messages.
std::vector<std::string> feature_names(const SceneFeatures& f);

}  // namespace octrace
