// glTF 2.0 through tinygltf; scene/gltf.h says what is read and how.
//
// tinygltf parses the JSON, resolves buffers and images and splits .glb files,
// but checks little of what it reads: a property of the wrong type silently
// keeps its default ("scene": "hello" reads as no scene), and nothing checks
// accessors against their views, views against their buffers or indices
// against the vertices. So the JSON is first checked against the part of the
// glTF schema that octrace reads (check_schema), and every index and byte range
// is checked where it is used, each error naming its glTF path.
//
// Section numbers refer to the glTF 2.0 specification (Khronos, 2021).

// Before tiny_gltf.h: it includes nlohmann/json.hpp under `#pragma GCC
// visibility push(hidden)`, and a system header first included there would
// declare hidden what it declares (unistd.h's syscall, which the threads of
// core/parallel.h call through libstdc++'s atomic waits: the link failed).
#include <atomic>
#include <thread>
#include <unistd.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE        // images go through decode_image below
#define TINYGLTF_NO_STB_IMAGE_WRITE  // octrace writes no glTF
#include <tiny_gltf.h>

#include "scene/gltf.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <span>
#include <string_view>
#include <tuple>

#include <stb_image.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "core/parallel.h"
#include "core/text.h"
#include "io/file.h"
#include "io/image.h"
#include "scene/json_text.h"

