// Small glTF files that the tests write themselves (no downloads, no files of
// the machine): binary data appended view by view, the JSON built as
// nlohmann::json, written as .gltf (buffer in a data URI or a .bin beside it)
// or .glb. Shared by the scene, glTF and command-line tests.
#pragma once

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "scene/scene.h"

namespace octrace::test {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kPoints = 0, kLines = 1, kTriangles = 4, kStrip = 5, kFan = 6;
constexpr int kRepeat = 10497, kClampToEdge = 33071, kMirroredRepeat = 33648;

inline std::string base64(const uint8_t* data, size_t size) {
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t n = uint32_t(data[i]) << 16 | (i + 1 < size ? uint32_t(data[i + 1]) << 8 : 0) |
                       (i + 2 < size ? uint32_t(data[i + 2]) : 0);
    out += digits[n >> 18 & 63];
    out += digits[n >> 12 & 63];
    out += i + 1 < size ? digits[n >> 6 & 63] : '=';
    out += i + 2 < size ? digits[n & 63] : '=';
  }
  return out;
}

// A PNG of width x height RGBA8 texels, rows from the top (stb_image_write).
inline std::string png(int width, int height, const std::vector<uint8_t>& rgba) {
  std::string out;
  const auto append = [](void* to, void* data, int size) {
    static_cast<std::string*>(to)->append(static_cast<const char*>(data), size_t(size));
  };
  stbi_write_png_to_func(append, &out, width, height, 4, rgba.data(), width * 4);
  return out;
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

struct GltfBuilder {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  // Appends `size` bytes as a new bufferView, 4-byte aligned as accessors need.
  int add_view(const void* data, size_t size, size_t stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (stride) view["byteStride"] = stride;
    const auto* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + size);
    doc["bufferViews"].push_back(view);
    return int(doc["bufferViews"].size()) - 1;
  }
  template <typename T>
  int add_view(const std::vector<T>& v, size_t stride = 0) {
    return add_view(v.data(), v.size() * sizeof(T), stride);
  }

  int add_accessor(int view, int component_type, size_t count, const std::string& type, size_t offset = 0,
                   bool normalized = false) {
    nlohmann::json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    if (offset) a["byteOffset"] = offset;
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size()) - 1;
  }

  int add_vec3(const std::vector<glm::vec3>& v) { return add_accessor(add_view(v), kFloat, v.size(), "VEC3"); }
  int add_vec2(const std::vector<glm::vec2>& v) { return add_accessor(add_view(v), kFloat, v.size(), "VEC2"); }
  int add_indices(const std::vector<uint8_t>& v) { return add_accessor(add_view(v), kUnsignedByte, v.size(), "SCALAR"); }
  int add_indices(const std::vector<uint16_t>& v) {
    return add_accessor(add_view(v), kUnsignedShort, v.size(), "SCALAR");
  }
  int add_indices(const std::vector<uint32_t>& v) { return add_accessor(add_view(v), kUnsignedInt, v.size(), "SCALAR"); }

  int add(const char* array, nlohmann::json item) {
    doc[array].push_back(std::move(item));
    return int(doc[array].size()) - 1;
  }
  // An image of `png_bytes` in a data URI, and a texture of it with a sampler
  // of these wrap modes; returns the texture's index.
  int add_texture(const std::string& png_bytes, int wrap_s = kRepeat, int wrap_t = kRepeat) {
    const auto* bytes = reinterpret_cast<const uint8_t*>(png_bytes.data());
    const int image = add("images", {{"uri", "data:image/png;base64," + base64(bytes, png_bytes.size())}});
    const int sampler = add("samplers", {{"wrapS", wrap_s}, {"wrapT", wrap_t}});
    return add("textures", {{"source", image}, {"sampler", sampler}});
  }

  // A mesh of one primitive.
  int add_mesh(int positions, int indices = -1, int mode = kTriangles, int material = -1) {
    nlohmann::json p = {{"attributes", {{"POSITION", positions}}}, {"mode", mode}};
    if (indices >= 0) p["indices"] = indices;
    if (material >= 0) p["material"] = material;
    return add("meshes", {{"primitives", {p}}});
  }
  void set_scene(const std::vector<int>& roots) {
    doc["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }

  // The document with its buffer at `uri` (none: a data URI).
  nlohmann::json with_buffer(const std::string& uri = "") const {
    nlohmann::json d = doc;
    if (bin.empty()) return d;
    d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
    if (!uri.empty()) d["buffers"][0]["uri"] = uri;
    else d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin.data(), bin.size());
    return d;
  }
  std::string gltf() const { return with_buffer().dump(); }

  // glTF 2.0 spec 4.4: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
  std::string glb() const {
    nlohmann::json d = doc;
    if (!bin.empty()) d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
    std::string json = d.dump();
    while (json.size() % 4) json += ' ';
    std::string data(bin.begin(), bin.end());
    while (data.size() % 4) data += '\0';
    std::string out;
    const auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(0x46546C67);
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + (data.empty() ? 0 : 8 + data.size())));
    u32(uint32_t(json.size()));
    u32(0x4E4F534A);
    out += json;
    if (!data.empty()) {
      u32(uint32_t(data.size()));
      u32(0x004E4942);
      out += data;
    }
    return out;
  }

  // Writes the file, as .glb (in any case) or .gltf by `path`'s extension; returns `path`.
  std::string write(const std::string& path) const {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    write_bytes(path, ext == ".glb" ? glb() : gltf());
    return path;
  }
};

// glTF's default material, as a primitive without one loads: base colour 1,
// metallic 1, roughness 1, single-sided.
inline Material gltf_default_material() {
  Material m{MaterialType::Pbr, glm::vec3(1.0f)};
  m.double_sided = false;
  return m;
}

// A unit square in the xy plane facing +z: 4 vertices, 2 triangles, one node.
inline GltfBuilder quad_gltf() {
  GltfBuilder b;
  const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const int indices = b.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  b.add_mesh(positions, indices);
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  return b;
}

// The unit square of quad_gltf() with TEXCOORD_0 as glTF maps an image onto
// it seen from +z with y up: uv (0, 0), the image's top-left texel, at the
// corner (0, 1, 0), u along +x and v along -y. Its material samples an image
// of `png_bytes` as its base colour (metallicFactor 0: nothing to warn about).
inline GltfBuilder textured_quad_gltf(const std::string& png_bytes, int wrap_s = kRepeat, int wrap_t = kRepeat) {
  GltfBuilder b;
  const int positions = b.add_vec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const int uvs = b.add_vec2({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  const int indices = b.add_indices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  const int texture = b.add_texture(png_bytes, wrap_s, wrap_t);
  b.add("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}}}});
  b.add("meshes", {{"primitives", {{{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                    {"indices", indices}, {"material", 0}}}}});
  b.add("nodes", {{"mesh", 0}});
  b.set_scene({0});
  return b;
}

}  // namespace octrace::test
