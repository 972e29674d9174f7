// Environment maps (Sky type envmap): the orientation convention, the image
// loader, and the importance-sampling tables with a host mirror of the
// shader's sampling functions (shaders/shading/envmap.glsl). No Vulkan here.
//
// Convention (Sky in scene/scene.h; docs/design.md "Environment map"): an
// equirectangular (latitude-longitude) map, +y up. A texel coordinate
// (u, v) in [0, 1]^2 faces
//   theta = pi v   (polar angle from +y: v = 0 the top row, +y),
//   phi   = 2 pi (u - rotate / 360),
//   dir   = (-sin theta sin phi, cos theta, sin theta cos phi),
// so with rotate 0 the image centre (0.5, 0.5) faces -z, u = 0.25 faces -x,
// u = 0.75 faces +x and u = 0 or 1 face +z: u grows clockwise seen from
// above, to the right of a viewer looking at the image centre (the picture
// is seen unmirrored from inside). rotate > 0 turns the map counter-
// clockwise seen from above (right-handed about +y).
//
// Radiance is piecewise constant: a direction reads the texel its (u, v)
// falls in (nearest, no filtering), so that the sampling density below is
// exactly proportional to the luminance the renderer sees.
//
// Sampling (Pharr, Jakob & Humphreys, "Physically Based Rendering", 3rd ed.,
// 14.2.4 "Infinite area lights" and 13.6.7 "Piecewise-constant 2D
// distributions"): the function f(x, y) = luminance(texel) x sin(theta of
// row y's centre) is sampled with a marginal CDF over rows and a conditional
// CDF per row; the density in (u, v) is p(u, v) = f / mean(f), and in solid
// angle p(u, v) / (2 pi^2 sin theta), since d omega = 2 pi^2 sin theta du dv.
// The sin theta factor stops the stretched polar rows from being over-
// sampled; it also makes a direction whose sin theta is 0 (the poles
// exactly) unsampleable, which the functions report as no sample / pdf 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace octrace {

// The direction the map coordinate (u, v) faces, and the map coordinate of a
// unit direction (u in [0, 1), v in [0, 1]).
glm::vec3 envmap_direction(glm::vec2 uv, float rotate_degrees);
glm::vec2 envmap_uv(glm::vec3 dir, float rotate_degrees);
// The texel that map coordinate (u, v) falls in (nearest; clamped to the image).
glm::uvec2 envmap_texel(glm::vec2 uv, uint32_t width, uint32_t height);

// Rec. 709 luminance, the sampling weight of a texel.
float envmap_luminance(const float* rgb);

// Reads an environment map: .exr (tinyexr), .hdr (Radiance RGBE, stb_image),
// or any other image read_image reads. Throws InputError naming the file for a
// missing or unreadable file and for a texel that is NaN, infinite or negative.
EnvmapImage load_envmap(const std::string& path);

// The tables of shaders/shared/shared.h's envmap bindings:
//   marginal: height + 2 floats: the CDF over rows, marginal[0] = 0 ...
//             marginal[height] = 1, then the density scale s = width x height /
//             sum(f) at marginal[height + 1] (0 when the map is black, or so
//             dim that s overflows a float: no sampling);
//   conditional: height x (width + 1) floats: row y's CDF over its texels at
//             conditional[y * (width + 1) + x], 0 ... 1 (a row of f = 0 holds
//             x / width, never chosen by the marginal).
// p(u, v) of texel (x, y) is f(x, y) x s.
struct EnvmapTables {
  std::vector<float> marginal;
  std::vector<float> conditional;
};
EnvmapTables build_envmap_tables(const EnvmapImage& image);

// Host mirrors of envmap_sample and envmap_pdf in shaders/shading/envmap.glsl,
// the same arithmetic in fp32. envmap_sample maps two uniform numbers in
// [0, 1) to a direction and its density in solid angle; false (and pdf 0)
// when the map cannot be sampled.
bool envmap_sample(const EnvmapImage& image, const EnvmapTables& tables, float rotate_degrees, glm::vec2 u,
                   glm::vec3& dir, float& pdf);
float envmap_pdf(const EnvmapImage& image, const EnvmapTables& tables, float rotate_degrees, glm::vec3 dir);

}  // namespace octrace
