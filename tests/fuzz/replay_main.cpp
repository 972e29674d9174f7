// Replays a fuzz target's corpus without libFuzzer: linked with one target
// (fuzz_*.cpp), it feeds every file under the folders given to
// LLVMFuzzerTestOneInput, so the regular build checks in CI that no input of
// the corpus (seeds and past findings) crashes or throws anything but
// InputError. Run by the fuzz_replay_* tests (label "fuzz").
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "io/file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i)
    for (const auto& entry : std::filesystem::recursive_directory_iterator(argv[i]))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "replay: no corpus files found\n");
    return 1;
  }
  for (const auto& file : files) {
    // Named before it runs, so that a crash is attributed to its input.
    std::fprintf(stderr, "replay: %s\n", file.c_str());
    const std::string bytes = octrace::read_file(file.string());
    try {
      LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "replay: FAILED: %s: uncaught exception: %s\n", file.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "replay: %zu inputs, none crashed or threw anything but InputError\n", files.size());
  return 0;
}