namespace octrace {
namespace {

using Json = nlohmann::json;

// "1 mesh", "3 meshes", "1 bufferView": a count of the items of a glTF array.
std::string count_of(size_t n, std::string_view array) {
  if (n != 1) return std::to_string(n) + " " + std::string(array);
  return "1 " + std::string(array == "meshes" ? "mesh" : array.substr(0, array.size() - 1));
}

std::string item(std::string_view array, size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

// "1 vertex", "24 vertices".
std::string plural(size_t n, const std::string& one, const std::string& many = "") {
  return std::to_string(n) + " " + (n == 1 ? one : many.empty() ? one + "s" : many);
}

// ---------------------------------------------------------------------------
// schema: the types of the properties octrace reads (glTF 2.0 spec, 5 and the
// JSON schema). Unknown properties are allowed, as the spec asks of readers.
// ---------------------------------------------------------------------------

enum class Kind : uint8_t {
  Index,     // an integer >= 0 (tinygltf stores indices as int)
  Uint,      // an integer >= 0
  Integer,
  Number,
  Bool,
  String,
  Object,    // checked against `fields`
  Objects,   // an array of objects checked against `fields`
  Numbers,   // an array of numbers, of `length` if not 0
  Indices,   // an array of Index
  Strings,
  IndexMap,  // an object whose values are Index (primitive attributes)
  IndexMaps, // an array of IndexMap (morph targets)
};

struct Field {
  const char* name = nullptr;  // nullptr ends a list
  Kind kind = Kind::Object;
  const Field* fields = nullptr;
  uint8_t length = 0;
  bool required = false;
};

constexpr Field required(const char* name, Kind kind, const Field* fields = nullptr) {
  return {name, kind, fields, 0, true};
}

constexpr Field kTextureTransform[] = {{"offset", Kind::Numbers, nullptr, 2}, {"rotation", Kind::Number},
                                       {"scale", Kind::Numbers, nullptr, 2}, {"texCoord", Kind::Uint}, {}};
constexpr Field kTextureInfoExtensions[] = {{"KHR_texture_transform", Kind::Object, kTextureTransform}, {}};
constexpr Field kTextureInfo[] = {required("index", Kind::Index), {"texCoord", Kind::Uint}, {"scale", Kind::Number},
                                  {"strength", Kind::Number}, {"extensions", Kind::Object, kTextureInfoExtensions},
                                  {}};
constexpr Field kPbr[] = {{"baseColorFactor", Kind::Numbers, nullptr, 4}, {"baseColorTexture", Kind::Object, kTextureInfo},
                          {"metallicFactor", Kind::Number}, {"roughnessFactor", Kind::Number},
                          {"metallicRoughnessTexture", Kind::Object, kTextureInfo}, {}};
constexpr Field kEmissiveStrength[] = {{"emissiveStrength", Kind::Number}, {}};
constexpr Field kIor[] = {{"ior", Kind::Number}, {}};
constexpr Field kTransmission[] = {{"transmissionFactor", Kind::Number},
                                   {"transmissionTexture", Kind::Object, kTextureInfo}, {}};
constexpr Field kVolume[] = {{"thicknessFactor", Kind::Number}, {"thicknessTexture", Kind::Object, kTextureInfo},
                             {"attenuationDistance", Kind::Number}, {"attenuationColor", Kind::Numbers, nullptr, 3},
                             {}};
constexpr Field kMaterialExtensions[] = {{"KHR_materials_emissive_strength", Kind::Object, kEmissiveStrength},
                                         {"KHR_materials_ior", Kind::Object, kIor},
                                         {"KHR_materials_transmission", Kind::Object, kTransmission},
                                         {"KHR_materials_volume", Kind::Object, kVolume}, {}};
constexpr Field kMaterial[] = {{"pbrMetallicRoughness", Kind::Object, kPbr}, {"normalTexture", Kind::Object, kTextureInfo},
                               {"occlusionTexture", Kind::Object, kTextureInfo},
                               {"emissiveTexture", Kind::Object, kTextureInfo},
                               {"emissiveFactor", Kind::Numbers, nullptr, 3}, {"alphaMode", Kind::String},
                               {"alphaCutoff", Kind::Number}, {"doubleSided", Kind::Bool},
                               {"extensions", Kind::Object, kMaterialExtensions}, {}};
constexpr Field kPrimitive[] = {required("attributes", Kind::IndexMap), {"indices", Kind::Index},
                                {"material", Kind::Index}, {"mode", Kind::Integer}, {"targets", Kind::IndexMaps}, {}};
constexpr Field kMesh[] = {required("primitives", Kind::Objects, kPrimitive), {"weights", Kind::Numbers}, {}};
constexpr Field kNode[] = {{"camera", Kind::Index}, {"children", Kind::Indices}, {"skin", Kind::Index},
                           {"matrix", Kind::Numbers, nullptr, 16}, {"mesh", Kind::Index},
                           {"rotation", Kind::Numbers, nullptr, 4}, {"scale", Kind::Numbers, nullptr, 3},
                           {"translation", Kind::Numbers, nullptr, 3}, {"weights", Kind::Numbers}, {}};
constexpr Field kScene[] = {{"nodes", Kind::Indices}, {}};
constexpr Field kSparseIndices[] = {required("bufferView", Kind::Index), {"byteOffset", Kind::Uint},
                                    required("componentType", Kind::Integer), {}};
constexpr Field kSparseValues[] = {required("bufferView", Kind::Index), {"byteOffset", Kind::Uint}, {}};
constexpr Field kSparse[] = {required("count", Kind::Uint), required("indices", Kind::Object, kSparseIndices),
                             required("values", Kind::Object, kSparseValues), {}};
constexpr Field kAccessor[] = {{"bufferView", Kind::Index}, {"byteOffset", Kind::Uint},
                               required("componentType", Kind::Integer), {"normalized", Kind::Bool},
                               required("count", Kind::Uint), required("type", Kind::String),
                               {"max", Kind::Numbers}, {"min", Kind::Numbers}, {"sparse", Kind::Object, kSparse}, {}};
constexpr Field kBufferView[] = {required("buffer", Kind::Index), {"byteOffset", Kind::Uint},
                                 required("byteLength", Kind::Uint), {"byteStride", Kind::Uint},
                                 {"target", Kind::Integer}, {}};
constexpr Field kBuffer[] = {{"uri", Kind::String}, required("byteLength", Kind::Uint), {}};
constexpr Field kPerspective[] = {{"aspectRatio", Kind::Number}, required("yfov", Kind::Number), {"zfar", Kind::Number},
                                  required("znear", Kind::Number), {}};
constexpr Field kOrthographic[] = {required("xmag", Kind::Number), required("ymag", Kind::Number),
                                   required("zfar", Kind::Number), required("znear", Kind::Number), {}};
constexpr Field kCamera[] = {required("type", Kind::String), {"perspective", Kind::Object, kPerspective},
                             {"orthographic", Kind::Object, kOrthographic}, {}};
constexpr Field kImage[] = {{"uri", Kind::String}, {"mimeType", Kind::String}, {"bufferView", Kind::Index}, {}};
constexpr Field kTexture[] = {{"sampler", Kind::Index}, {"source", Kind::Index}, {}};
constexpr Field kSampler[] = {{"magFilter", Kind::Integer}, {"minFilter", Kind::Integer}, {"wrapS", Kind::Integer},
                              {"wrapT", Kind::Integer}, {}};
constexpr Field kAsset[] = {required("version", Kind::String), {"minVersion", Kind::String},
                            {"generator", Kind::String}, {"copyright", Kind::String}, {}};
constexpr Field kNothing[] = {{}};
constexpr Field kRoot[] = {required("asset", Kind::Object, kAsset), {"scene", Kind::Index},
                           {"scenes", Kind::Objects, kScene}, {"nodes", Kind::Objects, kNode},
                           {"meshes", Kind::Objects, kMesh}, {"accessors", Kind::Objects, kAccessor},
                           {"bufferViews", Kind::Objects, kBufferView}, {"buffers", Kind::Objects, kBuffer},
                           {"materials", Kind::Objects, kMaterial}, {"textures", Kind::Objects, kTexture},
                           {"images", Kind::Objects, kImage}, {"samplers", Kind::Objects, kSampler},
                           {"cameras", Kind::Objects, kCamera}, {"skins", Kind::Objects, kNothing},
                           {"animations", Kind::Objects, kNothing}, {"extensionsUsed", Kind::Strings},
                           {"extensionsRequired", Kind::Strings}, {}};

// Where a JSON value sits ("meshes[0].primitives[2].mode"), spelled out only
// when an error needs it.
struct Where {
  const Where* parent = nullptr;
  std::string_view key{};  // member name, unless is_element
  bool is_element = false;
  size_t index = 0;

  std::string path() const { return json_path(*this); }
};

struct SchemaCheck {
  const std::string& file;

  [[noreturn]] void fail(const Where& at, const std::string& what) const {
    throw InputError(file + ": " + at.path() + ": " + what);
  }

  bool is_index(const Json& v) const {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
  }

  void index(const Json& v, const Where& at) const {
    if (!is_index(v) || v.get<uint64_t>() > uint64_t(INT_MAX))
      fail(at, "expected an index (an integer >= 0), got " + describe_json(v));
  }

  void object(const Json& v, const Field* fields, const Where& at) const {
    if (!v.is_object()) fail(at, "expected an object, got " + describe_json(v));
    for (const Field* f = fields; f->name; ++f) {
      const auto it = v.find(f->name);
      const Where field_at{&at, f->name};
      if (it == v.end()) {
        if (f->required) fail(field_at, "missing required property");
        continue;
      }
      value(*it, *f, field_at);
    }
    if (const auto it = v.find("name"); it != v.end() && !it->is_string())
      fail({&at, "name"}, "expected a string, got " + describe_json(*it));
    if (const auto it = v.find("extensions"); it != v.end()) {
      const Where ext_at{&at, "extensions"};
      if (!it->is_object()) fail(ext_at, "expected an object, got " + describe_json(*it));
      for (auto e = it->begin(); e != it->end(); ++e)
        if (!e->is_object()) fail({&ext_at, e.key()}, "expected an object, got " + describe_json(*e));
    }
  }

  void array(const Json& v, const Where& at) const {
    if (!v.is_array()) fail(at, "expected an array, got " + describe_json(v));
  }

  void value(const Json& v, const Field& f, const Where& at) const {
    switch (f.kind) {
      case Kind::Index:
        return index(v, at);
      case Kind::Uint:
        if (!is_index(v)) fail(at, "expected an integer >= 0, got " + describe_json(v));
        return;
      case Kind::Integer:
        if (!v.is_number_integer()) fail(at, "expected an integer, got " + describe_json(v));
        return;
      case Kind::Number:
        if (!v.is_number()) fail(at, "expected a number, got " + describe_json(v));
        return;
      case Kind::Bool:
        if (!v.is_boolean()) fail(at, "expected true or false, got " + describe_json(v));
        return;
      case Kind::String:
        if (!v.is_string()) fail(at, "expected a string, got " + describe_json(v));
        return;
      case Kind::Object:
        return object(v, f.fields, at);
      case Kind::Objects:
        array(v, at);
        for (size_t i = 0; i < v.size(); ++i) object(v[i], f.fields, {&at, {}, true, i});
        return;
      case Kind::Numbers:
        if (!v.is_array() || !std::all_of(v.begin(), v.end(), [](const Json& e) { return e.is_number(); }) ||
            (f.length && v.size() != f.length))
          fail(at, "expected an array of " + (f.length ? std::to_string(f.length) + " " : std::string()) +
                       "numbers, got " + describe_json(v));
        return;
      case Kind::Indices:
        array(v, at);
        for (size_t i = 0; i < v.size(); ++i) index(v[i], {&at, {}, true, i});
        return;
      case Kind::Strings:
        array(v, at);
        for (size_t i = 0; i < v.size(); ++i)
          if (!v[i].is_string()) fail({&at, {}, true, i}, "expected a string, got " + describe_json(v[i]));
        return;
      case Kind::IndexMap:
        if (!v.is_object()) fail(at, "expected an object, got " + describe_json(v));
        for (auto e = v.begin(); e != v.end(); ++e) index(*e, {&at, e.key()});
        return;
      case Kind::IndexMaps:
        array(v, at);
        for (size_t i = 0; i < v.size(); ++i) value(v[i], {f.name, Kind::IndexMap}, {&at, {}, true, i});
        return;
    }
  }
};

// Extensions a file may require (extensionsRequired) that octrace reads.
constexpr std::string_view kSupportedExtensions[] = {"KHR_mesh_quantization", "KHR_materials_emissive_strength",
                                                     "KHR_materials_ior", "KHR_materials_transmission",
                                                     "KHR_materials_volume", "KHR_texture_transform",
                                                     "KHR_lights_punctual"};

void check_schema(const Json& doc, const std::string& file) {
  const Where root;
  if (!doc.is_object()) throw InputError(file + ": expected a JSON object at the top level, got " + describe_json(doc));
  SchemaCheck{file}.object(doc, kRoot, root);
  const std::string& version = doc["asset"]["version"].get_ref<const std::string&>();
  if (version.rfind("2.", 0) != 0)
    throw InputError(file + ": asset.version: glTF " + version + " is not supported (only 2.x)");
  if (const auto it = doc.find("extensionsRequired"); it != doc.end()) {
    for (size_t i = 0; i < it->size(); ++i) {
      const std::string& name = (*it)[i].get_ref<const std::string&>();
      if (std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), name) ==
          std::end(kSupportedExtensions))
        throw InputError(file + ": " + item("extensionsRequired", i) + ": extension " + name +
                         " is not supported");
    }
  }
}

// ---------------------------------------------------------------------------
// the file: container, JSON, buffers and images
// ---------------------------------------------------------------------------

// The JSON chunk of a .glb, its header checked (glTF 2.0 spec, 4.4 "Binary glTF Layout").
std::string_view glb_json(const std::string& bytes, const std::string& file) {
  const auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);  // little-endian, as the format and every host octrace runs on
    return v;
  };
  if (bytes.size() < 20)
    throw InputError(file + ": not a glTF binary: " + plural(bytes.size(), "byte") + ", less than a GLB header (20)");
  if (u32(0) != 0x46546C67) throw InputError(file + ": not a glTF binary (no \"glTF\" magic at the start)");
  if (u32(4) != 2) throw InputError(file + ": GLB version " + std::to_string(u32(4)) + " is not supported (only 2)");
  if (u32(8) != bytes.size())
    throw InputError(file + ": the GLB header gives a length of " + plural(u32(8), "byte") + ", the file has " +
                     std::to_string(bytes.size()) + " (truncated or corrupt)");
  if (u32(16) != 0x4E4F534A) throw InputError(file + ": the first GLB chunk is not JSON");
  if (u32(12) > bytes.size() - 20)
    throw InputError(file + ": the GLB JSON chunk (" + plural(u32(12), "byte") + ") runs past the end of the file");
  return std::string_view(bytes).substr(20, u32(12));
}

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// tinygltf names no buffer when one's file is missing, and only warns about a
// missing image; both are part of the scene, so they are checked here first.
void check_external_files(const Json& doc, const std::string& file, const std::string& dir) {
  for (const char* array : {"buffers", "images"}) {
    const auto list = doc.find(array);
    if (list == doc.end()) continue;
    for (size_t i = 0; i < list->size(); ++i) {
      const auto uri = (*list)[i].find("uri");
      if (uri == (*list)[i].end() || is_data_uri(uri->get_ref<const std::string&>())) continue;
      // As tinygltf finds it: percent-decoded, relative to the file's folder.
      const std::string path =
          (std::filesystem::path(dir) / tinygltf::dlib::urldecode(uri->get<std::string>())).string();
      std::FILE* opened = std::fopen(path.c_str(), "rb");
      if (!opened)
        throw InputError(file + ": " + item(array, i) + ".uri: cannot open " + path + ": " + std::strerror(errno));
      std::fclose(opened);
      std::error_code ec;
      if (std::filesystem::is_directory(path, ec))
        throw InputError(file + ": " + item(array, i) + ".uri: " + path + " is a folder, not a file");
    }
  }
}

// Decodes an image's bytes with stb_image (PNG and JPEG, the formats of the
// core spec, 3.8.1, and the others stb reads) to RGBA8, whatever its channels
// and bit depth (16-bit PNGs are rounded to 8 bits), rows from the top.
// Returns the error, or nothing.
std::string decode_rgba8(tinygltf::Image& image, size_t index, const unsigned char* bytes, size_t size) {
  const std::string at = item("images", index);
  if (size > size_t(INT_MAX)) return at + ": cannot be decoded (larger than 2 GiB)";
  if (std::string why = png_chunk_error(bytes, size); !why.empty()) return at + ": cannot be decoded (" + why + ")";
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load_from_memory(bytes, int(size), &width, &height, &channels, 4);
  if (!pixels) return at + ": cannot be decoded (" + stb_failure_reason() + ")";
  image.width = width;
  image.height = height;
  image.component = 4;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image.image.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
  stbi_image_free(pixels);
  return {};
}

