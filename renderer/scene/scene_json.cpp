// Scene <-> JSON, the format of README "Scene format".
//
// Required and optional fields:
//   top level     "materials" is required (it may be empty); "spheres",
//                 "meshes", "camera" and "sky" are optional.
//   camera        every field is optional; the defaults are Camera's in scene.h
//                 (the rtiow camera).
//   sky           optional as a whole (default: the book's gradient); if given,
//                 "type" is required; gradient "down"/"up" are optional (the
//                 book's white and blue); uniform "radiance" is required;
//                 envmap "file" (relative to the scene file, read when the
//                 scene loads) is required, "strength" (1) and "rotate" (0,
//                 degrees) are optional.
//   materials[i]  "type" is required; lambertian/metal "albedo" and emissive
//                 "radiance" are required; metal "fuzz" is optional (0: a mirror),
//                 dielectric "ior" is optional (1.5: glass); every pbr field
//                 is optional, with glTF's defaults: "base_color" [1, 1, 1],
//                 "metallic" 1, "roughness" 1, "emission" [0, 0, 0],
//                 "transmission" 0 (> 0: the material bounds a closed solid
//                 of index "ior", on spheres and meshes alike) and "ior" 1.5.
//   spheres[i]    "center", "radius" and "material" are all required.
//   lights[i]     optional list of punctual lights (scene.h Light): "type"
//                 (point | spot | directional) is required; point and spot
//                 "position" and spot and directional "direction" (any
//                 non-zero vector, normalised) are required; "color" [1, 1, 1]
//                 and "intensity" 1 are optional (radiant intensity for point
//                 and spot, irradiance for directional); spot "inner_cone" 0
//                 and "outer_cone" 45 (degrees) are optional.
//   meshes[i]     a glTF file: "file" (relative to the scene file) is required;
//                 "material" (overrides the file's materials), "scene" (which
//                 of the file's scenes) and "transform" ({"scale", "rotate",
//                 "translate"} or {"matrix"}) are optional. Written back as
//                 references, the transform as a matrix; the files' own
//                 materials are not written.
// Any other key is an error, a field of another material or sky type included,
// so that a typo never silently turns into a default. Fields a type does not use
// are neither written nor read; they load as scene.h's defaults.
//
// Numbers go straight to float: the JSON type below stores floats, which
// nlohmann parses with strtof (correctly rounded; going through double could
// round twice), and they are written with std::to_chars, the shortest text that
// reads back to the same float. So a round trip is bit-exact and 0.2f is written
// as 0.2.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "io/file.h"
#include "core/errors.h"
#include "scene/envmap.h"
#include "scene/gltf.h"
#include "scene/json_text.h"
#include "scene/scene.h"

namespace octrace {
namespace {

using Json = nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t, std::uint64_t, float>;

// Indexed by the enum values.
constexpr std::string_view kMaterialNames[] = {"lambertian", "metal", "dielectric", "emissive", "pbr"};
constexpr std::string_view kSkyNames[] = {"gradient", "uniform", "none", "envmap"};
constexpr std::string_view kLightNames[] = {"point", "spot", "directional"};

// ---------------------------------------------------------------------------
// reading
// ---------------------------------------------------------------------------

// A JSON value and where it sits in the file. The path ("spheres[12].radius") is
// spelled out only when an error needs it, so reading a million spheres builds
// no strings.
struct Node {
  const Json* value;
  const std::string* source;
  const Node* parent = nullptr;
  std::string_view key{};  // member name, unless is_element
  bool is_element = false;
  size_t index = 0;

  std::string path() const { return json_path(*this); }

  [[noreturn]] void fail(const std::string& what) const {
    const std::string p = path();
    throw InputError(*source + ": " + (p.empty() ? "" : p + ": ") + what);
  }

  Node member(std::string_view name, const Json* v) const { return {v, source, this, name}; }
  Node element(size_t i, const Json* v) const { return {v, source, this, {}, true, i}; }
  Node element(size_t i) const { return element(i, &(*value)[i]); }

