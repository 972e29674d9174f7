// Errors the library throws. The front end catches them once, prints the message
// as one line, and exits 2 for bad input and 1 for a runtime failure.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace octrace {

// Something the user gave us is wrong: a scene file, an image path, a setting.
// The message names the input ("scene.json: spheres[12].radius: must be > 0").
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A bad value of one setting of the library's API (a field of RenderSettings,
// the device selection, a generator parameter). `setting` is the library's own
// name for it ("spp", "octree.leaf_size", "device") and the message starts
// with that name ("spp: must be >= 1, got 0"), never with a CLI flag: a front
// end that knows the setting by another name (app/ maps it to its flag)
// replaces that prefix.
struct SettingError : InputError {
  SettingError(std::string name, const std::string& rest) : InputError(name + rest), setting(std::move(name)) {}
  std::string setting;
};

// The scene is too large for the device: its memory, or a buffer where the
// scene cannot be split. The message names what does not fit and the limit;
// a front end that loaded the scene from a file puts the file's name first.
struct SceneSizeError : InputError {
  using InputError::InputError;
};

// The input was fine but the machine could not do it: no device, device lost,
// out of memory, an I/O failure while writing.
struct RuntimeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace octrace