// The images of a file to decode once it is loaded, on the host's threads
// (optimisation log 109): images[index] from the bytes tinygltf handed over
// (`kept`: a file's or data URI's, which it frees after the call) or from
// the model's own buffer (a bufferView's image, not copied).
struct PendingImage {
  size_t index;
  std::vector<unsigned char> kept;
  std::span<const unsigned char> view;
  std::span<const unsigned char> bytes() const { return view.data() ? view : std::span<const unsigned char>(kept); }
};

// Decodes each pending image into images[index]; the first failure in
// `pending`'s order, or nothing.
std::string decode_images(std::vector<tinygltf::Image>& images, const std::vector<PendingImage>& pending) {
  std::vector<std::string> errors(pending.size());
  parallel_items(pending.size(), [&](size_t k) {
    const PendingImage& p = pending[k];
    errors[k] = decode_rgba8(images[p.index], p.index, p.bytes().data(), p.bytes().size());
  });
  for (const std::string& e : errors)
    if (!e.empty()) return e;
  return {};
}

// tinygltf's image callback, for images in a file or a data URI: their bytes
// kept (`user`: the std::vector<PendingImage>) to be decoded after loading.
// An image in a bufferView is left to open_gltf, after its view's checks:
// tinygltf hands over the view's bytes without checking that the view lies
// inside its buffer (a crash found by tests/fuzz/fuzz_gltf.cpp).
bool keep_image(tinygltf::Image* image, int index, std::string*, std::string*, int, int, const unsigned char* bytes,
                int size, void* user) {
  if (image->bufferView >= 0) return true;
  auto& pending = *static_cast<std::vector<PendingImage>*>(user);
  pending.push_back({size_t(index), std::vector<unsigned char>(bytes, bytes + std::max(size, 0)), {}});
  return true;
}

struct File {
  std::string path;  // names the file in messages
  tinygltf::Model model;
  std::vector<std::string> warnings;

  [[noreturn]] void fail(const std::string& at, const std::string& what) const {
    throw InputError(path + ": " + at + ": " + what);
  }

  // model.<array>[index], checked: `at` is where the index was given.
  template <typename T>
  const T& get(const std::vector<T>& array, int index, const char* array_name, const std::string& at) const {
    if (index < 0 || size_t(index) >= array.size())
      fail(at, "index " + std::to_string(index) + " out of range (" + count_of(array.size(), array_name) + ")");
    return array[size_t(index)];
  }
};

void check_buffer_views(const File& f) {
  const auto& m = f.model;
  for (size_t i = 0; i < m.bufferViews.size(); ++i) {
    const tinygltf::BufferView& v = m.bufferViews[i];
    const std::string at = item("bufferViews", i);
    const tinygltf::Buffer& b = f.get(m.buffers, v.buffer, "buffers", at + ".buffer");
    if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
      f.fail(at, "byteOffset " + std::to_string(v.byteOffset) + " + byteLength " + std::to_string(v.byteLength) +
                     " exceeds buffers[" + std::to_string(v.buffer) + "] (" + plural(b.data.size(), "byte") + ")");
  }
}

// The file's bytes read by tinygltf after the checks tinygltf does not make;
// `path` names them and is where their external buffers and images lie.
File open_gltf(const std::string& bytes, const std::string& path) {
  File f{path, {}, {}};
  if (bytes.size() > UINT_MAX) throw InputError(path + ": larger than 4 GiB, which tinygltf cannot read");
  std::string lower = std::filesystem::path(path).extension().string();
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  // Binary by its magic, or by its name: a damaged .glb then says what is
  // wrong with its header rather than that it is not JSON.
  const bool binary = bytes.rfind("glTF", 0) == 0 || lower == ".glb";
  const std::string_view text = binary ? glb_json(bytes, path) : std::string_view(bytes);

  Json doc;
  try {
    doc = Json::parse(text.begin(), text.end(),
                      json_depth_limit<Json>(path + ": " + (binary ? "GLB JSON chunk: " : "")));
  } catch (const Json::exception& e) {
    throw InputError(path + ": " + (binary ? "GLB JSON chunk: " : "") + invalid_json_message(e.what()));
  }
  check_schema(doc, path);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  check_external_files(doc, path, dir);
  doc = Json();  // tinygltf parses its own copy

  tinygltf::TinyGLTF loader;
  std::vector<PendingImage> pending;
  loader.SetImageLoader(&keep_image, &pending);
  std::string err, warn;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&f.model, &err, &warn, data, unsigned(bytes.size()), dir)
                         : loader.LoadASCIIFromString(&f.model, &err, &warn, bytes.data(), unsigned(bytes.size()), dir);
  // A broken image is reported before what tinygltf says of the rest, as
  // when it was decoded inside tinygltf's loading, which stopped there.
  if (std::string error = decode_images(f.model.images, pending); !error.empty())
    throw InputError(path + ": " + error);
  if (!ok || !err.empty()) {
    // tinygltf lists every problem, one per line; the first is the one to fix first.
    std::string first = err.substr(0, err.find('\n'));
    if (first.empty()) first = "tinygltf could not read the file and gave no reason";
    throw InputError(path + ": " + first);
  }
  check_buffer_views(f);
  // The images in bufferViews, now that every view is known to lie inside its buffer.
  pending.clear();
  for (size_t i = 0; i < f.model.images.size(); ++i) {
    const tinygltf::Image& image = f.model.images[i];
    if (image.bufferView < 0) continue;
    const tinygltf::BufferView& v = f.get(f.model.bufferViews, image.bufferView, "bufferViews", item("images", i) + ".bufferView");
    const unsigned char* view = f.model.buffers[size_t(v.buffer)].data.data() + v.byteOffset;
    pending.push_back({i, {}, {view, v.byteLength}});
  }
  if (std::string error = decode_images(f.model.images, pending); !error.empty()) throw InputError(path + ": " + error);
  return f;
}

// ---------------------------------------------------------------------------
// accessors (glTF 2.0 spec, 3.6.2)
// ---------------------------------------------------------------------------

size_t component_bytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
  }
  return 0;
}

std::string component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
  }
  return "componentType " + std::to_string(type);
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
  }
  return 0;
}

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
  }
  return "type " + std::to_string(type);
}

// An accessor without a bufferView is all zeros (before its sparse values):
// its count costs no file space, so it is bounded here rather than by the file.
constexpr size_t kMaxZeroElements = size_t(1) << 24;

// Where `count` elements of `element_size` bytes lie in a bufferView, checked
// against the view (which check_buffer_views checked against its buffer).
struct Elements {
  const uint8_t* data;
  size_t stride;
};

Elements locate(const File& f, const std::string& at, int view_index, size_t offset, size_t element_size,
                size_t count, const std::string& view_at) {
  const tinygltf::BufferView& view = f.get(f.model.bufferViews, view_index, "bufferViews", view_at);
  const size_t stride = view.byteStride ? view.byteStride : element_size;
  if (stride < element_size)
    f.fail(at, "byteStride " + std::to_string(stride) + " of bufferView " + std::to_string(view_index) +
                   " is less than an element (" + plural(element_size, "byte") + ")");
  const size_t fits = offset <= view.byteLength && element_size <= view.byteLength - offset
                          ? (view.byteLength - offset - element_size) / stride + 1
                          : 0;
  if (count > fits)
    f.fail(at, "count " + std::to_string(count) + " exceeds bufferView " + std::to_string(view_index) + " (" +
                   plural(fits, "element") + ")");
  return {f.model.buffers[size_t(view.buffer)].data.data() + view.byteOffset + offset, stride};
}

const tinygltf::Accessor& accessor(const File& f, int index, const std::string& at) {
  const tinygltf::Accessor& a = f.get(f.model.accessors, index, "accessors", at);
  const std::string self = item("accessors", size_t(index));
  if (!component_bytes(a.componentType)) f.fail(self, "unsupported " + component_name(a.componentType));
  if (!type_components(a.type)) f.fail(self, "unsupported " + type_name(a.type));
  if (a.bufferView < 0 && a.count > kMaxZeroElements)
    f.fail(self, "count " + std::to_string(a.count) + " without a bufferView is more than octrace reads (" +
                     std::to_string(kMaxZeroElements) + ")");
  // The count against its view before a reader allocates that many elements.
  if (a.bufferView >= 0)
    locate(f, self, a.bufferView, a.byteOffset, component_bytes(a.componentType) * size_t(type_components(a.type)),
           a.count, self + ".bufferView");
  return a;
}

