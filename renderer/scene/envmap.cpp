#include "scene/envmap.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "core/text.h"
#include "io/image.h"

namespace octrace {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The sampling function f of texel (x, y): luminance x sin theta of the
// row's centre, in fp32 as the shader computes it.
float envmap_weight(const EnvmapImage& image, uint32_t x, uint32_t y) {
  const float sin_row = std::sin(kPi * (float(y) + 0.5f) / float(image.height));
  return envmap_luminance(&image.rgb[3 * (size_t(y) * image.width + x)]) * sin_row;
}

// The largest i in [0, n) with cdf[i] <= u, for cdf[0] <= u < cdf[n].
uint32_t find_interval(const float* cdf, uint32_t n, float u) {
  uint32_t lo = 0, hi = n;
  while (hi - lo > 1) {
    const uint32_t mid = (lo + hi) / 2;
    if (cdf[mid] <= u) lo = mid;
    else hi = mid;
  }
  return lo;
}

// A CDF over `n` cells of weight w[i] (doubles, so that a long row's sum
// loses nothing): cdf[0] = 0, cdf[n] = 1, monotone; a zero sum gives the
// uniform CDF i / n.
void write_cdf(const std::vector<double>& w, float* cdf) {
  const size_t n = w.size();
  double sum = 0.0;
  for (double x : w) sum += x;
  double partial = 0.0;
  cdf[0] = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    partial += w[i];
    cdf[i + 1] = sum > 0.0 ? float(partial / sum) : float(double(i + 1) / double(n));
  }
  cdf[n] = 1.0f;
}

}  // namespace

glm::vec3 envmap_direction(glm::vec2 uv, float rotate_degrees) {
  const float theta = kPi * uv.y;
  const float phi = 2.0f * kPi * (uv.x - rotate_degrees / 360.0f);
  const float sin_theta = std::sin(theta);
  return {-sin_theta * std::sin(phi), std::cos(theta), sin_theta * std::cos(phi)};
}

glm::vec2 envmap_uv(glm::vec3 dir, float rotate_degrees) {
  // At the poles (x = z = 0) u is 0, as in the shader (GLSL's atan(0, 0) is undefined).
  const bool pole = dir.x == 0.0f && dir.z == 0.0f;
  float u = (pole ? 0.0f : std::atan2(-dir.x, dir.z) / (2.0f * kPi)) + rotate_degrees / 360.0f;
  u -= std::floor(u);
  return {u, std::atan2(std::sqrt(dir.x * dir.x + dir.z * dir.z), dir.y) / kPi};
}

glm::uvec2 envmap_texel(glm::vec2 uv, uint32_t width, uint32_t height) {
  return {std::min(uint32_t(std::max(uv.x, 0.0f) * float(width)), width - 1),
          std::min(uint32_t(std::max(uv.y, 0.0f) * float(height)), height - 1)};
}

float envmap_luminance(const float* rgb) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

EnvmapImage load_envmap(const std::string& path) {
  const Image image = read_image(path);
  // The first bad texel names the problem; for negative ones (lossy
  // compression rings below 0: every HDRI in Debian's blender-data has some)
  // also how many there are and how far below 0 they go.
  size_t first = image.rgb.size(), negative = 0;
  float least = 0.0f;
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    const float c = image.rgb[i];
    if (std::isfinite(c) && c >= 0.0f) continue;
    if (first == image.rgb.size()) first = i;
    if (!std::isfinite(c)) break;
    ++negative;
    least = std::min(least, c);
  }
  if (first == image.rgb.size()) return {uint32_t(image.width), uint32_t(image.height), image.rgb};
  const size_t texel = first / 3;
  const std::string where = "(" + std::to_string(texel % size_t(image.width)) + ", " +
                            std::to_string(texel / size_t(image.width)) + ")";
  const float c = image.rgb[first];
  if (!std::isfinite(c))
    throw InputError(path + ": texel " + where + " is " + (std::isnan(c) ? "NaN" : "infinite") +
                     " (an environment map needs finite radiance >= 0)");
  throw InputError(path + ": " + std::to_string(negative) + " texel channel" + (negative == 1 ? " is" : "s are") +
                   " negative, the first at texel " + where + ", the lowest " + float_string(least) +
                   " (an environment map needs finite radiance >= 0)");
}

EnvmapTables build_envmap_tables(const EnvmapImage& image) {
  const uint32_t w = image.width, h = image.height;
  EnvmapTables t;
  t.marginal.resize(size_t(h) + 2);
  t.conditional.resize(size_t(h) * (w + 1));
  std::vector<double> row(w), rows(h);
  double total = 0.0;
  for (uint32_t y = 0; y < h; ++y) {
    double sum = 0.0;
    for (uint32_t x = 0; x < w; ++x) sum += row[x] = envmap_weight(image, x, y);
    write_cdf(row, &t.conditional[size_t(y) * (w + 1)]);
    rows[y] = sum;
    total += sum;
  }
  write_cdf(rows, t.marginal.data());
  const float scale = total > 0.0 ? float(double(w) * double(h) / total) : 0.0f;
  t.marginal[h + 1] = std::isfinite(scale) ? scale : 0.0f;
  return t;
}

bool envmap_sample(const EnvmapImage& image, const EnvmapTables& tables, float rotate_degrees, glm::vec2 u,
                   glm::vec3& dir, float& pdf) {
  const uint32_t w = image.width, h = image.height;
  pdf = 0.0f;
  const float scale = tables.marginal[h + 1];
  if (scale == 0.0f) return false;
  const float* marginal = tables.marginal.data();
  const uint32_t y = find_interval(marginal, h, u.y);
  const float dv = (u.y - marginal[y]) / (marginal[y + 1] - marginal[y]);
  const float* cdf = &tables.conditional[size_t(y) * (w + 1)];
  const uint32_t x = find_interval(cdf, w, u.x);
  const float du = (u.x - cdf[x]) / (cdf[x + 1] - cdf[x]);
  const glm::vec2 uv((float(x) + du) / float(w), (float(y) + dv) / float(h));
  dir = envmap_direction(uv, rotate_degrees);
  const float sin_theta = std::sin(kPi * uv.y);
  const float p_uv = envmap_weight(image, x, y) * scale;
  if (!(sin_theta > 0.0f) || !(p_uv > 0.0f)) return false;
  pdf = p_uv / (2.0f * kPi * kPi * sin_theta);
  return true;
}

float envmap_pdf(const EnvmapImage& image, const EnvmapTables& tables, float rotate_degrees, glm::vec3 dir) {
  // sin theta from x and z: 1 - y^2 cancels near the poles.
  const float sin_theta = std::sqrt(dir.x * dir.x + dir.z * dir.z);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const glm::uvec2 t = envmap_texel(envmap_uv(dir, rotate_degrees), image.width, image.height);
  return envmap_weight(image, t.x, t.y) * tables.marginal[image.height + 1] / (2.0f * kPi * kPi * sin_theta);
}

}  // namespace octrace
