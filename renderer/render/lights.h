// The lights that next-event estimation samples (shaders/shading/lights.glsl),
// built from the Scene on the CPU: emissive spheres, punctual lights,
// emissive mesh triangles (one light per triangle and instance) and an
// envmap sky, in one list that is also an alias table picking a light in
// proportion to its power. Plain data, no Vulkan; render/gpu_scene uploads it.
//
// Choice of light: by power, with Walker's alias method (A. J. Walker 1977,
// "An Efficient Method for Generating Discrete Random Variables with General
// Distributions", ACM TOMS 3(3)) in Vose's construction (M. D. Vose 1991, "A
// Linear Algorithm for Generating Random Variates with a Given Distribution",
// IEEE TSE 17(9)): O(1) per pick, whatever the light count, where a CDF needs
// a binary search. The pick draws two numbers: a column i uniform in [0, n)
// and u in [0, 1); it returns i if u < q[i], else alias[i]. The probability
// of light k is pmf[k] = weight_k / sum of weights (exactly, up to float
// rounding of the table), which the estimator divides by and the MIS weights
// use. Powers (radiometric flux, luminance of the rgb):
//   sphere       pi * area * L = 4 pi^2 r^2 lum(L)  (a Lambertian emitter)
//   point        4 pi lum(I)
//   spot         2 pi (1 - (cos_inner + cos_outer) / 2) lum(I)  (pbrt-v4's
//                SpotLight::Phi, the cone's solid angle with the falloff
//                taken at its middle)
//   directional  pi R^2 lum(E), R the radius of the scene's bounding sphere
//                (pbrt-v4's DistantLight::Phi): the flux through the scene
//   triangle     pi * area * lum(E), E = triangle_emission (scene/features.h:
//                the emission factor; an emission texture's mean is left out,
//                so a textured light is picked as if its texture were white),
//                area in world space (the instance's placement applied)
//   envmap       pi R^2 x integral of lum(L) over all directions (pbrt-v4's
//                ImageInfiniteLight::Phi); the sky's envmap is the list's
//                last light. Gradient and uniform skies are no lights.
// Lights of power 0 (black) are left out. The weights the table picks by are
// a defensive mixture, half power and half uniform (lights.cpp says why):
// pmf[k] = power_k / (2 sum) + 1 / (2 n).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/features.h"
#include "scene/scene.h"
#include "shared/shared.h"

namespace octrace {

// Walker's alias table over non-negative weights (Vose's construction).
struct AliasTable {
  std::vector<float> q;         // probability of keeping column i
  std::vector<uint32_t> alias;  // where column i goes otherwise
  std::vector<float> pmf;       // weight_i / sum of weights
};
// Empty when the weights are empty or all 0.
AliasTable build_alias_table(const std::vector<double>& weights);

struct LightList {
  std::vector<gpu::GpuLight> lights;  // with the alias table filled in
  // Per sphere, the index of its light (gpu::NO_LIGHT for one that does not
  // emit); empty when no sphere emits.
  std::vector<uint32_t> sphere_lights;
  // The light index of each emissive triangle, by instance and triangle
  // (shaders/shared/shared.h, BINDING_TRIANGLE_LIGHTS, has the layout):
  // {0} when no triangle emits.
  std::vector<uint32_t> triangle_lights;
};

// Rec. 709 luminance.
double luminance(glm::vec3 c);

LightList build_light_list(const Scene& scene);

}  // namespace octrace