// Calls put(i, bytes of element i) for every element, sparse substitutions
// (3.6.2.3) after the dense values they replace.
template <typename Put>
void visit_elements(const File& f, int index, const tinygltf::Accessor& a, Put&& put) {
  const std::string at = item("accessors", size_t(index));
  const size_t size = component_bytes(a.componentType) * size_t(type_components(a.type));
  if (a.bufferView >= 0) {
    const Elements e = locate(f, at, a.bufferView, a.byteOffset, size, a.count, at + ".bufferView");
    for (size_t i = 0; i < a.count; ++i) put(i, e.data + i * e.stride);
  } else {
    static const uint8_t zeros[64] = {};
    for (size_t i = 0; i < a.count; ++i) put(i, zeros);
  }
  if (!a.sparse.isSparse) return;
  const auto& s = a.sparse;
  const std::string sparse_at = at + ".sparse";
  if (s.count < 1 || size_t(s.count) > a.count)
    f.fail(sparse_at + ".count", "must be in [1, " + std::to_string(a.count) + "] (the accessor's count), got " +
                                     std::to_string(s.count));
  const int index_type = s.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    f.fail(sparse_at + ".indices.componentType",
           "must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " + component_name(index_type));
  const size_t index_size = component_bytes(index_type);
  const Elements indices = locate(f, sparse_at + ".indices", s.indices.bufferView, size_t(s.indices.byteOffset),
                                  index_size, size_t(s.count), sparse_at + ".indices.bufferView");
  const Elements values = locate(f, sparse_at + ".values", s.values.bufferView, size_t(s.values.byteOffset), size,
                                 size_t(s.count), sparse_at + ".values.bufferView");
  uint64_t previous = 0;
  for (size_t k = 0; k < size_t(s.count); ++k) {
    uint32_t i = 0;
    const uint8_t* p = indices.data + k * index_size;
    if (index_size == 1) i = *p;
    else if (index_size == 2) i = uint16_t(p[0] | p[1] << 8);
    else std::memcpy(&i, p, 4);
    if (i >= a.count)
      f.fail(item(sparse_at + ".indices", k), "index " + std::to_string(i) + " out of range (" +
                                                  plural(a.count, "element") + ")");
    if (k > 0 && i <= previous)
      f.fail(item(sparse_at + ".indices", k), "index " + std::to_string(i) + " does not increase");
    previous = i;
    put(i, values.data + k * size);
  }
}

// One component as a float; normalized integers as the spec maps them (3.11).
float component(const uint8_t* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = int8_t(p[0]);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0.0f;  // refused before: UNSIGNED_INT is no attribute type
}

// A vertex attribute as N floats per vertex: FLOAT, or (normalized) 8/16-bit
// integers, which the spec allows for texture coordinates and
// KHR_mesh_quantization for positions and normals. Values must be finite.
template <int N>
std::vector<glm::vec<N, float>> read_attribute(const File& f, int index, const std::string& at, const char* semantic) {
  const tinygltf::Accessor& a = accessor(f, index, at);
  const std::string self = item("accessors", size_t(index));
  if (type_components(a.type) != N || a.type == TINYGLTF_TYPE_MAT2)
    f.fail(self, std::string(semantic) + " must be VEC" + std::to_string(N) + ", got " + type_name(a.type));
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    f.fail(self, std::string(semantic) + " cannot be UNSIGNED_INT");
  const size_t size = component_bytes(a.componentType);
  std::vector<glm::vec<N, float>> out(a.count);
  visit_elements(f, index, a, [&](size_t i, const uint8_t* p) {
    for (int c = 0; c < N; ++c) out[i][c] = component(p + size_t(c) * size, a.componentType, a.normalized);
  });
  for (size_t i = 0; i < out.size(); ++i) {
    for (int c = 0; c < N; ++c) {
      if (std::isfinite(out[i][c])) continue;
      std::string got;
      for (int k = 0; k < N; ++k) got += (k ? ", " : "") + float_string(out[i][k]);
      f.fail(item(self, i), "must be " + std::to_string(N) + " finite numbers, got [" + got + "]");
    }
  }
  return out;
}

// Vertex indices, each checked against the primitive's vertex count.
std::vector<uint32_t> read_indices(const File& f, int index, const std::string& at, size_t vertices) {
  const tinygltf::Accessor& a = accessor(f, index, at);
  const std::string self = item("accessors", size_t(index));
  if (a.type != TINYGLTF_TYPE_SCALAR) f.fail(self, "indices must be SCALAR, got " + type_name(a.type));
  const int type = a.componentType;
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    f.fail(self, "indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, got " + component_name(type));
  std::vector<uint32_t> out(a.count);
  visit_elements(f, index, a, [&](size_t i, const uint8_t* p) {
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      out[i] = p[0];
    } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t v;
      std::memcpy(&v, p, 2);
      out[i] = v;
    } else {
      std::memcpy(&out[i], p, 4);
    }
  });
  for (size_t i = 0; i < out.size(); ++i)
    if (out[i] >= vertices)
      f.fail(item(self, i), "index " + std::to_string(out[i]) + " out of range (" +
                                plural(vertices, "vertex", "vertices") + ")");
  return out;
}

// ---------------------------------------------------------------------------
// meshes (3.7.2)
// ---------------------------------------------------------------------------

const char* kModeNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};

int attribute(const tinygltf::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

// glTF mesh `m` as a Mesh whose per-triangle materials index the file's
// materials, the index materials.size() standing for glTF's default material.
// Returns a mesh without triangles if none of its primitives has any.
Mesh read_mesh(File& f, size_t m) {
  const tinygltf::Mesh& gm = f.model.meshes[m];
  const std::string mesh_at = item("meshes", m);
  Mesh mesh;
  mesh.name = gm.name.empty() ? mesh_at : gm.name;

  // Triangle primitives with positions; the others are skipped (and named in one warning).
  std::vector<size_t> kept;
  std::vector<std::string> skipped;
  for (size_t j = 0; j < gm.primitives.size(); ++j) {
    const tinygltf::Primitive& p = gm.primitives[j];
    if (p.mode < 0 || p.mode > 6)
      f.fail(item(mesh_at + ".primitives", j) + ".mode", "unknown mode " + std::to_string(p.mode) + " (expected 0 to 6)");
    std::string reason = p.mode < TINYGLTF_MODE_TRIANGLES ? kModeNames[p.mode] : "";
    if (reason.empty() && attribute(p, "POSITION") < 0) reason = "no POSITION";
    if (reason.empty()) kept.push_back(j);
    else if (std::find(skipped.begin(), skipped.end(), reason) == skipped.end()) skipped.push_back(reason);
  }
  if (kept.size() < gm.primitives.size()) {
    std::string reasons;
    for (const std::string& r : skipped) reasons += (reasons.empty() ? "" : ", ") + r;
    f.warnings.push_back(f.path + ": " + mesh_at + (gm.name.empty() ? "" : " \"" + gm.name + "\"") + ": skipped " +
                         plural(gm.primitives.size() - kept.size(), "primitive") + " (" + reasons +
                         "): only triangles are rendered");
  }
  const auto has = [&](size_t j, const char* name) { return attribute(gm.primitives[j], name) >= 0; };
  const bool normals =
      !kept.empty() && std::all_of(kept.begin(), kept.end(), [&](size_t j) { return has(j, "NORMAL"); });
  // Uvs matter only under a texture: a primitive without them beside one
  // with them (an untextured part of a textured mesh) gets uv (0, 0).
  const bool uvs = std::any_of(kept.begin(), kept.end(), [&](size_t j) { return has(j, "TEXCOORD_0"); });
  // TANGENT (3.7.2.1) is kept only where it is used: beside normals (the
  // spec ignores it without) and uvs, under a material with a normal map.
  // Elsewhere it is still read and checked, so that a bad one is refused
  // whatever material the primitive has.
  const auto normal_mapped = [&](size_t j) {
    const int material = gm.primitives[j].material;
    return material >= 0 && size_t(material) < f.model.materials.size() &&
           f.model.materials[size_t(material)].normalTexture.index >= 0;
  };
  const auto keeps_tangents = [&](size_t j) {
    return normals && uvs && has(j, "TANGENT") && normal_mapped(j);
  };
  const bool tangents = std::any_of(kept.begin(), kept.end(), keeps_tangents);

  // Primitives that share their vertex accessors share the vertices.
  struct VertexSet {
    int position, normal, uv, tangent;
    uint32_t base, count;
  };
  std::vector<VertexSet> sets;
  const size_t default_material = f.model.materials.size();
  for (size_t j : kept) {
    const tinygltf::Primitive& p = gm.primitives[j];
    const std::string at = item(mesh_at + ".primitives", j);
    const int position = attribute(p, "POSITION");
    const int normal = normals ? attribute(p, "NORMAL") : -1;
    const int uv = uvs ? attribute(p, "TEXCOORD_0") : -1;
    const int tangent = attribute(p, "TANGENT");
    const bool keep_tangent = keeps_tangents(j);
    auto set = std::find_if(sets.begin(), sets.end(), [&](const VertexSet& s) {
      return s.position == position && s.normal == normal && s.uv == uv && s.tangent == (keep_tangent ? tangent : -1);
    });
    if (set == sets.end()) {
      const auto positions = read_attribute<3>(f, position, at + ".attributes.POSITION", "POSITION");
      const auto count_check = [&](size_t count, const char* name, int index) {
        if (count != positions.size())
          f.fail(at + ".attributes." + name, item("accessors", size_t(index)) + " has " + plural(count, "element") +
                                                 ", POSITION " + std::to_string(positions.size()));
      };
      if (normal >= 0) {
        const auto n = read_attribute<3>(f, normal, at + ".attributes.NORMAL", "NORMAL");
        count_check(n.size(), "NORMAL", normal);
        mesh.normals.insert(mesh.normals.end(), n.begin(), n.end());
      }
      if (uv >= 0) {
        const auto t = read_attribute<2>(f, uv, at + ".attributes.TEXCOORD_0", "TEXCOORD_0");
        count_check(t.size(), "TEXCOORD_0", uv);
        mesh.uvs.insert(mesh.uvs.end(), t.begin(), t.end());
      } else if (uvs) {
        mesh.uvs.insert(mesh.uvs.end(), positions.size(), glm::vec2(0.0f));
      }
      if (tangent >= 0) {
        const std::string tangent_at = at + ".attributes.TANGENT";
        const auto t = read_attribute<4>(f, tangent, tangent_at, "TANGENT");
        count_check(t.size(), "TANGENT", tangent);
        for (size_t i = 0; i < t.size(); ++i)
          if (t[i].w != 1.0f && t[i].w != -1.0f)
            f.fail(tangent_at, item(item("accessors", size_t(tangent)), i) +
                                   ": w (the handedness) must be 1 or -1, got " + float_string(t[i].w));
        if (keep_tangent) mesh.tangents.insert(mesh.tangents.end(), t.begin(), t.end());
      }
      if (tangents && !keep_tangent) mesh.tangents.insert(mesh.tangents.end(), positions.size(), glm::vec4(0.0f));
      if (mesh.positions.size() + positions.size() > UINT32_MAX)
        f.fail(mesh_at, "more than 2^32 - 1 vertices");
      sets.push_back({position, normal, uv, keep_tangent ? tangent : -1, uint32_t(mesh.positions.size()),
                      uint32_t(positions.size())});
      mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
      set = sets.end() - 1;
    }

    std::vector<uint32_t> v;
    if (p.indices >= 0) {
      v = read_indices(f, p.indices, at + ".indices", set->count);
    } else {
      v.resize(set->count);
      for (uint32_t i = 0; i < set->count; ++i) v[i] = i;
    }
    const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
      mesh.indices.insert(mesh.indices.end(), {set->base + a, set->base + b, set->base + c});
    };
    // Strips and fans as the spec lists their triangles (3.7.2.1), which keeps
    // every triangle's winding that of the first.
    if (p.mode == TINYGLTF_MODE_TRIANGLES) {
      if (v.size() % 3)
        f.fail(at, plural(v.size(), "vertex", "vertices") + " do not make whole triangles (TRIANGLES takes 3 each)");
      for (size_t i = 0; i + 2 < v.size(); i += 3) add(v[i], v[i + 1], v[i + 2]);
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < v.size(); ++i) {
        if (i % 2 == 0) add(v[i], v[i + 1], v[i + 2]);
        else add(v[i], v[i + 2], v[i + 1]);
      }
    } else {  // TRIANGLE_FAN
      for (size_t i = 0; i + 2 < v.size(); ++i) add(v[i + 1], v[i + 2], v[0]);
    }
    size_t material = default_material;
    if (p.material >= 0) {
      f.get(f.model.materials, p.material, "materials", at + ".material");
      material = size_t(p.material);
    }
    mesh.materials.resize(mesh.indices.size() / 3, uint32_t(material));
  }
  return mesh;
}

