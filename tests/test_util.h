// Helpers shared by the tests: one Vulkan context per test binary (created
// with the validation layer when OCTRACE_VALIDATION=1, as ctest sets it), and
// a check after every test that the layer stayed silent.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <utility>
#include <vector>
#include <cstdlib>
#include <memory>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/path_tracer.h"
#include "vk/context.h"

namespace octrace::test {

// The suite runs on the CPU device (lavapipe) unless OCTRACE_TEST_DEVICE
// names another (`gpu`, an index): the same tests then check a GPU driver.
inline VulkanContext& shared_context() {
  static std::unique_ptr<VulkanContext> ctx = [] {
    auto c = std::make_unique<VulkanContext>();
    const char* device = std::getenv("OCTRACE_TEST_DEVICE");
    create_context(*c, {device ? device : "cpu", false, false});
    return c;
  }();
  return *ctx;
}

// Fails the current test if the validation layer reported anything during it.
class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override { messages_before_ = validation_message_count(); }
  void TearDown() override {
    EXPECT_EQ(validation_message_count(), messages_before_) << "the validation layer reported messages";
  }

 private:
  uint32_t messages_before_ = 0;
};

// The `--json` summary in a process's output (stdout and stderr together):
// from its first '{' to its last '}', so that lines around it (a warning
// before, a sanitizer's suppression report after) are left out; a discarded
// value (is_discarded()) if there is none or it does not parse.
inline nlohmann::json json_of(const std::string& output) {
  const auto first = output.find('{'), last = output.rfind('}');
  if (first == std::string::npos || last == std::string::npos || last < first)
    return nlohmann::json::value_t::discarded;
  return nlohmann::json::parse(output.substr(first, last - first + 1), nullptr, false);
}

inline std::string tmp_path(const std::string& name) { return std::string(OCTRACE_TEST_TMP) + "/" + name; }

struct RunResult {
  int code;
  std::string output;  // stdout and stderr together
};

// Runs the octrace binary with `args` (after environment assignments `env`).
inline RunResult run_octrace(const std::string& args, const std::string& env = "") {
  std::string cmd = env + " " + OCTRACE_BIN + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  RunResult r{-1, ""};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Ray/sphere in double, in the form that keeps precision for small spheres far
// from the origin (Haines et al., "Precision Improvements for Ray/Sphere
// Intersection", Ray Tracing Gems ch. 7): the nearest t > 0 along the unit
// direction d, or +infinity. The tests' reference for the shader's float test.
inline double ray_sphere(glm::dvec3 o, glm::dvec3 d, glm::dvec3 center, double r) {
  const glm::dvec3 f = o - center;
  const double b = glm::dot(f, d);
  const glm::dvec3 l = f - b * d;
  const double disc = r * r - glm::dot(l, l);
  if (disc < 0.0) return std::numeric_limits<double>::infinity();
  const double c = glm::dot(f, f) - r * r;
  const double q = -b - std::copysign(std::sqrt(disc), b);
  const double t0 = std::min(c / q, q), t1 = std::max(c / q, q);
  if (t0 > 0.0) return t0;
  if (t1 > 0.0) return t1;
  return std::numeric_limits<double>::infinity();
}

// The message of the InputError that `f` throws, or a test failure if it throws none.
template <typename F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return {};
}

// Materials for scenes built in tests.
inline Material lambertian(glm::vec3 albedo) { return {MaterialType::Lambertian, albedo}; }
inline Material lambertian(float albedo) { return lambertian(glm::vec3(albedo)); }
inline Material metal(glm::vec3 albedo, float fuzz) { return {MaterialType::Metal, albedo, fuzz}; }
inline Material metal(float albedo, float fuzz) { return metal(glm::vec3(albedo), fuzz); }
inline Material glass(float ior) {
  Material m;
  m.type = MaterialType::Dielectric;
  m.ior = ior;
  return m;
}
// glTF's metallic-roughness material (ior 1.5).
inline Material pbr(float base_color, float metallic, float roughness) {
  Material m;
  m.type = MaterialType::Pbr;
  m.albedo = glm::vec3(base_color);
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}
inline Material emitter(glm::vec3 radiance) {
  Material m;
  m.type = MaterialType::Emissive;
  m.radiance = radiance;
  return m;
}

// Punctual lights built in tests (white; the other fields as Light's defaults).
inline Light point_light(glm::vec3 position, float intensity = 1.0f) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.intensity = intensity;
  return l;
}
// `direction`: where the light travels (unit).
inline Light directional_light(glm::vec3 direction, float intensity = 1.0f) {
  Light l;
  l.type = LightType::Directional;
  l.direction = direction;
  l.intensity = intensity;
  return l;
}

// Meshes built in tests (object space, counter-clockwise = front).