  std::optional<Node> find(const char* name) const {
    const auto it = value->find(name);
    if (it == value->end()) return std::nullopt;
    return member(name, &*it);
  }

  Node require(const char* name) const {
    const std::optional<Node> n = find(name);
    if (!n) member(name, nullptr).fail("missing required field");
    return *n;
  }
};

template <typename Names>
std::string join(const Names& names) {
  std::string out;
  for (std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

void require_object(const Node& n) {
  if (!n.value->is_object()) n.fail("expected an object, got " + describe_json(*n.value));
}

void require_array(const Node& n) {
  if (!n.value->is_array()) n.fail("expected an array, got " + describe_json(*n.value));
}

void check_keys(const Node& n, std::initializer_list<std::string_view> allowed) {
  for (auto it = n.value->begin(); it != n.value->end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end())
      n.member(it.key(), &*it).fail("unknown key (expected " + join(allowed) + ")");
  }
}

float read_float(const Node& n) {
  if (!n.value->is_number()) n.fail("expected a number, got " + describe_json(*n.value));
  return n.value->get<float>();  // finite: the parser refuses numbers beyond float's range
}

glm::vec3 read_vec3(const Node& n) {
  const Json& v = *n.value;
  if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); }))
    n.fail("expected an array of 3 numbers, got " + describe_json(v));
  return {read_float(n.element(0)), read_float(n.element(1)), read_float(n.element(2))};
}

uint32_t read_index(const Node& n, const char* what = "material") {
  const Json& v = *n.value;
  // nlohmann stores every integer literal >= 0 as unsigned; 1.5, 2.0 and -1 are not.
  if (!v.is_number_unsigned() || v.get<uint64_t>() > std::numeric_limits<uint32_t>::max())
    n.fail("expected a " + std::string(what) + " index (an integer >= 0), got " + describe_json(v));
  return static_cast<uint32_t>(v.get<uint64_t>());
}

// The position of the "type" string in `names`, or an error listing them.
template <size_t N>
uint32_t read_type(const Node& n, const std::string_view (&names)[N], const char* kind) {
  const Node type = n.require("type");
  if (type.value->is_string()) {
    const auto it = std::find(std::begin(names), std::end(names), type.value->get_ref<const std::string&>());
    if (it != std::end(names)) return static_cast<uint32_t>(it - std::begin(names));
  }
  type.fail("unknown " + std::string(kind) + " type " + describe_json(*type.value) + " (expected " + join(names) + ")");
}

template <typename T>
void read_optional(const Node& n, const char* name, T& out) {
  if (const std::optional<Node> field = n.find(name)) {
    if constexpr (std::is_same_v<T, float>) out = read_float(*field);
    else out = read_vec3(*field);
  }
}

Camera read_camera(const Node& n) {
  require_object(n);
  check_keys(n, {"lookfrom", "lookat", "vup", "vfov", "aperture", "focus_dist"});
  Camera c;
  read_optional(n, "lookfrom", c.lookfrom);
  read_optional(n, "lookat", c.lookat);
  read_optional(n, "vup", c.vup);
  read_optional(n, "vfov", c.vfov);
  read_optional(n, "aperture", c.aperture);
  read_optional(n, "focus_dist", c.focus_dist);
  return c;
}

Sky read_sky(const Node& n) {
  require_object(n);
  Sky sky;
  sky.type = static_cast<SkyType>(read_type(n, kSkyNames, "sky"));
  switch (sky.type) {
    case SkyType::Gradient:
      check_keys(n, {"type", "down", "up"});
      read_optional(n, "down", sky.down);
      read_optional(n, "up", sky.up);
      break;
    case SkyType::Uniform:
      check_keys(n, {"type", "radiance"});
      sky.radiance = read_vec3(n.require("radiance"));
      break;
    case SkyType::None:
      check_keys(n, {"type"});
      break;
    case SkyType::Envmap: {
      check_keys(n, {"type", "file", "strength", "rotate"});
      const Node file = n.require("file");
      if (!file.value->is_string() || file.value->get_ref<const std::string&>().empty())
        file.fail("expected a file name (a non-empty string), got " + describe_json(*file.value));
      sky.file = file.value->get_ref<const std::string&>();
      read_optional(n, "strength", sky.strength);
      read_optional(n, "rotate", sky.rotate);
      // Relative to the scene file's folder, as mesh files are; the loader's
      // errors name the image file.
      sky.image = load_envmap((std::filesystem::path(*n.source).parent_path() / sky.file).string());
      break;
    }
  }
  return sky;
}