// ---------------------------------------------------------------------------
// materials
// ---------------------------------------------------------------------------

// The file's textures that its materials use, each stored once however many
// materials refer to it, in the order they are first used.
struct Textures {
  std::vector<Texture> list;
  std::vector<int> index_of;  // glTF texture -> index in `list`; -1: not used yet
};

Wrap wrap_mode(const File& f, int mode, const std::string& at) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
  }
  f.fail(at, "unknown wrap mode " + std::to_string(mode) +
                 " (expected 10497 REPEAT, 33071 CLAMP_TO_EDGE or 33648 MIRRORED_REPEAT)");
}

// The texture a textureInfo at `at` names: its image (decoded by
// decode_rgba8) and its sampler's wrap modes (3.8.4; without a sampler,
// REPEAT). Filters are not read: textures are always sampled bilinearly.
uint32_t read_texture(const File& f, Textures& textures, int index, const std::string& at) {
  const tinygltf::Texture& t = f.get(f.model.textures, index, "textures", at + ".index");
  int& stored = textures.index_of[size_t(index)];
  if (stored >= 0) return uint32_t(stored);
  const std::string self = item("textures", size_t(index));
  if (t.source < 0) f.fail(self, "has no source image (octrace reads the images of the core spec, PNG and JPEG)");
  const tinygltf::Image& image = f.get(f.model.images, t.source, "images", self + ".source");
  const std::string image_at = item("images", size_t(t.source));
  if (image.width <= 0 || image.height <= 0 || image.image.size() != size_t(image.width) * size_t(image.height) * 4)
    f.fail(image_at, "has no image data");
  Texture out;
  out.width = uint32_t(image.width);
  out.height = uint32_t(image.height);
  out.texels.resize(size_t(out.width) * out.height);
  // R, G, B, A bytes read as one little-endian uint: r | g << 8 | b << 16 | a << 24.
  std::memcpy(out.texels.data(), image.image.data(), image.image.size());
  if (t.sampler >= 0) {
    const tinygltf::Sampler& sampler = f.get(f.model.samplers, t.sampler, "samplers", self + ".sampler");
    const std::string sampler_at = item("samplers", size_t(t.sampler));
    out.wrap_s = wrap_mode(f, sampler.wrapS, sampler_at + ".wrapS");
    out.wrap_t = wrap_mode(f, sampler.wrapT, sampler_at + ".wrapT");
  }
  stored = int(textures.list.size());
  textures.list.push_back(std::move(out));
  return uint32_t(stored);
}

std::string numbers_string(const std::vector<double>& v) {
  std::string out;
  for (double x : v) out += (out.empty() ? "" : ", ") + float_string(float(x));
  return "[" + out + "]";
}

bool in_unit_range(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return x >= 0.0 && x <= 1.0; });
}

// A number of the material's extension `name`, or `fallback` without one
// (the schema checked its type).
double extension_number(const tinygltf::Material& gm, const char* name, const char* field, double fallback) {
  const auto it = gm.extensions.find(name);
  if (it == gm.extensions.end()) return fallback;
  const tinygltf::Value& v = it->second.Get(field);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// The uv transform of a textureInfo (KHR_texture_transform; identity
// without it), as the extension defines it: uv' = T R S uv, T the offset, R
// the rotation counter-clockwise in uv space by `rotation` radians, S the
// scale. By columns: x_axis = R (sx, 0), y_axis = R (0, sy), offset.
// `extensions`: the textureInfo's (a normalTextureInfo is another type).
glm::mat3x2 texture_transform(const File& f, const tinygltf::Value& v, const std::string& ext_at);

glm::mat3x2 uv_transform(const File& f, const tinygltf::ExtensionMap& extensions, const std::string& at) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end()) return glm::mat3x2(1.0f);
  return texture_transform(f, it->second, at + ".extensions.KHR_texture_transform");
}

// The same for a textureInfo that tinygltf leaves as a JSON value (one in
// an extension, as KHR_materials_transmission's transmissionTexture).
glm::mat3x2 uv_transform(const File& f, const tinygltf::Value& texture_info, const std::string& at) {
  const tinygltf::Value& v = texture_info.Get("extensions").Get("KHR_texture_transform");
  if (!v.IsObject()) return glm::mat3x2(1.0f);
  return texture_transform(f, v, at + ".extensions.KHR_texture_transform");
}

// KHR_texture_transform's object `v` (at `ext_at`) as the 2x3 matrix.
glm::mat3x2 texture_transform(const File& f, const tinygltf::Value& v, const std::string& ext_at) {
  // The schema checked the types and lengths; the values must fit a float.
  const auto number = [&](const tinygltf::Value& x, const std::string& field) {
    const double d = x.GetNumberAsDouble();
    if (!std::isfinite(float(d))) f.fail(ext_at + "." + field, "must be a finite number, got " + float_string(float(d)));
    return d;
  };
  const auto pair = [&](const char* field, double fallback) {
    const tinygltf::Value& x = v.Get(field);
    if (!x.IsArray()) return glm::dvec2(fallback);
    return glm::dvec2(number(x.Get(0), field), number(x.Get(1), field));
  };
  const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
  const double rotation = v.Get("rotation").IsNumber() ? number(v.Get("rotation"), "rotation") : 0.0;
  const double c = std::cos(rotation), s = std::sin(rotation);
  return glm::mat3x2(glm::vec2(glm::dvec2(c, s) * scale.x), glm::vec2(glm::dvec2(-s, c) * scale.y), glm::vec2(offset));
}

// The texture coordinate set a textureInfo uses: KHR_texture_transform's
// texCoord overrides the textureInfo's own.
int texture_coordinate_set(const tinygltf::TextureInfo& t) {
  const auto it = t.extensions.find("KHR_texture_transform");
  if (it != t.extensions.end() && it->second.Get("texCoord").IsInt()) return it->second.Get("texCoord").GetNumberAsInt();
  return t.texCoord;
}

