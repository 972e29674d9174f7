// glTF 2.0 files (.gltf with its .bin and images beside it or in data URIs,
// and .glb) as meshes, instances, materials and a camera of a Scene.
//
// Geometry: primitives of mode TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN
// (strips and fans become triangles of the same winding, glTF 2.0 spec
// 3.7.2.1); POINTS and LINES are skipped with one warning per mesh. Indexed or
// not, 8/16/32-bit indices, byteStride, sparse accessors, normalized integer
// attributes (and KHR_mesh_quantization). One glTF mesh is one Mesh, its
// primitives concatenated with a material per triangle; NORMAL is kept when
// every primitive of the mesh has it, TEXCOORD_0 when any has it (the other
// primitives' vertices at uv (0, 0)).
//
// Placement: the node hierarchy of one scene (TRS or matrix, parent * child);
// every node with a mesh is an Instance, and a mesh placed by several nodes is
// stored once. Windings are kept as the file has them even under a transform
// with a negative determinant (a mirror): the renderer flips the front face of
// such an instance, so that the file's triangles stay shared between instances.
//
// Materials: glTF's metallic-roughness material (MaterialType::Pbr), base
// colour = baseColorFactor.rgb x baseColorTexture (sRGB), metallic and
// roughness = metallicFactor and roughnessFactor x metallicRoughnessTexture's
// blue and green channels (linear), ior from KHR_materials_ior, emission =
// emissiveFactor x emissiveStrength (KHR_materials_emissive_strength) x
// emissiveTexture (sRGB); alpha = baseColorFactor.a x baseColorTexture's
// alpha, with alphaMode (MASK cuts out below alphaCutoff, BLEND is a
// stochastic cut-out), and doubleSided (false: back faces are not hit). A
// texture is its image decoded to RGBA8 (stb_image) with its sampler's wrap modes, stored once however many
// materials use it. Whatever else the materials have (normal maps,
// transmission and other material extensions, texture transforms) is
// named in one warning. Primitives without a material take glTF's default
// material (base colour 1, metallic 1, roughness 1).
//
// Errors: every problem with the file is an InputError of one line naming the
// file and the glTF path ("model.glb: accessors[3]: count 900 exceeds
// bufferView 2 (600 elements)", "model.glb: images[2]: cannot be decoded
// (...)"). Every image is decoded as the file loads, used or not.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>

#include "scene/scene.h"

namespace octrace {

// Prints "octrace: warning: MESSAGE" on stderr.
void print_warning(const std::string& message);

struct GltfOptions {
  // Which of the file's scenes to place (default: the file's default scene,
  // else its first). Out of range: SettingError "gltf.scene".
  std::optional<uint32_t> scene;
  // load_gltf_scene only: which of the file's cameras to look through
  // (default: the first perspective camera a node of the scene places, else a
  // camera that frames the scene). Not perspective, not placed by a node of the
  // scene, or out of range: SettingError "gltf.camera".
  std::optional<uint32_t> camera;
  // Receives each warning (one line, starting with the file name), once the
  // file has loaded without error; empty: none is reported.
  std::function<void(const std::string&)> warn = print_warning;
};

// A scene of the file alone: its meshes, instances and materials, its camera
// (see GltfOptions::camera; the framing camera looks at the centre of the
// scene's bounds from the direction of rtiow's (13, 2, 3) at the distance where
// the bounding sphere fills the 30 degree vertical field of view, pinhole) and
// the default gradient sky. Its mesh_refs holds one reference to the file (by
// absolute path), so that --dump-scene writes a JSON scene that loads it again.
Scene load_gltf_scene(const std::string& path, const GltfOptions& opts = {});
// The same from the file's bytes (what load_gltf_scene does once it has read
// them): .glb by its "glTF" magic or a ".glb" extension of `path`, else .gltf.
// `path` names the file in messages and is where its external buffers and
// images are looked for. The fuzz target tests/fuzz/fuzz_gltf.cpp calls it.
Scene parse_gltf_scene(const std::string& bytes, const std::string& path, const GltfOptions& opts = {});

// Adds the file's meshes to `scene` (a JSON scene's "meshes" entry), placed at
// `transform` * (node transform). The file's materials are appended to
// scene.materials unless `material_override` (an index into scene.materials)
// is given, which then colours every triangle. opts.camera is ignored.
// Returns what it placed, so that another reference to the same file (same
// scene, same material override) can be placed again by place_again without
// loading the file twice: its meshes, materials and textures are shared.
struct GltfPlacement {
  uint32_t mesh_base = 0;                             // the file's meshes start here in Scene::meshes
  std::vector<std::pair<uint32_t, glm::dmat4>> nodes;  // mesh (file index) and node transform, per instance
  std::vector<Light> lights;                           // KHR_lights_punctual, in the file's space
};
GltfPlacement append_gltf(Scene& scene, const std::string& path, std::optional<uint32_t> material_override,
                          const glm::mat4& transform, const GltfOptions& opts = {});
// Adds the instances of `placement` again, at `transform` * (node transform).
void place_again(Scene& scene, const GltfPlacement& placement, const glm::mat4& transform);

}  // namespace octrace
