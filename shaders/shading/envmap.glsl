// The environment map (SKY_ENVMAP): radiance, and importance sampling by
// luminance x sin theta. The convention, the tables and the maths are in
// renderer/scene/envmap.h (a host mirror of these functions, tested against
// them); in short, map coordinate (u, v) faces
//   theta = pi v, phi = 2 pi (u - rotate / 360),
//   dir = (-sin theta sin phi, cos theta, sin theta cos phi)
// (+y up, v = 0 the top, the image centre facing -z, u growing towards +x),
// and a direction reads the texel it falls in (nearest), so that the sampling
// density is exactly proportional to the luminance the path sees. The
// includer declares `scene` (SceneParams) and the buffers envmap_texels,
// envmap_marginal and envmap_conditional (shared/shared.h's bindings).
// Everything here is fp32, in every precision variant: directions, texels,
// CDFs and densities (a sun's texel and its density exceed half's range).
#ifndef OCTRACE_ENVMAP_GLSL
#define OCTRACE_ENVMAP_GLSL

const float ENVMAP_PI = 3.14159265358979;

vec3 envmap_direction(vec2 uv) {
  float theta = ENVMAP_PI * uv.y;
  float phi = 2.0 * ENVMAP_PI * (uv.x - scene.sky_b.x);
  float sin_theta = sin(theta);
  return vec3(-sin_theta * sin(phi), cos(theta), sin_theta * cos(phi));
}

// theta by atan(sin, cos), not acos(y): lavapipe's acos is off by up to
// 1.6e-4 rad (measured by tests/render/envmap_render_test.cpp), a tenth of a
// row of a 2k map (1.5e-3 rad): directions that near a row's edge would read
// the neighbouring row; atan's error is below 3e-6 rad, and it keeps its
// precision near the poles.
// At the poles (x = z = 0) atan(0, 0) is undefined in GLSL: u is 0 there.
vec2 envmap_uv(vec3 dir) {
  bool pole = dir.x == 0.0 && dir.z == 0.0;
  float u = (pole ? 0.0 : atan(-dir.x, dir.z) / (2.0 * ENVMAP_PI)) + scene.sky_b.x;
  return vec2(u - floor(u), atan(length(dir.xz), dir.y) / ENVMAP_PI);
}

// The texel map coordinate uv falls in (clamped to the image).
uvec2 envmap_texel(vec2 uv) {
  return min(uvec2(max(uv, vec2(0.0)) * vec2(scene.envmap_width, scene.envmap_height)),
             uvec2(scene.envmap_width - 1u, scene.envmap_height - 1u));
}

vec3 envmap_texel_rgb(uvec2 t) {
  uint i = 3u * (t.y * scene.envmap_width + t.x);
  return vec3(envmap_texels[i], envmap_texels[i + 1u], envmap_texels[i + 2u]);
}

// The sampling function f of a texel: Rec. 709 luminance x sin theta of its
// row's centre.
float envmap_weight(uvec2 t) {
  vec3 c = envmap_texel_rgb(t);
  float sin_row = sin(ENVMAP_PI * (float(t.y) + 0.5) / float(scene.envmap_height));
  return (0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b) * sin_row;
}

// Radiance from direction dir (unit): strength x the texel.
vec3 envmap_radiance(vec3 dir) {
  return scene.sky_a * envmap_texel_rgb(envmap_texel(envmap_uv(dir)));
}

// Density in solid angle of envmap_sample choosing dir (unit): p(u, v) /
// (2 pi^2 sin theta), p(u, v) = f x the scale at envmap_marginal[height + 1];
// 0 where the map cannot be sampled (black, or exactly at a pole).
float envmap_pdf(vec3 dir) {
  // sin theta from x and z: 1 - y^2 cancels near the poles.
  float sin_theta = length(dir.xz);
  if (!(sin_theta > 0.0)) return 0.0;
  float scale = envmap_marginal[scene.envmap_height + 1u];
  return envmap_weight(envmap_texel(envmap_uv(dir))) * scale / (2.0 * ENVMAP_PI * ENVMAP_PI * sin_theta);
}

// The largest i in [0, n) with cdf[first + i] <= u, for cdf[first] <= u <
// cdf[first + n]: binary search in the marginal CDF (row false) or in the
// conditional CDF of the row that starts at `first`.
float envmap_cdf(bool row, uint i) { return row ? envmap_conditional[i] : envmap_marginal[i]; }
uint envmap_find_interval(bool row, uint first, uint n, float u) {
  uint lo = 0u, hi = n;
  while (hi - lo > 1u) {
    uint mid = (lo + hi) / 2u;
    if (envmap_cdf(row, first + mid) <= u) lo = mid;
    else hi = mid;
  }
  return lo;
}

// Maps two uniform numbers in [0, 1) to a direction, by the marginal CDF
// (a row) and the row's conditional CDF (a texel), continuous within the
// texel; pdf is its density in solid angle (envmap_pdf's). false, with pdf
// 0, when the map cannot be sampled (black: no sample, no NaN). The light
// the direction brings is envmap_radiance(dir): the same texel, but for a
// direction within rounding (~1e-6) of the texel's edge.
bool envmap_sample(vec2 u, out vec3 dir, out float pdf) {
  uint w = scene.envmap_width, h = scene.envmap_height;
  dir = vec3(0.0, 1.0, 0.0);
  pdf = 0.0;
  float scale = envmap_marginal[h + 1u];
  if (scale == 0.0) return false;
  uint y = envmap_find_interval(false, 0u, h, u.y);
  float dv = (u.y - envmap_marginal[y]) / (envmap_marginal[y + 1u] - envmap_marginal[y]);
  uint row = y * (w + 1u);
  uint x = envmap_find_interval(true, row, w, u.x);
  float du = (u.x - envmap_conditional[row + x]) / (envmap_conditional[row + x + 1u] - envmap_conditional[row + x]);
  vec2 uv = vec2((float(x) + du) / float(w), (float(y) + dv) / float(h));
  dir = envmap_direction(uv);
  float sin_theta = sin(ENVMAP_PI * uv.y);
  float p_uv = envmap_weight(uvec2(x, y)) * scale;
  if (!(sin_theta > 0.0) || !(p_uv > 0.0)) return false;
  pdf = p_uv / (2.0 * ENVMAP_PI * ENVMAP_PI * sin_theta);
  return true;
}

#endif