// A glTF material as octrace renders it: glTF's metallic-roughness material
// (3.9.2, Appendix B) with base colour = baseColorFactor.rgb x
// baseColorTexture, metallic and roughness = their factors x the blue and
// green channels of metallicRoughnessTexture, the ior of KHR_materials_ior,
// and emission = emissiveFactor x KHR_materials_emissive_strength's
// emissiveStrength x emissiveTexture (3.9.3), the normal map of
// normalTexture (3.9.4: tangent space, xy times its scale), each texture through its
// KHR_texture_transform, and alpha = baseColorFactor.a x the base colour
// texture's alpha with alphaMode and alphaCutoff (3.9.6; BLEND as a
// stochastic cut-out) and doubleSided (false: back faces are not hit), and
// KHR_materials_transmission's transmissionFactor (times its
// transmissionTexture's red channel): thin-walled without
// KHR_materials_volume, a closed solid of the material's ior with it
// (thicknessFactor > 0; the thickness value itself is not used), absorbing
// by the volume's attenuationColor and attenuationDistance.
Material read_material(const File& f, Textures& textures, size_t i) {
  const tinygltf::Material& gm = f.model.materials[i];
  const std::string at = item("materials", i);
  const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
  const std::string pbr_at = at + ".pbrMetallicRoughness";
  const std::vector<double>& c = pbr.baseColorFactor;
  if (!in_unit_range(c)) f.fail(pbr_at + ".baseColorFactor", "must be 4 numbers in [0, 1], got " + numbers_string(c));
  Material m;
  m.type = MaterialType::Pbr;
  m.albedo = {float(c[0]), float(c[1]), float(c[2])};
  m.alpha = float(c[3]);
  // Alpha (3.9.6): OPAQUE ignores it, MASK cuts out below alphaCutoff, BLEND
  // is rendered as a stochastic cut-out (scene.h).
  if (gm.alphaMode == "MASK") m.alpha_mode = AlphaMode::Mask;
  else if (gm.alphaMode == "BLEND") m.alpha_mode = AlphaMode::Blend;
  else if (gm.alphaMode != "OPAQUE")
    f.fail(at + ".alphaMode", "must be \"OPAQUE\", \"MASK\" or \"BLEND\", got \"" + gm.alphaMode + "\"");
  if (!(gm.alphaCutoff >= 0.0 && std::isfinite(float(gm.alphaCutoff))))
    f.fail(at + ".alphaCutoff", "must be a finite number >= 0, got " + float_string(float(gm.alphaCutoff)));
  m.alpha_cutoff = float(gm.alphaCutoff);
  m.double_sided = gm.doubleSided;
  if (pbr.baseColorTexture.index >= 0) {
    m.base_color_texture = read_texture(f, textures, pbr.baseColorTexture.index, pbr_at + ".baseColorTexture");
    m.base_color_uv = uv_transform(f, pbr.baseColorTexture.extensions, pbr_at + ".baseColorTexture");
  }
  for (const auto& [factor, out, name] : {std::tuple{pbr.metallicFactor, &m.metallic, ".metallicFactor"},
                                          std::tuple{pbr.roughnessFactor, &m.roughness, ".roughnessFactor"}}) {
    if (!(factor >= 0.0 && factor <= 1.0))
      f.fail(pbr_at + name, "must be a number in [0, 1], got " + float_string(float(factor)));
    *out = float(factor);
  }
  if (pbr.metallicRoughnessTexture.index >= 0) {
    m.metallic_roughness_texture =
        read_texture(f, textures, pbr.metallicRoughnessTexture.index, pbr_at + ".metallicRoughnessTexture");
    m.metallic_roughness_uv = uv_transform(f, pbr.metallicRoughnessTexture.extensions, pbr_at + ".metallicRoughnessTexture");
  }
  const double ior = extension_number(gm, "KHR_materials_ior", "ior", 1.5);
  // The extension's schema: 1 or more (its 0, "infinitely reflective", is not supported).
  if (!(ior >= 1.0 && std::isfinite(float(ior))))
    f.fail(at + ".extensions.KHR_materials_ior.ior", "must be a finite number >= 1, got " + float_string(float(ior)));
  m.ior = float(ior);
  const std::string transmission_at = at + ".extensions.KHR_materials_transmission.transmissionFactor";
  const double transmission = extension_number(gm, "KHR_materials_transmission", "transmissionFactor", 0.0);
  if (!(transmission >= 0.0 && transmission <= 1.0))
    f.fail(transmission_at, "must be a number in [0, 1], got " + float_string(float(transmission)));
  m.transmission = float(transmission);
  const double thickness = extension_number(gm, "KHR_materials_volume", "thicknessFactor", 0.0);
  if (!(thickness >= 0.0 && std::isfinite(float(thickness))))
    f.fail(at + ".extensions.KHR_materials_volume.thicknessFactor",
           "must be a finite number >= 0, got " + float_string(float(thickness)));
  // Only whether the thickness is > 0 matters: it says that the mesh is a
  // closed solid. Its value is a rasteriser's stand-in for the distance a
  // ray travels inside; a path tracer traces that distance through the real
  // geometry (as is thicknessTexture, not read).
  m.thin_walled = !(thickness > 0.0);
  if (const auto it = gm.extensions.find("KHR_materials_transmission"); it != gm.extensions.end()) {
    const tinygltf::Value& info = it->second.Get("transmissionTexture");
    const std::string texture_at = at + ".extensions.KHR_materials_transmission.transmissionTexture";
    if (info.IsObject()) {
      const int index = info.Get("index").GetNumberAsInt();
      f.get(f.model.textures, index, "textures", texture_at + ".index");
      // Times a zero factor it passes nothing: not stored.
      if (m.transmission > 0.0f) {
        m.transmission_texture = read_texture(f, textures, index, texture_at);
        m.transmission_uv = uv_transform(f, info, texture_at);
      }
    }
  }
  if (const auto it = gm.extensions.find("KHR_materials_volume"); it != gm.extensions.end()) {
    const std::string volume_at = at + ".extensions.KHR_materials_volume";
    const tinygltf::Value& color = it->second.Get("attenuationColor");
    if (color.IsArray()) {
      // The schema checked 3 numbers.
      const std::vector<double> c = {color.Get(0).GetNumberAsDouble(), color.Get(1).GetNumberAsDouble(),
                                     color.Get(2).GetNumberAsDouble()};
      if (!in_unit_range(c))
        f.fail(volume_at + ".attenuationColor", "must be 3 numbers in [0, 1], got " + numbers_string(c));
      m.attenuation_color = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
    }
    const tinygltf::Value& distance = it->second.Get("attenuationDistance");
    if (distance.IsNumber()) {
      const double d = distance.GetNumberAsDouble();
      if (!(d > 0.0 && std::isfinite(float(d))))
        f.fail(volume_at + ".attenuationDistance",
               "must be a finite number > 0 (leave it out for no absorption), got " + float_string(float(d)));
      m.attenuation_distance = float(d);
    }
  }
  // A ray leaves a closed solid through the back faces of its triangles:
  // they are hit whatever doubleSided says (the volume extension requires a
  // closed mesh; glTF's doubleSided defaults to false).
  if (m.transmission > 0.0f && !m.thin_walled) m.double_sided = true;

  if (gm.normalTexture.index >= 0) {
    const std::string normal_at = at + ".normalTexture";
    m.normal_texture = read_texture(f, textures, gm.normalTexture.index, normal_at);
    m.normal_uv = uv_transform(f, gm.normalTexture.extensions, normal_at);
    if (!std::isfinite(float(gm.normalTexture.scale)))
      f.fail(normal_at + ".scale", "must be a finite number, got " + float_string(float(gm.normalTexture.scale)));
    m.normal_scale = float(gm.normalTexture.scale);
  }

  const std::vector<double>& e = gm.emissiveFactor;
  if (!in_unit_range(e)) f.fail(at + ".emissiveFactor", "must be 3 numbers in [0, 1], got " + numbers_string(e));
  const double strength = extension_number(gm, "KHR_materials_emissive_strength", "emissiveStrength", 1.0);
  if (!(strength >= 0.0 && std::isfinite(float(strength))))
    f.fail(at + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
           "must be a finite number >= 0, got " + float_string(float(strength)));
  if (e.size() == 3) m.emission = glm::vec3(float(e[0] * strength), float(e[1] * strength), float(e[2] * strength));
  if (gm.emissiveTexture.index >= 0) {
    const std::string texture_at = at + ".emissiveTexture";
    f.get(f.model.textures, gm.emissiveTexture.index, "textures", texture_at + ".index");
    // Times a zero emission it adds nothing: not stored.
    if (m.emission != glm::vec3(0.0f)) {
      m.emission_texture = read_texture(f, textures, gm.emissiveTexture.index, texture_at);
      m.emission_uv = uv_transform(f, gm.emissiveTexture.extensions, texture_at);
    }
  }
  return m;
}