// A unit direction: any non-zero vector, normalised (in double, then rounded
// once); one already unit to 1e-6 is kept as written, so that what
// scene_to_json wrote reads back bit for bit.
glm::vec3 read_direction(const Node& n) {
  const glm::vec3 v = read_vec3(n);
  const glm::dvec3 d(v);
  const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  if (!(len > 0.0) || !std::isfinite(len)) n.fail("must be a non-zero vector, got " + describe_json(*n.value));
  return std::abs(len - 1.0) <= 1e-6 ? v : glm::vec3(d / len);
}

Light read_light(const Node& n) {
  require_object(n);
  Light l;
  l.type = static_cast<LightType>(read_type(n, kLightNames, "light"));
  switch (l.type) {
    case LightType::Point:
      check_keys(n, {"type", "position", "color", "intensity"});
      l.position = read_vec3(n.require("position"));
      break;
    case LightType::Spot:
      check_keys(n, {"type", "position", "direction", "color", "intensity", "inner_cone", "outer_cone"});
      l.position = read_vec3(n.require("position"));
      l.direction = read_direction(n.require("direction"));
      read_optional(n, "inner_cone", l.inner_cone);
      read_optional(n, "outer_cone", l.outer_cone);
      break;
    case LightType::Directional:
      check_keys(n, {"type", "direction", "color", "intensity"});
      l.direction = read_direction(n.require("direction"));
      break;
  }
  read_optional(n, "color", l.color);
  read_optional(n, "intensity", l.intensity);
  return l;
}

Material read_material(const Node& n) {
  require_object(n);
  Material m;
  m.type = static_cast<MaterialType>(read_type(n, kMaterialNames, "material"));
  switch (m.type) {
    case MaterialType::Lambertian:
      check_keys(n, {"type", "albedo"});
      m.albedo = read_vec3(n.require("albedo"));
      break;
    case MaterialType::Metal:
      check_keys(n, {"type", "albedo", "fuzz"});
      m.albedo = read_vec3(n.require("albedo"));
      read_optional(n, "fuzz", m.fuzz);
      break;
    case MaterialType::Dielectric:
      check_keys(n, {"type", "ior"});
      read_optional(n, "ior", m.ior);
      break;
    case MaterialType::Emissive:
      check_keys(n, {"type", "radiance"});
      m.radiance = read_vec3(n.require("radiance"));
      break;
    case MaterialType::Pbr:
      check_keys(n, {"type", "base_color", "metallic", "roughness", "emission", "transmission", "ior"});
      m.albedo = glm::vec3(1.0f);
      read_optional(n, "base_color", m.albedo);
      read_optional(n, "metallic", m.metallic);
      read_optional(n, "roughness", m.roughness);
      read_optional(n, "emission", m.emission);
      read_optional(n, "transmission", m.transmission);
      read_optional(n, "ior", m.ior);
      break;
  }
  return m;
}

Sphere read_sphere(const Node& n) {
  require_object(n);
  check_keys(n, {"center", "radius", "material"});
  // Braced initialisation evaluates left to right, so the first bad field is reported.
  return {read_vec3(n.require("center")), read_float(n.require("radius")), read_index(n.require("material"))};
}

