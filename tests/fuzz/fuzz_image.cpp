// Fuzz target: bytes -> the image readers of `octrace compare` and `merge`
// and of environment maps (decode_image as .png, .pfm, .exr and .hdr: each
// reader rejects the others' files at their first bytes, so one corpus
// serves all four). A broken file
// must end in InputError; any other exception, a crash, a hang, a leak or
// undefined behaviour is a finding.
// Built for libFuzzer by tools/fuzz.sh, and replayed over its corpus
// (tests/fuzz/corpus/image/) by the fuzz_replay_image test.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors.h"
#include "io/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (const char* name : {"fuzz.png", "fuzz.pfm", "fuzz.exr", "fuzz.hdr"}) {
    try {
      octrace::decode_image(bytes, name);
    } catch (const octrace::InputError&) {
    }
  }
  return 0;
}