// What of the file's materials is not rendered yet, named in one warning.
// (Occlusion textures are not listed: a path tracer finds occlusion itself.)
std::vector<std::string> approximations(const tinygltf::Model& model) {
  std::vector<std::string> out;
  const auto note = [&](const std::string& what) {
    if (std::find(out.begin(), out.end(), what) == out.end()) out.push_back(what);
  };
  for (const tinygltf::Material& m : model.materials) {
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    for (const tinygltf::TextureInfo* t : {&pbr.baseColorTexture, &pbr.metallicRoughnessTexture, &m.emissiveTexture})
      if (t->index >= 0 && texture_coordinate_set(*t) != 0) note("texture coordinate sets other than 0");
    if (m.normalTexture.index >= 0 && m.normalTexture.texCoord != 0) note("texture coordinate sets other than 0");
    if (const auto it = m.extensions.find("KHR_materials_transmission"); it != m.extensions.end()) {
      const tinygltf::Value& t = it->second.Get("transmissionTexture");
      const tinygltf::Value& transform = t.Get("extensions").Get("KHR_texture_transform");
      if ((t.Get("texCoord").IsInt() && t.Get("texCoord").GetNumberAsInt() != 0) ||
          (transform.Get("texCoord").IsInt() && transform.Get("texCoord").GetNumberAsInt() != 0))
        note("texture coordinate sets other than 0");
    }
  }
  for (const std::string& e : model.extensionsUsed)
    if (e.rfind("KHR_materials_", 0) == 0 && e != "KHR_materials_emissive_strength" && e != "KHR_materials_ior" &&
        e != "KHR_materials_transmission" && e != "KHR_materials_volume")
      note(e);
  return out;
}

// ---------------------------------------------------------------------------
// nodes (3.5)
// ---------------------------------------------------------------------------

glm::dmat4 local_transform(const File& f, size_t n) {
  const tinygltf::Node& node = f.model.nodes[n];
  if (node.matrix.size() == 16) {
    const glm::dmat4 m = glm::make_mat4(node.matrix.data());  // column-major, as glm
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
      f.fail(item("nodes", n) + ".matrix", "must be an affine transform (last row 0, 0, 0, 1)");
    return m;
  }
  glm::dmat4 m(1.0);
  if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
  if (node.rotation.size() == 4) {
    // (x, y, z, w) in the file; exporters write them a little off unit length.
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (glm::length(q) == 0.0) f.fail(item("nodes", n) + ".rotation", "must be a unit quaternion, got [0, 0, 0, 0]");
    m *= glm::mat4_cast(glm::normalize(q));
  }
  if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
  return m;
}

bool finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(float(m[c][r]))) return false;
  return true;
}

struct PlacedCamera {
  uint32_t camera;  // index into the file's cameras
  glm::dmat4 world;
  bool perspective;
  double yfov;      // radians
};

// One file's scene in the file's own space.
struct Loaded {
  std::vector<Mesh> meshes;         // materials index `materials`
  std::vector<Material> materials;  // the file's, then glTF's default material if a primitive uses it
  std::vector<Texture> textures;    // the materials' textures index these
  std::vector<Instance> instances;  // world transforms of the nodes
  std::vector<PlacedCamera> cameras;  // camera nodes in the order of the hierarchy
  std::vector<Light> lights;          // KHR_lights_punctual, placed by their nodes
  size_t file_cameras = 0;
  size_t scene = 0;  // the scene placed (if the file has any)
  std::vector<std::string> warnings;
};

// KHR_lights_punctual's photometric units to octrace's radiometric ones: a
// point or spot's intensity in candela (lm/sr) and a directional light's in
// lux (lm/m^2), divided by 683 lm/W (the luminous efficacy that defines the
// candela, at 555 nm). Exporters that start from watts (Blender: W x 683 /
// 4 pi for a point light) come back to W / 4 pi, the radiant intensity of
// that many watts spread evenly.
constexpr double kLumensPerWatt = 683.0;

// Light `index` of the file, placed by a node with transform `world`: a
// light shines down the node's -Z (KHR_lights_punctual); the node's scale
// moves it but changes none of its properties.
Light read_light(const File& f, int index, const glm::dmat4& world, const std::string& at) {
  const std::string path = "extensions.KHR_lights_punctual." + item("lights", size_t(index));
  if (index < 0 || size_t(index) >= f.model.lights.size())
    f.fail(at, "index " + std::to_string(index) + " out of range (" + plural(f.model.lights.size(), "light") + ")");
  const tinygltf::Light& l = f.model.lights[size_t(index)];
  Light out;
  if (l.type == "point") out.type = LightType::Point;
  else if (l.type == "spot") out.type = LightType::Spot;
  else if (l.type == "directional") out.type = LightType::Directional;
  else f.fail(path + ".type", "unknown light type \"" + l.type + "\" (expected point, spot, directional)");
  if (!l.color.empty()) {
    if (l.color.size() != 3) f.fail(path + ".color", "expected 3 numbers");
    for (double c : l.color)
      if (!(std::isfinite(c) && c >= 0.0)) f.fail(path + ".color", "must be 3 finite numbers >= 0");
    out.color = glm::vec3(float(l.color[0]), float(l.color[1]), float(l.color[2]));
  }
  if (!(std::isfinite(l.intensity) && l.intensity >= 0.0))
    f.fail(path + ".intensity", "must be a finite number >= 0, got " + float_string(float(l.intensity)));
  out.intensity = float(l.intensity / kLumensPerWatt);
  if (out.type == LightType::Spot) {
    const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
    if (!(outer > 0.0 && outer <= glm::half_pi<double>()))
      f.fail(path + ".spot.outerConeAngle", "must be in (0, pi/2] radians, got " + float_string(float(outer)));
    if (!(inner >= 0.0 && inner < outer))
      f.fail(path + ".spot.innerConeAngle", "must be in [0, outerConeAngle) radians, got " + float_string(float(inner)));
    out.inner_cone = float(glm::degrees(inner));
    out.outer_cone = float(glm::degrees(outer));
    // Rounding to degrees in float must keep inner < outer <= 90.
    out.outer_cone = std::min(out.outer_cone, 90.0f);
    if (!(out.inner_cone < out.outer_cone)) out.inner_cone = std::nextafter(out.outer_cone, 0.0f);
  }
  out.position = glm::vec3(world[3]);
  const glm::dvec3 d = glm::dmat3(world) * glm::dvec3(0, 0, -1);
  if (!(glm::length(d) > 0.0)) f.fail(at, "the node's transform flattens the light's direction");
  out.direction = glm::vec3(glm::normalize(d));
  return out;
}

// `own_materials`: read the file's materials and textures (not when the
// scene replaces them).
Loaded read_gltf(const std::string& bytes, const std::string& path, std::optional<uint32_t> scene_index,
                 bool own_materials) {
  File f = open_gltf(bytes, path);
  const tinygltf::Model& model = f.model;
  Loaded out;
  out.file_cameras = model.cameras.size();

  if (scene_index && *scene_index >= model.scenes.size())
    throw SettingError("gltf.scene", ": index " + std::to_string(*scene_index) + " out of range (" + path + " has " +
                                         plural(model.scenes.size(), "scene") + ")");
  if (model.defaultScene >= 0) f.get(model.scenes, model.defaultScene, "scenes", "scene");
  out.scene = scene_index ? *scene_index : model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
  if (model.scenes.empty()) f.warnings.push_back(path + ": has no scenes: nothing to place");

  if (own_materials) {
    Textures textures{{}, std::vector<int>(model.textures.size(), -1)};
    for (size_t i = 0; i < model.materials.size(); ++i) out.materials.push_back(read_material(f, textures, i));
    out.textures = std::move(textures.list);
    const std::vector<std::string> missing = approximations(model);
    if (!missing.empty()) {
      std::string list;
      for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
      f.warnings.push_back(path + ": materials render without what octrace does not support yet: " + list);
    }
  }

  // Depth first with an explicit stack, so that a deep hierarchy cannot
  // overflow the call stack. glTF nodes form disjoint trees (3.5.3): a node
  // met twice is either in a loop (RecursiveNodes) or has two parents.
  enum : uint8_t { Unseen, OnPath, Done };
  std::vector<uint8_t> state(model.nodes.size(), Unseen);
  std::vector<int> mesh_of(model.meshes.size(), -2);  // -2: not read yet, -1: no triangles
  struct Frame {
    size_t node;
    glm::dmat4 world;
    size_t next_child = 0;
  };
  std::vector<Frame> stack;
  const auto enter = [&](int node, const glm::dmat4& parent, const std::string& at) {
    f.get(model.nodes, node, "nodes", at);
    const size_t n = size_t(node);
    if (state[n] == OnPath)
      f.fail(at, "node " + std::to_string(n) + " is its own ancestor (the node hierarchy loops)");
    if (state[n] == Done) f.fail(at, "node " + std::to_string(n) + " is placed twice (glTF nodes form trees)");
    state[n] = OnPath;
    const glm::dmat4 world = parent * local_transform(f, n);
    if (!finite(world)) f.fail(item("nodes", n), "the transform from the scene root is not finite");
    stack.push_back({n, world});

    const tinygltf::Node& gn = model.nodes[n];
    if (gn.mesh >= 0) {
      f.get(model.meshes, gn.mesh, "meshes", item("nodes", n) + ".mesh");
      int& m = mesh_of[size_t(gn.mesh)];
      if (m == -2) {
        Mesh mesh = read_mesh(f, size_t(gn.mesh));
        m = mesh.indices.empty() ? -1 : int(out.meshes.size());
        if (m >= 0) out.meshes.push_back(std::move(mesh));
      }
      // A node scaled to nothing (as animations hide parts) shows nothing and
      // has no inverse for the renderer's rays.
      if (m >= 0 && glm::determinant(glm::dmat3(world)) != 0.0) out.instances.push_back({uint32_t(m), glm::mat4(world)});
    }
    if (gn.camera >= 0) {
      const tinygltf::Camera& c = f.get(model.cameras, gn.camera, "cameras", item("nodes", n) + ".camera");
      out.cameras.push_back({uint32_t(gn.camera), world, c.type == "perspective", c.perspective.yfov});
    }
    if (const auto it = gn.extensions.find("KHR_lights_punctual"); it != gn.extensions.end()) {
      const std::string at = item("nodes", n) + ".extensions.KHR_lights_punctual.light";
      const tinygltf::Value& v = it->second;
      if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsInt()) f.fail(at, "expected a light index");
      out.lights.push_back(read_light(f, v.Get("light").GetNumberAsInt(), world, at));
    }
  };
  if (!model.scenes.empty()) {
    const tinygltf::Scene& scene = model.scenes[out.scene];
    for (size_t r = 0; r < scene.nodes.size(); ++r) {
      enter(scene.nodes[r], glm::dmat4(1.0), item(item("scenes", out.scene) + ".nodes", r));
      while (!stack.empty()) {
        Frame& top = stack.back();
        const std::vector<int>& children = model.nodes[top.node].children;
        if (top.next_child == children.size()) {
          state[top.node] = Done;
          stack.pop_back();
          continue;
        }
        const size_t c = top.next_child++;
        const glm::dmat4 world = top.world;  // `top` moves when enter() grows the stack
        enter(children[c], world, item(item("nodes", top.node) + ".children", c));
      }
    }
  }

  const bool default_used = std::any_of(out.meshes.begin(), out.meshes.end(), [&](const Mesh& m) {
    return std::find(m.materials.begin(), m.materials.end(), uint32_t(model.materials.size())) != m.materials.end();
  });
  if (default_used) {
    Material m{MaterialType::Pbr, glm::vec3(1.0f)};
    m.double_sided = false;  // glTF's default material is single-sided (3.9.1)
    out.materials.push_back(m);
  }
  out.warnings = std::move(f.warnings);
  return out;
}

