// The built-in rtiow scene and the checks every scene passes before it is rendered.
#include "scene/scene.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "core/errors.h"
#include "core/text.h"

namespace octrace {
namespace {

// ---------------------------------------------------------------------------
// rtiow generator
//
// The book places one sphere per unit cell of a 22x22 grid and skips those that
// touch the big metal sphere. To place any number N of spheres of any radius R
// without overlaps, the 20x20 field [-10,10]^2 (x, z) is cut into g x g cells of
// edge c = 20/g. A sphere stays inside its cell (its centre moves at most
// (c - 2R - kGap) / 2 either way from the cell centre), so neighbours never touch.
// Cells from which a sphere could touch one of the three big spheres are left
// out, g is grown until at least N cells remain, and N of them are drawn
// uniformly (Knuth's selection sampling, TAOCP vol. 2, 3.4.2 algorithm S), so the
// spheres spread over the whole field in one pass without storing the cells.
//
// When N spheres of radius R do not fit (c < 2R + kGap), the spheres sit at their
// cell centres and overlap their neighbours: the field just gets denser. When R
// is so large that the big spheres' keep-out zones leave too little of the
// field, the keep-out is dropped too and small spheres may cut into big ones.
// ---------------------------------------------------------------------------

constexpr double kFieldHalf = 10.0;
// Clearance kept between neighbouring small spheres, so that rounding the centres
// to float (at most ulp(10)/2 ~ 5e-7 per coordinate) cannot make them overlap.
constexpr double kGap = 1e-5;
constexpr uint64_t kMaxSpheres = 100'000'000;

// The three radius-1 spheres standing on the ground at y = 1 (docs/design.md).
constexpr double kBigX[3] = {0.0, -4.0, 4.0};

struct Grid {
  uint64_t g = 0;         // cells per side
  double cell = 0.0;      // cell edge
  double span = 0.0;      // range of a centre coordinate inside its cell
  double keep_out = 0.0;  // least horizontal distance of a small centre from a big one
};

Grid make_grid(uint64_t g, double radius, double keep_out) {
  const double cell = 2.0 * kFieldHalf / static_cast<double>(g);
  return {g, cell, std::max(0.0, cell - 2.0 * radius - kGap), keep_out};
}

// Whether some centre the cell allows lies within keep_out of a big sphere's centre.
bool cell_blocked(const Grid& grid, uint64_t i, uint64_t j) {
  const double mid_x = -kFieldHalf + (static_cast<double>(i) + 0.5) * grid.cell;
  const double mid_z = -kFieldHalf + (static_cast<double>(j) + 0.5) * grid.cell;
  const double dz = std::max(0.0, std::abs(mid_z) - 0.5 * grid.span);
  for (double big_x : kBigX) {
    const double dx = std::max(0.0, std::abs(mid_x - big_x) - 0.5 * grid.span);
    if (dx * dx + dz * dz < grid.keep_out * grid.keep_out) return true;
  }
  return false;
}

// Cells left once the blocked ones are out; only cells near the big spheres are visited.
uint64_t free_cells(const Grid& grid) {
  const double reach = grid.keep_out + grid.cell;
  const auto to_cell = [&](double x) {
    const double c = std::floor((x + kFieldHalf) / grid.cell);
    return static_cast<uint64_t>(std::clamp(c, 0.0, static_cast<double>(grid.g - 1)));
  };
  uint64_t blocked = 0;
  for (uint64_t i = to_cell(kBigX[1] - reach); i <= to_cell(kBigX[2] + reach); ++i) {
    for (uint64_t j = to_cell(-reach); j <= to_cell(reach); ++j) blocked += cell_blocked(grid, i, j);
  }
  return grid.g * grid.g - blocked;
}

Grid choose_grid(uint64_t n, double radius) {
  // A small sphere (centre height R) and a big one (centre height 1, radius 1)
  // touch when d^2 + (1 - R)^2 = (1 + R)^2, i.e. at horizontal distance d = 2 sqrt(R).
  const double keep_out = 2.0 * std::sqrt(radius) + kGap;
  const auto g0 = static_cast<uint64_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  Grid grid = make_grid(g0, radius, keep_out);
  for (uint64_t free = free_cells(grid); free < n; free = free_cells(grid)) {
    // Jump to the side length the current free fraction calls for; at least one step.
    const double want = std::ceil(static_cast<double>(grid.g) *
                                  std::sqrt(static_cast<double>(n) / std::max(1.0, static_cast<double>(free))));
    const uint64_t g = std::max(grid.g + 1, static_cast<uint64_t>(want));
    if (g > 4 * g0 + 64) return make_grid(g0, radius, 0.0);
    grid = make_grid(g, radius, keep_out);
  }
  return grid;
}

// [0,1) from the top 53 bits. std::uniform_real_distribution would do, but its
// algorithm is left to the implementation and scenes must not differ by compiler.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }

void add_small_material(Scene& scene, std::mt19937_64& rng, uint32_t shared_glass) {
  Material m;
  const double choice = unit(rng);
  if (choice < 0.8) {
    for (int c = 0; c < 3; ++c) m.albedo[c] = static_cast<float>(unit(rng) * unit(rng));
  } else if (choice < 0.95) {
    m.type = MaterialType::Metal;
    for (int c = 0; c < 3; ++c) m.albedo[c] = static_cast<float>(0.5 + 0.5 * unit(rng));
    m.fuzz = static_cast<float>(0.5 * unit(rng));
  } else {
    scene.spheres.back().material = shared_glass;
    return;
  }
  scene.spheres.back().material = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(m);
}

// ---------------------------------------------------------------------------
// validation
// ---------------------------------------------------------------------------

std::string format(float v) { return float_string(v); }
std::string format(glm::vec3 v) { return vec3_string(v); }

[[noreturn]] void invalid(const std::string& source, const std::string& path, const std::string& what) {
  throw InputError(source + ": " + path + ": " + what);
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_finite(glm::vec3 v, const std::string& source, const std::string& path) {
  if (!finite(v)) invalid(source, path, "must be 3 finite numbers, got " + format(v));
}

void check_colour(glm::vec3 v, const std::string& source, const std::string& path) {
  if (!finite(v) || v.x < 0.0f || v.y < 0.0f || v.z < 0.0f)
    invalid(source, path, "must be 3 finite numbers >= 0, got " + format(v));
}

void check_positive(float v, const std::string& source, const std::string& path) {
  if (!(std::isfinite(v) && v > 0.0f)) invalid(source, path, "must be a finite number > 0, got " + format(v));
}

// NaN fails both comparisons.
void check_unit(float v, const std::string& source, const std::string& path) {
  if (!(v >= 0.0f && v <= 1.0f)) invalid(source, path, "must be a number in [0, 1], got " + format(v));
}

void validate_camera(const Camera& c, const std::string& source) {
  check_finite(c.lookfrom, source, "camera.lookfrom");
  check_finite(c.lookat, source, "camera.lookat");
  check_finite(c.vup, source, "camera.vup");
  if (!(std::isfinite(c.vfov) && c.vfov > 0.0f && c.vfov < 180.0f))
    invalid(source, "camera.vfov", "must be a finite number in (0, 180) degrees, got " + format(c.vfov));
  if (!(std::isfinite(c.aperture) && c.aperture >= 0.0f))
    invalid(source, "camera.aperture", "must be a finite number >= 0, got " + format(c.aperture));
  check_positive(c.focus_dist, source, "camera.focus_dist");
  // In double, so that distant or tiny camera set-ups do not overflow or flush to zero.
  const glm::dvec3 dir = glm::dvec3(c.lookat) - glm::dvec3(c.lookfrom);
  const glm::dvec3 vup(c.vup);
  if (dir == glm::dvec3(0.0)) invalid(source, "camera.lookat", "must differ from camera.lookfrom");
  if (vup == glm::dvec3(0.0)) invalid(source, "camera.vup", "must not be the zero vector");
  // The camera basis is built from cross(vup, -dir); below this sine it is noise.
  if (glm::length(glm::cross(glm::normalize(vup), glm::normalize(dir))) < 1e-6)
    invalid(source, "camera.vup", "must not be parallel to the view direction (lookat - lookfrom), got " +
                                      format(c.vup));
}

void validate_sky(const Sky& sky, const std::string& source) {
  switch (sky.type) {
    case SkyType::Gradient:
      check_colour(sky.down, source, "sky.down");
      check_colour(sky.up, source, "sky.up");
      return;
    case SkyType::Uniform:
      check_colour(sky.radiance, source, "sky.radiance");
      return;
    case SkyType::None:
      return;
    case SkyType::Envmap: {
      if (!(std::isfinite(sky.strength) && sky.strength >= 0.0f))
        invalid(source, "sky.strength", "must be a finite number >= 0, got " + format(sky.strength));
      if (!std::isfinite(sky.rotate)) invalid(source, "sky.rotate", "must be a finite number, got " + format(sky.rotate));
      const EnvmapImage& image = sky.image;
      if (image.width == 0 || image.height == 0 || image.rgb.size() != size_t(image.width) * image.height * 3)
        invalid(source, "sky.file", sky.file + ": an environment map needs an image of at least 1x1 texels");
      for (float c : image.rgb)
        if (!(std::isfinite(c) && c >= 0.0f))
          invalid(source, "sky.file", sky.file + ": every texel must be finite and >= 0");
      return;
    }
  }
  invalid(source, "sky.type", "unknown sky type " + std::to_string(static_cast<uint32_t>(sky.type)));
}

void validate_light(const Light& l, const std::string& source, size_t index) {
  const std::string path = "lights[" + std::to_string(index) + "]";
  if (l.type != LightType::Point && l.type != LightType::Spot && l.type != LightType::Directional)
    invalid(source, path + ".type", "unknown light type " + std::to_string(static_cast<uint32_t>(l.type)));
  check_colour(l.color, source, path + ".color");
  if (!(std::isfinite(l.intensity) && l.intensity >= 0.0f))
    invalid(source, path + ".intensity", "must be a finite number >= 0, got " + format(l.intensity));
  if (l.type != LightType::Directional) check_finite(l.position, source, path + ".position");
  if (l.type != LightType::Point) {
    check_finite(l.direction, source, path + ".direction");
    if (std::abs(glm::length(glm::dvec3(l.direction)) - 1.0) > 1e-5)
      invalid(source, path + ".direction", "must be a unit vector, got " + format(l.direction));
  }
  if (l.type == LightType::Spot) {
    if (!(l.outer_cone > 0.0f && l.outer_cone <= 90.0f))
      invalid(source, path + ".outer_cone", "must be a number in (0, 90] degrees, got " + format(l.outer_cone));
    if (!(l.inner_cone >= 0.0f && l.inner_cone < l.outer_cone))
      invalid(source, path + ".inner_cone", "must be a number in [0, outer_cone) degrees, got " + format(l.inner_cone));
  }
}

// "index 9 out of range (3 materials)".
std::string out_of_range(size_t index, size_t size, const char* one, const char* many) {
  return "index " + std::to_string(index) + " out of range (" + std::to_string(size) + " " + (size == 1 ? one : many) +
         ")";
}

void validate_material(const Material& m, const Scene& scene, const std::string& source, size_t index) {
  const std::string path = "materials[" + std::to_string(index) + "]";
  const bool emits = m.emission != glm::vec3(0.0f) || m.emission_texture;
  const bool surface = m.type == MaterialType::Lambertian || m.type == MaterialType::Pbr;
  if (!surface && (m.base_color_texture || emits))
    invalid(source, path,
            "only lambertian and pbr materials take textures and an emission (an emissive one has a radiance)");
  if (m.type != MaterialType::Pbr && m.metallic_roughness_texture)
    invalid(source, path, "only pbr materials take a metallic-roughness texture");
  if (m.type != MaterialType::Pbr && (m.transmission_texture || m.attenuation_color != glm::vec3(1.0f) ||
                                      m.attenuation_distance != INFINITY))
    invalid(source, path, "only pbr materials take a transmission texture and an attenuation");
  for (const MaterialTexture& t : kMaterialTextures)
    if (const std::optional<uint32_t>& texture = m.*t.index; texture && *texture >= scene.textures.size())
      invalid(source, path + "." + t.field, out_of_range(*texture, scene.textures.size(), "texture", "textures"));
  switch (m.type) {
    case MaterialType::Lambertian:
      check_colour(m.albedo, source, path + ".albedo");
      check_colour(m.emission, source, path + ".emission");
      return;
    case MaterialType::Metal:
      check_colour(m.albedo, source, path + ".albedo");
      check_unit(m.fuzz, source, path + ".fuzz");
      return;
    case MaterialType::Dielectric:
      check_positive(m.ior, source, path + ".ior");
      return;
    case MaterialType::Emissive:
      check_colour(m.radiance, source, path + ".radiance");
      return;
    case MaterialType::Pbr:
      // glTF's baseColorFactor is in [0, 1]; above 1 the surface would make light.
      if (!(m.albedo.x >= 0.0f && m.albedo.x <= 1.0f && m.albedo.y >= 0.0f && m.albedo.y <= 1.0f &&
            m.albedo.z >= 0.0f && m.albedo.z <= 1.0f))
        invalid(source, path + ".base_color", "must be 3 numbers in [0, 1], got " + format(m.albedo));
      check_unit(m.metallic, source, path + ".metallic");
      check_unit(m.roughness, source, path + ".roughness");
      check_colour(m.emission, source, path + ".emission");
      check_unit(m.transmission, source, path + ".transmission");
      check_positive(m.ior, source, path + ".ior");
      if (m.alpha_mode != AlphaMode::Opaque && m.alpha_mode != AlphaMode::Mask && m.alpha_mode != AlphaMode::Blend)
        invalid(source, path + ".alpha_mode",
                "unknown alpha mode " + std::to_string(static_cast<uint32_t>(m.alpha_mode)));
      if (!(m.alpha_cutoff >= 0.0f && std::isfinite(m.alpha_cutoff)))
        invalid(source, path + ".alpha_cutoff", "must be a finite number >= 0, got " + format(m.alpha_cutoff));
      check_unit(m.alpha, source, path + ".alpha");
      if (!(m.attenuation_color.x >= 0.0f && m.attenuation_color.x <= 1.0f && m.attenuation_color.y >= 0.0f &&
            m.attenuation_color.y <= 1.0f && m.attenuation_color.z >= 0.0f && m.attenuation_color.z <= 1.0f))
        invalid(source, path + ".attenuation_color", "must be 3 numbers in [0, 1], got " + format(m.attenuation_color));
      if (!(m.attenuation_distance > 0.0f))
        invalid(source, path + ".attenuation_distance",
                "must be a number > 0 (infinite: no absorption), got " + format(m.attenuation_distance));
      return;
  }
  invalid(source, path + ".type", "unknown material type " + std::to_string(static_cast<uint32_t>(m.type)));
}

void validate_mesh(const Mesh& m, const Scene& scene, const std::string& source, size_t index) {
  const std::string path = "meshes[" + std::to_string(index) + "]";
  const auto element = [&](const char* field, size_t i) { return path + "." + field + "[" + std::to_string(i) + "]"; };
  const size_t vertices = m.positions.size();
  for (size_t i = 0; i < vertices; ++i)
    if (!finite(m.positions[i])) check_finite(m.positions[i], source, element("positions", i));
  if (!m.normals.empty() && m.normals.size() != vertices)
    invalid(source, path + ".normals", std::to_string(m.normals.size()) + " normals for " + std::to_string(vertices) +
                                          " positions (must be as many, or none)");
  for (size_t i = 0; i < m.normals.size(); ++i)
    if (!finite(m.normals[i])) check_finite(m.normals[i], source, element("normals", i));
  if (!m.tangents.empty() && m.tangents.size() != vertices)
    invalid(source, path + ".tangents", std::to_string(m.tangents.size()) + " tangents for " +
                                            std::to_string(vertices) + " positions (must be as many, or none)");
  if (!m.tangents.empty() && m.normals.empty()) invalid(source, path + ".tangents", "tangents need normals");
  for (size_t i = 0; i < m.tangents.size(); ++i) {
    const glm::vec4 t = m.tangents[i];
    if (!finite(glm::vec3(t)) || !(t.w == 1.0f || t.w == -1.0f || t == glm::vec4(0.0f)))
      invalid(source, element("tangents", i),
              "must be a finite tangent with w = 1 or -1 (or all 0: none), got [" + format(t.x) + ", " + format(t.y) +
                  ", " + format(t.z) + ", " + format(t.w) + "]");
  }
  if (!m.uvs.empty() && m.uvs.size() != vertices)
    invalid(source, path + ".uvs", std::to_string(m.uvs.size()) + " uvs for " + std::to_string(vertices) +
                                       " positions (must be as many, or none)");
  for (size_t i = 0; i < m.uvs.size(); ++i)
    if (!std::isfinite(m.uvs[i].x) || !std::isfinite(m.uvs[i].y))
      invalid(source, element("uvs", i),
              "must be 2 finite numbers, got [" + format(m.uvs[i].x) + ", " + format(m.uvs[i].y) + "]");
  if (m.indices.size() % 3)
    invalid(source, path + ".indices", std::to_string(m.indices.size()) + " indices do not make whole triangles");
  for (size_t i = 0; i < m.indices.size(); ++i)
    if (m.indices[i] >= vertices)
      invalid(source, element("indices", i), out_of_range(m.indices[i], vertices, "vertex", "vertices"));
  if (m.materials.size() != m.triangle_count())
    invalid(source, path + ".materials", std::to_string(m.materials.size()) + " materials for " +
                                             std::to_string(m.triangle_count()) + " triangles (must be one each)");
  for (size_t i = 0; i < m.materials.size(); ++i)
    if (m.materials[i] >= scene.materials.size())
      invalid(source, element("materials", i), out_of_range(m.materials[i], scene.materials.size(), "material", "materials"));
}

void validate_texture(const Texture& t, const std::string& source, size_t index) {
  const std::string path = "textures[" + std::to_string(index) + "]";
  if (t.width == 0 || t.height == 0)
    invalid(source, path, "must be at least 1x1 texels, got " + std::to_string(t.width) + "x" + std::to_string(t.height));
  if (t.texels.size() != uint64_t(t.width) * t.height)
    invalid(source, path + ".texels", std::to_string(t.texels.size()) + " texels for " + std::to_string(t.width) + "x" +
                                          std::to_string(t.height));
  for (const auto& [wrap, field] : {std::pair{t.wrap_s, ".wrap_s"}, std::pair{t.wrap_t, ".wrap_t"}})
    if (wrap != Wrap::Repeat && wrap != Wrap::ClampToEdge && wrap != Wrap::MirroredRepeat)
      invalid(source, path + field, "unknown wrap mode " + std::to_string(static_cast<uint32_t>(wrap)));
}

void validate_instance(const Instance& in, const Scene& scene, const std::string& source, size_t index) {
  const std::string path = "instances[" + std::to_string(index) + "]";
  if (in.mesh >= scene.meshes.size())
    invalid(source, path + ".mesh", out_of_range(in.mesh, scene.meshes.size(), "mesh", "meshes"));
  const glm::mat4& t = in.transform;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(t[c][r])) invalid(source, path + ".transform", "must be 16 finite numbers");
  // The renderer takes rays into the instance through the inverse.
  if (t[0][3] != 0.0f || t[1][3] != 0.0f || t[2][3] != 0.0f || t[3][3] != 1.0f)
    invalid(source, path + ".transform", "must be an affine transform (last row 0, 0, 0, 1)");
  if (glm::determinant(glm::dmat3(glm::mat3(t))) == 0.0) invalid(source, path + ".transform", "must be invertible");
}

}  // namespace

uint64_t unique_triangle_count(const Scene& scene) {
  uint64_t n = 0;
  for (const Mesh& m : scene.meshes) n += m.triangle_count();
  return n;
}

uint64_t instanced_triangle_count(const Scene& scene) {
  uint64_t n = 0;
  for (const Instance& i : scene.instances) n += i.mesh < scene.meshes.size() ? scene.meshes[i.mesh].triangle_count() : 0;
  return n;
}

void check_rtiow_params(const RtiowParams& params) {
  if (!(std::isfinite(params.radius) && params.radius > 0.0f))
    throw SettingError("rtiow.radius", ": must be a finite number > 0, got " + format(params.radius));
  if (params.spheres > kMaxSpheres)
    throw SettingError("rtiow.spheres", ": at most " + std::to_string(kMaxSpheres) + " small spheres, got " +
                                            std::to_string(params.spheres));
}

Scene make_rtiow_scene(const RtiowParams& params) {
  check_rtiow_params(params);

  Scene scene;  // the camera defaults are the study's rtiow camera
  const auto lambertian = [](glm::vec3 albedo) { Material m; m.albedo = albedo; return m; };
  Material glass;
  glass.type = MaterialType::Dielectric;
  glass.ior = 1.5f;
  Material metal;
  metal.type = MaterialType::Metal;
  metal.albedo = {0.7f, 0.6f, 0.5f};
  metal.fuzz = 0.0f;
  scene.materials = {lambertian(glm::vec3(0.5f)), glass, lambertian({0.4f, 0.2f, 0.1f}), metal};
  scene.spheres = {{{0.0f, -1000.0f, 0.0f}, 1000.0f, 0},
                   {{0.0f, 1.0f, 0.0f}, 1.0f, 1},
                   {{-4.0f, 1.0f, 0.0f}, 1.0f, 2},
                   {{4.0f, 1.0f, 0.0f}, 1.0f, 3}};
  const uint32_t shared_glass = 1;  // small glass spheres share the big one's material
  if (params.spheres == 0) return scene;

  scene.spheres.reserve(scene.spheres.size() + params.spheres);
  scene.materials.reserve(scene.materials.size() + params.spheres);
  std::mt19937_64 rng(params.seed);
  const double radius = params.radius;
  const Grid grid = choose_grid(params.spheres, radius);
  uint64_t free_left = free_cells(grid);
  uint64_t needed = params.spheres;
  for (uint64_t i = 0; i < grid.g && needed > 0; ++i) {
    for (uint64_t j = 0; j < grid.g && needed > 0; ++j) {
      if (cell_blocked(grid, i, j)) continue;
      // Algorithm S: take this cell with probability needed / free_left (in integers,
      // so that the last cells are taken for sure when free_left == needed).
      if (rng() % free_left-- >= needed) continue;
      --needed;
      const double x = -kFieldHalf + (static_cast<double>(i) + 0.5) * grid.cell + (unit(rng) - 0.5) * grid.span;
      const double z = -kFieldHalf + (static_cast<double>(j) + 0.5) * grid.cell + (unit(rng) - 0.5) * grid.span;
      scene.spheres.push_back({{static_cast<float>(x), params.radius, static_cast<float>(z)}, params.radius, 0});
      add_small_material(scene, rng, shared_glass);
    }
  }
  return scene;
}

void validate_scene(const Scene& scene, const std::string& source) {
  validate_camera(scene.camera, source);
  validate_sky(scene.sky, source);
  for (size_t i = 0; i < scene.textures.size(); ++i) validate_texture(scene.textures[i], source, i);
  for (size_t i = 0; i < scene.materials.size(); ++i) validate_material(scene.materials[i], scene, source, i);
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const auto path = [&](const char* field) { return "spheres[" + std::to_string(i) + "]." + field; };
    if (!finite(s.center)) check_finite(s.center, source, path("center"));
    if (!(std::isfinite(s.radius) && s.radius > 0.0f)) check_positive(s.radius, source, path("radius"));
    if (s.material >= scene.materials.size())
      invalid(source, path("material"), out_of_range(s.material, scene.materials.size(), "material", "materials"));
  }
  for (size_t i = 0; i < scene.meshes.size(); ++i) validate_mesh(scene.meshes[i], scene, source, i);
  for (size_t i = 0; i < scene.instances.size(); ++i) validate_instance(scene.instances[i], scene, source, i);
  for (size_t i = 0; i < scene.lights.size(); ++i) validate_light(scene.lights[i], source, i);
  if (scene.mesh_file_lights > scene.lights.size())
    invalid(source, "lights", std::to_string(scene.mesh_file_lights) + " from mesh files, but only " +
                                  std::to_string(scene.lights.size()) + " in all");
  if (scene.mesh_file_materials > scene.materials.size())
    invalid(source, "materials", std::to_string(scene.mesh_file_materials) + " from mesh files, but only " +
                                     std::to_string(scene.materials.size()) + " in all");
  for (size_t i = 0; i < scene.mesh_refs.size(); ++i) {
    const std::optional<uint32_t>& m = scene.mesh_refs[i].material;
    if (m && *m >= scene.materials.size())
      invalid(source, "mesh_refs[" + std::to_string(i) + "].material",
              out_of_range(*m, scene.materials.size(), "material", "materials"));
  }
}

}  // namespace octrace