// Column-major, as glTF and glm store matrices.
glm::mat4 read_matrix(const Node& n) {
  const Json& v = *n.value;
  if (!v.is_array() || v.size() != 16 || !std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); }))
    n.fail("expected an array of 16 numbers (column-major), got " + describe_json(v));
  glm::mat4 m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = read_float(n.element(size_t(i)));
  // The renderer takes rays into the mesh through the inverse.
  if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
    n.fail("must be an affine transform (last row, elements 3, 7, 11 and 15: 0, 0, 0, 1)");
  if (glm::determinant(glm::dmat3(glm::mat3(m))) == 0.0) n.fail("must be invertible");
  return m;
}

// {"scale", "rotate", "translate"} applied in that order, or {"matrix"};
// composed in double and rounded once.
glm::mat4 read_transform(const Node& n) {
  require_object(n);
  check_keys(n, {"scale", "rotate", "translate", "matrix"});
  if (const std::optional<Node> matrix = n.find("matrix")) {
    if (n.value->size() > 1) matrix->fail("excludes scale, rotate and translate (give one form or the other)");
    return read_matrix(*matrix);
  }
  glm::dmat4 t(1.0);
  if (const std::optional<Node> translate = n.find("translate")) t = glm::translate(t, glm::dvec3(read_vec3(*translate)));
  if (const std::optional<Node> rotate = n.find("rotate")) {
    const Json& v = *rotate->value;
    if (!v.is_array() || v.size() != 4 || !std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); }))
      rotate->fail("expected [axis x, y, z, angle in degrees], got " + describe_json(v));
    const glm::dvec3 axis(read_float(rotate->element(0)), read_float(rotate->element(1)), read_float(rotate->element(2)));
    if (axis == glm::dvec3(0.0)) rotate->fail("the axis must not be the zero vector");
    // Right-handed: counter-clockwise seen from the tip of the axis.
    t = glm::rotate(t, glm::radians(double(read_float(rotate->element(3)))), glm::normalize(axis));
  }
  if (const std::optional<Node> scale = n.find("scale")) {
    const glm::vec3 s = scale->value->is_number() ? glm::vec3(read_float(*scale)) : read_vec3(*scale);
    if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f)
      scale->fail("must not be 0 (it would flatten the mesh), got " + describe_json(*scale->value));
    t = glm::scale(t, glm::dvec3(s));
  }
  return glm::mat4(t);
}

MeshRef read_mesh_ref(const Node& n, size_t scene_materials) {
  require_object(n);
  check_keys(n, {"file", "material", "transform", "scene"});
  MeshRef ref;
  const Node file = n.require("file");
  if (!file.value->is_string() || file.value->get_ref<const std::string&>().empty())
    file.fail("expected a file name (a non-empty string), got " + describe_json(*file.value));
  ref.file = file.value->get<std::string>();
  if (const std::optional<Node> material = n.find("material")) {
    ref.material = read_index(*material);
    if (*ref.material >= scene_materials)
      material->fail("index " + std::to_string(*ref.material) + " out of range (" + std::to_string(scene_materials) +
                     (scene_materials == 1 ? " material)" : " materials)"));
  }
  if (const std::optional<Node> transform = n.find("transform")) ref.transform = read_transform(*transform);
  if (const std::optional<Node> scene = n.find("scene")) ref.scene = read_index(*scene, "scene");
  return ref;
}

// Loads the file a reference names, relative to the scene file's folder; its
// errors are prefixed with where the scene file names it.
// A file that several references name with the same scene and material
// override is loaded once: the later references place its meshes again.
using LoadedRefs = std::map<std::tuple<std::string, std::optional<uint32_t>, std::optional<uint32_t>>, GltfPlacement>;