// A closed icosphere of radius 1 about the origin: the icosahedron (its
// vertices (0, ±1, ±φ) and their cyclic permutations, symmetric under every
// sign flip of an axis) with each face cut `subdivisions` times into four,
// new vertices pushed onto the sphere. Outward winding; `smooth` adds vertex
// normals (the unit positions).
inline Mesh icosphere(int subdivisions, uint32_t material, bool smooth = false) {
  const float phi = (1.0f + std::sqrt(5.0f)) / 2.0f;
  Mesh m;
  m.name = "icosphere";
  for (glm::vec3 v : {glm::vec3(-1, phi, 0), glm::vec3(1, phi, 0), glm::vec3(-1, -phi, 0), glm::vec3(1, -phi, 0),
                      glm::vec3(0, -1, phi), glm::vec3(0, 1, phi), glm::vec3(0, -1, -phi), glm::vec3(0, 1, -phi),
                      glm::vec3(phi, 0, -1), glm::vec3(phi, 0, 1), glm::vec3(-phi, 0, -1), glm::vec3(-phi, 0, 1)})
    m.positions.push_back(glm::normalize(v));
  m.indices = {0, 11, 5, 0, 5, 1,  0, 1, 7,   0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2, 10, 7, 6, 7, 1, 8,
               3, 9, 4, 3, 4, 2,  3, 2, 6,   3, 6, 8,  3, 8, 9,   4, 9, 5, 2, 4, 11, 6, 2, 10,  8, 6, 7, 9, 8, 1};
  for (int level = 0; level < subdivisions; ++level) {
    std::vector<uint32_t> next;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      return mid[key] = uint32_t(m.positions.size() - 1);
    };
    for (size_t k = 0; k < m.indices.size(); k += 3) {
      const uint32_t a = m.indices[k], b = m.indices[k + 1], c = m.indices[k + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices = std::move(next);
  }
  if (smooth) m.normals = m.positions;
  m.materials.assign(m.triangle_count(), material);
  return m;
}

// A flat n x n grid of unit quads on z = 0 from (0,0) to (n,n), facing +z;
// each quad is two triangles split along its (x,y)-(x+1,y+1) diagonal.
inline Mesh grid(int n, uint32_t material) {
  Mesh m;
  m.name = "grid";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.positions.push_back({float(x), float(y), 0.0f});
  const auto at = [&](int x, int y) { return uint32_t(y * (n + 1) + x); };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      m.indices.insert(m.indices.end(), {at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y), at(x + 1, y + 1), at(x, y + 1)});
  m.materials.assign(m.triangle_count(), material);
  return m;
}

// Adds `mesh` to the scene, placed once with `transform`.
inline void place(Scene& s, Mesh mesh, const glm::mat4& transform = glm::mat4(1.0f)) {
  s.meshes.push_back(std::move(mesh));
  s.instances.push_back({uint32_t(s.meshes.size() - 1), transform});
}

// A scene of `spheres` under a uniform sky, camera looking at the origin.
// An environment map built in code (the tests write no files unless they test
// loading): w x h texels of a smooth sky, brighter and bluer towards +y with
// a warm band at the horizon, and, if `sun` > 0, one texel of that value at
// (3w/8, h/4) (45 degrees up, towards -x and -z).
inline EnvmapImage test_envmap(uint32_t w, uint32_t h, float sun = 0.0f) {
  EnvmapImage m{w, h, std::vector<float>(size_t(w) * h * 3)};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const float up = 1.0f - (float(y) + 0.5f) / float(h);                 // 1 at +y, 0 at -y
      const float band = std::exp(-40.0f * (up - 0.5f) * (up - 0.5f));      // the horizon
      const float ripple = 0.2f * (1.0f + std::sin(6.2831853f * float(x) / float(w)));
      float* c = &m.rgb[3 * (size_t(y) * w + x)];
      c[0] = 0.2f + 0.4f * up + 0.8f * band + ripple;
      c[1] = 0.2f + 0.6f * up + 0.4f * band + ripple;
      c[2] = 0.3f + 1.2f * up + 0.1f * band;
    }
  if (sun > 0.0f)
    for (int k = 0; k < 3; ++k) m.rgb[3 * (size_t(h / 4) * w + 3 * w / 8) + k] = sun;
  return m;
}

inline Sky envmap_sky(EnvmapImage image, float strength = 1.0f, float rotate = 0.0f) {
  Sky sky;
  sky.type = SkyType::Envmap;
  sky.file = "test.exr";
  sky.strength = strength;
  sky.rotate = rotate;
  sky.image = std::move(image);
  return sky;
}

inline Scene furnace_scene() {
  Scene s;
  s.sky.type = SkyType::Uniform;
  s.sky.radiance = glm::vec3(1.0f);
  s.camera.lookfrom = {0, 0, 6};
  s.camera.lookat = {0, 0, 0};
  s.camera.vfov = 40;
  s.camera.aperture = 0;
  s.camera.focus_dist = 6;
  return s;
}

// Light trapped in a closed mirror sphere (r 5, fuzz 0.6) around 20,000
// white diffuse spheres (r 0.04) and one small emitter, the camera inside:
// paths of 300 bounces walk the tree thousands of steps, past llvmpipe's
// limit of 65,535 loop iterations an invocation (RenderResult::cut_paths).
inline Scene light_trap_scene() {
  Scene scene = furnace_scene();
  scene.sky.radiance = glm::vec3(0.0f);  // light from the emitter only
  scene.camera.lookfrom = {0, 0, 4.5f};  // inside the mirror sphere
  scene.camera.vfov = 60;
  scene.materials = {{MaterialType::Metal, glm::vec3(1.0f), 0.6f}, {MaterialType::Lambertian, glm::vec3(1.0f)}, {}};
  scene.materials[2].type = MaterialType::Emissive;
  scene.materials[2].radiance = glm::vec3(4.0f);
  scene.spheres = {{{0, 0, 0}, 5.0f, 0}, {{3, 3, 0}, 0.15f, 2}};
  uint32_t state = 3;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 6.8f - 3.4f;
  };
  while (scene.spheres.size() < 20002) {
    const glm::vec3 c(next(), next(), next());
    if (glm::dot(c, c) > 3.4f * 3.4f || (c.x * c.x + c.y * c.y < 0.3f && c.z > 0)) continue;
    scene.spheres.push_back({c, 0.04f, 1});
  }
  return scene;
}

}  // namespace octrace::test