void emit_warnings(const GltfOptions& opts, const std::vector<std::string>& warnings) {
  if (!opts.warn) return;
  for (const std::string& w : warnings) opts.warn(w);
}

// Adds the file's materials (unless overridden), textures, meshes and
// instances; returns the placement, for place_again.
GltfPlacement append(Scene& scene, const Loaded& file, std::optional<uint32_t> material_override,
                     const glm::mat4& transform) {
  const auto mesh_base = uint32_t(scene.meshes.size());
  const auto material_base = uint32_t(scene.materials.size());
  if (!material_override) {
    const auto texture_base = uint32_t(scene.textures.size());
    for (Material m : file.materials) {
      for (const MaterialTexture& t : kMaterialTextures)
        if (m.*t.index) *(m.*t.index) += texture_base;
      scene.materials.push_back(m);
    }
    scene.mesh_file_materials += file.materials.size();
    scene.textures.insert(scene.textures.end(), file.textures.begin(), file.textures.end());
  }
  for (const Mesh& m : file.meshes) {
    scene.meshes.push_back(m);
    for (uint32_t& material : scene.meshes.back().materials)
      material = material_override ? *material_override : material_base + material;
  }
  GltfPlacement placement;
  placement.mesh_base = mesh_base;
  for (const Instance& i : file.instances) placement.nodes.emplace_back(i.mesh, glm::dmat4(i.transform));
  placement.lights = file.lights;
  place_again(scene, placement, transform);
  return placement;
}

// ---------------------------------------------------------------------------
// cameras
// ---------------------------------------------------------------------------

// A glTF camera looks down its node's -Z with +Y up (3.10.1); yfov in radians.
Camera placed_camera(const std::string& path, const PlacedCamera& placed) {
  if (!(placed.yfov > 0.0 && placed.yfov < glm::pi<double>()))
    throw InputError(path + ": " + item("cameras", placed.camera) + ".perspective.yfov: must be in (0, pi) radians, got " +
                     float_string(float(placed.yfov)));
  const glm::dvec3 eye(placed.world[3]);
  const glm::dvec3 forward = glm::normalize(-glm::dvec3(placed.world[2]));
  Camera c;
  c.lookfrom = glm::vec3(eye);
  c.lookat = glm::vec3(eye + forward);
  c.vup = glm::vec3(glm::normalize(glm::dvec3(placed.world[1])));
  c.vfov = float(glm::degrees(placed.yfov));
  c.aperture = 0.0f;  // glTF cameras are pinholes
  c.focus_dist = 1.0f;
  return c;
}

// Looks at the centre of the world bounds of the instances from rtiow's
// direction (13, 2, 3), as far away as makes their bounding sphere fill the
// 30 degree vertical field of view (wider images show more at the sides).
// The bounds are those of each mesh's box transformed, a little loose under
// rotation but cheap for many instances.
Camera framing_camera(const Scene& scene) {
  Camera c;
  c.aperture = 0.0f;
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes;
  for (const Mesh& m : scene.meshes) {
    glm::dvec3 a(INFINITY), b(-INFINITY);
    for (glm::vec3 p : m.positions) a = glm::min(a, glm::dvec3(p)), b = glm::max(b, glm::dvec3(p));
    boxes.emplace_back(a, b);
  }
  for (const Instance& i : scene.instances) {
    const auto& [a, b] = boxes[i.mesh];
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 corner(k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z);
      const glm::dvec3 p(glm::dmat4(i.transform) * glm::dvec4(corner, 1.0));
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
  }
  if (scene.instances.empty()) return c;
  const glm::dvec3 centre = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  if (radius == 0.0) radius = 1.0;  // a single point: any distance shows it
  const double distance = radius / std::sin(glm::radians(0.5 * double(c.vfov)));
  c.lookat = glm::vec3(centre);
  c.lookfrom = glm::vec3(centre + distance * glm::normalize(glm::dvec3(13.0, 2.0, 3.0)));
  c.focus_dist = float(distance);
  return c;
}

}  // namespace

void print_warning(const std::string& message) { std::fprintf(stderr, "octrace: warning: %s\n", message.c_str()); }

GltfPlacement append_gltf(Scene& scene, const std::string& path, std::optional<uint32_t> material_override,
                          const glm::mat4& transform, const GltfOptions& opts) {
  if (material_override && *material_override >= scene.materials.size())
    throw InputError(path + ": material " + std::to_string(*material_override) + " out of range (" +
                     plural(scene.materials.size(), "material") + ")");
  const Loaded file = read_gltf(read_file(path), path, opts.scene, !material_override);
  const GltfPlacement placement = append(scene, file, material_override, transform);
  emit_warnings(opts, file.warnings);
  return placement;
}

void place_again(Scene& scene, const GltfPlacement& placement, const glm::mat4& transform) {
  // append() places a file's instances through here too, so a file placed
  // again gives the instances of loading it again.
  const glm::dmat4 t(transform);
  for (const auto& [mesh, node] : placement.nodes)
    scene.instances.push_back({placement.mesh_base + mesh, glm::mat4(t * node)});
  for (Light l : placement.lights) {
    l.position = glm::vec3(t * glm::dvec4(glm::dvec3(l.position), 1.0));
    const glm::dvec3 d = glm::dmat3(t) * glm::dvec3(l.direction);
    l.direction = glm::vec3(glm::normalize(d));
    scene.lights.push_back(l);
  }
  scene.mesh_file_lights += placement.lights.size();
}

Scene load_gltf_scene(const std::string& path, const GltfOptions& opts) {
  return parse_gltf_scene(read_file(path), path, opts);
}

Scene parse_gltf_scene(const std::string& bytes, const std::string& path, const GltfOptions& opts) {
  const Loaded file = read_gltf(bytes, path, opts.scene, true);
  Scene scene;
  append(scene, file, std::nullopt, glm::mat4(1.0f));
  MeshRef ref;
  ref.file = std::filesystem::absolute(path).lexically_normal().string();
  ref.scene = opts.scene;
  scene.mesh_refs.push_back(ref);

  // The camera asked for, or the first perspective one placed, or a framing one.
  const auto camera_error = [&](const std::string& what) { return SettingError("gltf.camera", ": " + what); };
  const PlacedCamera* chosen = nullptr;
  for (const PlacedCamera& p : file.cameras) {
    const bool wanted = opts.camera ? p.camera == *opts.camera : p.perspective;
    if (wanted && (!chosen || p.camera < chosen->camera)) chosen = &p;
  }
  if (opts.camera) {
    const uint32_t c = *opts.camera;
    if (c >= file.file_cameras)
      throw camera_error("index " + std::to_string(c) + " out of range (" + path + " has " +
                         plural(file.file_cameras, "camera") + ")");
    if (!chosen)
      throw camera_error(item("cameras", c) + " of " + path + " is not placed by a node of " +
                         item("scenes", file.scene));
    if (!chosen->perspective)
      throw camera_error(item("cameras", c) + " of " + path + " is orthographic: only perspective cameras are supported");
  }
  scene.camera = chosen ? placed_camera(path, *chosen) : framing_camera(scene);
  validate_scene(scene, path);
  emit_warnings(opts, file.warnings);
  return scene;
}

}  // namespace octrace