void append_mesh_ref(Scene& scene, const MeshRef& ref, const Node& n, std::vector<std::string>& warnings,
                     LoadedRefs& loaded) {
  const std::string path = (std::filesystem::path(*n.source).parent_path() / ref.file).string();
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  const auto key = std::make_tuple(ec ? path : canonical.string(), ref.scene, ref.material);
  if (const auto it = loaded.find(key); it != loaded.end()) {
    place_again(scene, it->second, ref.transform);
    scene.mesh_refs.push_back(ref);
    return;
  }
  GltfOptions opts;
  opts.scene = ref.scene;
  opts.warn = [&](const std::string& w) { warnings.push_back(w); };
  try {
    loaded[key] = append_gltf(scene, path, ref.material, ref.transform, opts);
  } catch (const SettingError& e) {
    // The scene index: "gltf.scene: index 3 out of range (bunny.glb has 1 scene)".
    n.member("scene", nullptr).fail(std::string(e.what()).substr(e.setting.size() + 2));
  } catch (const InputError& e) {
    n.member("file", nullptr).fail(e.what());
  }
  scene.mesh_refs.push_back(ref);
}

// ---------------------------------------------------------------------------
// writing
// ---------------------------------------------------------------------------

void append(std::string& out, float v) {
  // "-0" would read back as the integer 0; "-0.0" is a float token.
  if (v == 0.0f && std::signbit(v)) {
    out += "-0.0";
    return;
  }
  char buf[32];
  out.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

void append(std::string& out, uint32_t v) {
  char buf[16];
  out.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

void append(std::string& out, glm::vec3 v) {
  out += '[';
  append(out, v.x);
  out += ", ";
  append(out, v.y);
  out += ", ";
  append(out, v.z);
  out += ']';
}

// `, "name": value`
template <typename T>
void append_field(std::string& out, const char* name, T value) {
  out += ", \"";
  out += name;
  out += "\": ";
  append(out, value);
}

void append_type(std::string& out, std::string_view name) {
  out += "{\"type\": \"";
  out += name;
  out += '"';
}

void append(std::string& out, const Sky& sky) {
  append_type(out, kSkyNames[static_cast<uint32_t>(sky.type)]);
  if (sky.type == SkyType::Gradient) {
    append_field(out, "down", sky.down);
    append_field(out, "up", sky.up);
  } else if (sky.type == SkyType::Uniform) {
    append_field(out, "radiance", sky.radiance);
  } else if (sky.type == SkyType::Envmap) {
    out += ", \"file\": ";
    out += Json(sky.file).dump();
    append_field(out, "strength", sky.strength);
    append_field(out, "rotate", sky.rotate);
  }
  out += '}';
}

void append(std::string& out, const Light& l) {
  append_type(out, kLightNames[static_cast<uint32_t>(l.type)]);
  if (l.type != LightType::Directional) append_field(out, "position", l.position);
  if (l.type != LightType::Point) append_field(out, "direction", l.direction);
  append_field(out, "color", l.color);
  append_field(out, "intensity", l.intensity);
  if (l.type == LightType::Spot) {
    append_field(out, "inner_cone", l.inner_cone);
    append_field(out, "outer_cone", l.outer_cone);
  }
  out += '}';
}

void append(std::string& out, const Material& m) {
  append_type(out, kMaterialNames[static_cast<uint32_t>(m.type)]);
  switch (m.type) {
    case MaterialType::Lambertian:
      append_field(out, "albedo", m.albedo);
      break;
    case MaterialType::Metal:
      append_field(out, "albedo", m.albedo);
      append_field(out, "fuzz", m.fuzz);
      break;
    case MaterialType::Dielectric:
      append_field(out, "ior", m.ior);
      break;
    case MaterialType::Emissive:
      append_field(out, "radiance", m.radiance);
      break;
    case MaterialType::Pbr:
      append_field(out, "base_color", m.albedo);
      append_field(out, "metallic", m.metallic);
      append_field(out, "roughness", m.roughness);
      append_field(out, "emission", m.emission);
      append_field(out, "transmission", m.transmission);
      append_field(out, "ior", m.ior);
      break;
  }
  out += '}';
}

void append(std::string& out, const Sphere& s) {
  out += "{\"center\": ";
  append(out, s.center);
  append_field(out, "radius", s.radius);
  append_field(out, "material", s.material);
  out += '}';
}

void append(std::string& out, const MeshRef& ref) {
  out += "{\"file\": ";
  out += Json(ref.file).dump();
  if (ref.material) append_field(out, "material", *ref.material);
  if (ref.scene) append_field(out, "scene", *ref.scene);
  if (ref.transform != glm::mat4(1.0f)) {
    out += ", \"transform\": {\"matrix\": [";
    for (int i = 0; i < 16; ++i) {
      if (i) out += ", ";
      append(out, ref.transform[i / 4][i % 4]);
    }
    out += "]}";
  }
  out += '}';
}

// One element per line, so that a file of a million spheres stays readable and diffable.
template <typename T>
void append(std::string& out, const std::vector<T>& items) {
  if (items.empty()) {
    out += "[]";
    return;
  }
  out += "[\n";
  for (size_t i = 0; i < items.size(); ++i) {
    out += "    ";
    append(out, items[i]);
    out += i + 1 < items.size() ? ",\n" : "\n";
  }
  out += "  ]";
}


}  // namespace

Scene parse_scene_json(const std::string& text, const std::string& source) {
  // The elements of "materials" and "spheres" are converted as the parser
  // finishes each one and then dropped from the document: a million spheres never
  // exist as a JSON tree (~400 bytes each) next to the Scene (20 bytes each), and
  // nlohmann's callback parser, which scans an array from its start at every
  // object end, has only the one element to scan. `open` follows the parser's
  // position: one entry per open object or array, with the current key or index.
  struct Open {
    bool is_array;
    size_t index = 0;
    std::string key{};
  };
  std::vector<Open> open;
  // The top-level list the parser is in: 0 none, 1 materials, 2 spheres (the
  // indices of `lists` and `seen`).
  const auto list = [&]() -> int {
    if (open.size() != 2 || open[0].is_array || !open[1].is_array) return 0;
    return open[0].key == "materials" ? 1 : open[0].key == "spheres" ? 2 : 0;
  };
  const Node root_path{nullptr, &source};
  const Node lists[3] = {root_path, root_path.member("materials", nullptr), root_path.member("spheres", nullptr)};
  bool seen[3] = {};
  Scene scene;
  using Event = Json::parse_event_t;
  const auto on_event = [&](int depth, Event event, Json& parsed) {
    check_json_depth(depth, source + ": ");
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        open.push_back({event == Event::array_start});
        // nlohmann keeps the last of duplicate keys; here both lists would be read, so refuse.
        if (const int l = list()) {
          if (seen[l]) lists[l].fail("appears twice");
          seen[l] = true;
        }
        return true;
      case Event::key:
        open.back().key = parsed.get_ref<const std::string&>();
        return true;
      case Event::object_end:
      case Event::array_end:
        open.pop_back();
        break;
      case Event::value:
        break;
    }
    // A value is complete.
    if (open.empty() || !open.back().is_array) return true;
    const size_t index = open.back().index++;
    switch (list()) {
      case 1:
        scene.materials.push_back(read_material(lists[1].element(index, &parsed)));
        return false;
      case 2:
        scene.spheres.push_back(read_sphere(lists[2].element(index, &parsed)));
        return false;
    }
    return true;
  };

  Json doc;
  try {
    doc = Json::parse(text, on_event);
  } catch (const Json::parse_error& e) {
    throw InputError(source + ": " + invalid_json_message(e.what()));
  } catch (const Json::out_of_range& e) {
    // A number beyond float's range (1e999, or just 1e39): nlohmann refuses it
    // without a position, but `open` knows where the parser stood.
    std::string path;
    for (const Open& o : open)
      path += o.is_array ? "[" + std::to_string(o.index) + "]" : (path.empty() ? "" : ".") + o.key;
    const std::string what = e.what();
    const size_t quote = what.find('\'');
    const std::string got = quote == std::string::npos ? "" : ", got " + what.substr(quote + 1, what.size() - quote - 2);
    throw InputError(source + ": " + (path.empty() ? "" : path + ": ") + "number out of range of a 32-bit float" + got);
  }

  const Node root{&doc, &source};
  if (!doc.is_object()) root.fail("expected a JSON object at the top level, got " + describe_json(doc));
  check_keys(root, {"camera", "sky", "materials", "spheres", "meshes", "lights"});
  std::vector<std::string> warnings;
  if (const std::optional<Node> camera = root.find("camera")) scene.camera = read_camera(*camera);
  if (const std::optional<Node> sky = root.find("sky")) scene.sky = read_sky(*sky);
  // If they are arrays, the parser has already moved their elements into `scene`.
  require_array(root.require("materials"));
  if (const std::optional<Node> spheres = root.find("spheres")) require_array(*spheres);
  if (const std::optional<Node> lights = root.find("lights")) {
    require_array(*lights);
    for (size_t i = 0; i < lights->value->size(); ++i) scene.lights.push_back(read_light(lights->element(i)));
  }
  if (const std::optional<Node> meshes = root.find("meshes")) {
    require_array(*meshes);
    // Validated before any file is read, so that the scene file's own errors come first.
    std::vector<MeshRef> refs;
    for (size_t i = 0; i < meshes->value->size(); ++i)
      refs.push_back(read_mesh_ref(meshes->element(i), scene.materials.size()));
    LoadedRefs loaded;
    for (size_t i = 0; i < refs.size(); ++i) append_mesh_ref(scene, refs[i], meshes->element(i), warnings, loaded);
  }
  validate_scene(scene, source);
  // Only once the whole scene has loaded, so that an error stays the one line printed.
  for (const std::string& w : warnings) print_warning(w);
  return scene;
}

