// Fuzz target: bytes -> the glTF loader (parse_gltf_scene: tinygltf, then
// octrace's checks, meshes, materials, textures, camera), as .glb or .gltf by
// the bytes' magic. A broken file must end in InputError; any other
// exception, a crash, a hang, a leak or undefined behaviour is a finding.
// Built for libFuzzer by tools/fuzz.sh, and replayed over its corpus
// (tests/fuzz/corpus/gltf/) by the fuzz_replay_gltf test.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "scene/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  octrace::GltfOptions opts;
  opts.warn = nullptr;  // warnings are not findings, and printing them slows the run
  try {
    octrace::parse_gltf_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.gltf", opts);
  } catch (const octrace::InputError&) {
  }
  return 0;
}
