// Fuzz target: bytes -> the JSON scene loader (parse_scene_json). A broken
// scene must end in InputError (SettingError is one); any other exception,
// a crash, a hang, a leak or undefined behaviour is a finding.
// Built for libFuzzer by tools/fuzz.sh, and replayed over its corpus
// (tests/fuzz/corpus/scene_json/) by the fuzz_replay_scene_json test.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    // Mesh files are looked for beside "fuzz.json", i.e. in the current
    // folder, where tools/fuzz.sh puts none.
    octrace::parse_scene_json(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const octrace::InputError&) {
  }
  return 0;
}