Scene load_scene_json(const std::string& path) { return parse_scene_json(read_file(path), path); }

std::string scene_to_json(const Scene& scene) {
  // What is written must load again; non-finite numbers cannot even be written.
  validate_scene(scene, "scene");
  if (!scene.meshes.empty() && scene.mesh_refs.empty())
    throw InputError("scene: meshes: only meshes loaded from files can be written (as references to the files)");
  const size_t written = scene.materials.size() - scene.mesh_file_materials;
  for (size_t i = 0; i < written; ++i) {
    const Material& m = scene.materials[i];
    if (has_texture(m) || (m.type != MaterialType::Pbr && m.emission != glm::vec3(0.0f)))
      throw InputError("scene: materials[" + std::to_string(i) +
                       "]: textures (and a lambertian material's emission) come only from mesh files and cannot be written");
  }
  std::string out;
  out.reserve(512 + 64 * scene.materials.size() + 72 * scene.spheres.size());
  const Camera& c = scene.camera;
  out += "{\n  \"camera\": {\"lookfrom\": ";
  append(out, c.lookfrom);
  append_field(out, "lookat", c.lookat);
  append_field(out, "vup", c.vup);
  append_field(out, "vfov", c.vfov);
  append_field(out, "aperture", c.aperture);
  append_field(out, "focus_dist", c.focus_dist);
  out += "},\n  \"sky\": ";
  append(out, scene.sky);
  out += ",\n  \"materials\": ";
  // The mesh files' materials come back when the references load.
  append(out, std::vector<Material>(scene.materials.begin(), scene.materials.begin() + ptrdiff_t(written)));
  out += ",\n  \"spheres\": ";
  append(out, scene.spheres);
  // The mesh files' lights come back when the references load.
  if (scene.lights.size() > scene.mesh_file_lights) {
    out += ",\n  \"lights\": ";
    append(out, std::vector<Light>(scene.lights.begin(), scene.lights.end() - ptrdiff_t(scene.mesh_file_lights)));
  }
  if (!scene.mesh_refs.empty()) {
    out += ",\n  \"meshes\": ";
    append(out, scene.mesh_refs);
  }
  out += "\n}\n";
  return out;
}

void save_scene_json(const Scene& scene, const std::string& path) {
  const std::string text = scene_to_json(scene);
  write_file_atomically(path, text.data(), text.size());
}

}  // namespace octrace
